//! Interpolating cubic splines of one variable, in the moment (second-derivative) form.
//!
//! On the interval `[x_i, x_{i+1}]` of width `h_i` the spline is
//!
//! ```text
//! S(t) = M_i (x_{i+1} - t)^3 / (6 h_i) + M_{i+1} (t - x_i)^3 / (6 h_i)
//!      + (y_i / h_i - M_i h_i / 6) (x_{i+1} - t) + (y_{i+1} / h_i - M_{i+1} h_i / 6) (t - x_i)
//! ```
//!
//! where the moments `M_i = S''(x_i)` solve the tridiagonal system
//! `h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (d_i - d_{i-1})`, `d_i` the
//! divided difference of interval `i`, closed by the end condition ([`EndCondition`]).
//! The same spline as scipy's `CubicSpline` with `bc_type` `"natural"`, `((1, s0), (1, sn))`
//! or `"periodic"`; the tests check that against a committed scipy fixture.

use thiserror::Error;

/// How the spline ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EndCondition {
    /// Zero second derivative at both ends.
    Natural,
    /// Given first derivatives at the first and last knot.
    Clamped {
        /// `S'(x_0)`.
        start_slope: f64,
        /// `S'(x_n)`.
        end_slope: f64,
    },
    /// `S`, `S'` and `S''` agree at both ends; the first and last values must be equal.
    /// Evaluation wraps the parameter into `[x_0, x_n)`.
    Periodic,
}

/// Why a spline could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SplineError {
    /// Knots and values differ in length.
    #[error("{knots} knots but {values} values")]
    LengthMismatch {
        /// Number of knots.
        knots: usize,
        /// Number of values.
        values: usize,
    },
    /// Too few knots for the end condition.
    #[error("a {kind} spline needs at least {needed} knots, got {got}")]
    TooFewKnots {
        /// End condition name.
        kind: &'static str,
        /// Minimum.
        needed: usize,
        /// Given.
        got: usize,
    },
    /// A knot or value is NaN or infinite.
    #[error("knot {index} is not finite (x = {x}, y = {y})")]
    NotFinite {
        /// Index of the offending knot.
        index: usize,
        /// Its abscissa.
        x: f64,
        /// Its value.
        y: f64,
    },
    /// Knots must increase strictly.
    #[error("knots must increase strictly: x[{index}] = {next} follows {prev}")]
    NotIncreasing {
        /// Index of the knot that does not increase.
        index: usize,
        /// The previous knot.
        prev: f64,
        /// The knot at `index`.
        next: f64,
    },
    /// Periodic splines need equal first and last values.
    #[error("a periodic spline needs y[0] == y[n] (got {first} and {last})")]
    NotPeriodic {
        /// First value.
        first: f64,
        /// Last value.
        last: f64,
    },
    /// A clamped end slope is NaN or infinite.
    #[error("end slopes must be finite (got {start} and {end})")]
    SlopeNotFinite {
        /// Start slope.
        start: f64,
        /// End slope.
        end: f64,
    },
}

/// An interpolating cubic spline `S(t)` through `(x_i, y_i)`.
#[derive(Clone, Debug, PartialEq)]
pub struct CubicSpline {
    x: Vec<f64>,
    y: Vec<f64>,
    /// Second derivatives at the knots.
    moments: Vec<f64>,
    periodic: bool,
}

impl CubicSpline {
    /// Builds the spline through `(x[i], y[i])` with the given ends.
    ///
    /// # Failures
    /// See [`SplineError`]: mismatched lengths, fewer than 2 knots (3 for periodic),
    /// non-finite input, knots not strictly increasing, periodic data whose ends differ.
    pub fn try_new(x: &[f64], y: &[f64], end: EndCondition) -> Result<Self, SplineError> {
        if x.len() != y.len() {
            return Err(SplineError::LengthMismatch {
                knots: x.len(),
                values: y.len(),
            });
        }
        let (kind, needed) = match end {
            EndCondition::Periodic => ("periodic", 3),
            EndCondition::Natural => ("natural", 2),
            EndCondition::Clamped { .. } => ("clamped", 2),
        };
        if x.len() < needed {
            return Err(SplineError::TooFewKnots {
                kind,
                needed,
                got: x.len(),
            });
        }
        for (index, (&xi, &yi)) in x.iter().zip(y).enumerate() {
            if !xi.is_finite() || !yi.is_finite() {
                return Err(SplineError::NotFinite { index, x: xi, y: yi });
            }
        }
        for (index, w) in x.windows(2).enumerate() {
            if let [prev, next] = *w
                && next <= prev
            {
                return Err(SplineError::NotIncreasing {
                    index: index + 1,
                    prev,
                    next,
                });
            }
        }
        let n = x.len() - 1; // number of intervals
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let d: Vec<f64> = (0..n).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
        let moments = match end {
            EndCondition::Natural => {
                let mut m = vec![0.0; n + 1];
                if n >= 2 {
                    let inner = solve_interior(&h, &d, 0.0, 0.0);
                    m[1..n].copy_from_slice(&inner);
                }
                m
            }
            EndCondition::Clamped { start_slope, end_slope } => {
                if !start_slope.is_finite() || !end_slope.is_finite() {
                    return Err(SplineError::SlopeNotFinite {
                        start: start_slope,
                        end: end_slope,
                    });
                }
                solve_clamped(&h, &d, start_slope, end_slope)
            }
            EndCondition::Periodic => {
                let (first, last) = (y[0], y[n]);
                // Exact equality is what scipy asks for; a relative slack of a few ulps
                // keeps data that went through one extra rounding usable.
                if (first - last).abs() > 4.0 * f64::EPSILON * first.abs().max(last.abs()).max(f64::MIN_POSITIVE) {
                    return Err(SplineError::NotPeriodic { first, last });
                }
                solve_periodic(&h, &d)
            }
        };
        Ok(Self {
            x: x.to_vec(),
            y: y.to_vec(),
            moments,
            periodic: end == EndCondition::Periodic,
        })
    }

    /// The knots.
    pub fn knots(&self) -> &[f64] {
        &self.x
    }

    /// The interpolated values at the knots.
    pub fn values(&self) -> &[f64] {
        &self.y
    }

    /// `S(t)` (the data's units). Outside the knot range the end polynomials are extended
    /// (periodic: wrapped).
    pub fn sample(&self, t: f64) -> f64 {
        self.eval(t).0
    }

    /// `S'(t)` (data units per unit of `t`).
    pub fn derivative(&self, t: f64) -> f64 {
        self.eval(t).1
    }

    /// `S''(t)` (data units per unit of `t` squared).
    pub fn second_derivative(&self, t: f64) -> f64 {
        self.eval(t).2
    }

    /// `(S(t), S'(t), S''(t))` in one interval look-up.
    pub fn eval(&self, t: f64) -> (f64, f64, f64) {
        let n = self.x.len() - 1;
        let (x0, xn) = (self.x[0], self.x[n]);
        let t = if self.periodic {
            let period = xn - x0;
            let w = x0 + (t - x0).rem_euclid(period);
            if w >= xn { x0 } else { w }
        } else {
            t
        };
        // Interval i with x_i <= t < x_{i+1}, clamped to the end intervals for extrapolation.
        let i = self.x.partition_point(|&k| k <= t).saturating_sub(1).min(n - 1);
        let (xa, xb) = (self.x[i], self.x[i + 1]);
        let (ya, yb) = (self.y[i], self.y[i + 1]);
        let (ma, mb) = (self.moments[i], self.moments[i + 1]);
        let h = xb - xa;
        let (a, b) = (xb - t, t - xa);
        let value = ma * a * a * a / (6.0 * h)
            + mb * b * b * b / (6.0 * h)
            + (ya / h - ma * h / 6.0) * a
            + (yb / h - mb * h / 6.0) * b;
        let slope = -ma * a * a / (2.0 * h) + mb * b * b / (2.0 * h) + (yb - ya) / h - (mb - ma) * h / 6.0;
        let curvature = (ma * a + mb * b) / h;
        (value, slope, curvature)
    }
}

/// Interior moments `M_1..M_{n-1}` with the end moments `m0`, `mn` known.
fn solve_interior(h: &[f64], d: &[f64], m0: f64, mn: f64) -> Vec<f64> {
    let n = h.len();
    let k = n - 1;
    let mut sub = vec![0.0; k];
    let mut diag = vec![0.0; k];
    let mut sup = vec![0.0; k];
    let mut rhs = vec![0.0; k];
    for r in 0..k {
        let i = r + 1;
        sub[r] = h[i - 1];
        diag[r] = 2.0 * (h[i - 1] + h[i]);
        sup[r] = h[i];
        rhs[r] = 6.0 * (d[i] - d[i - 1]);
    }
    rhs[0] -= h[0] * m0;
    rhs[k - 1] -= h[n - 1] * mn;
    solve_tridiagonal(&sub, &diag, &sup, &mut rhs);
    rhs
}

/// All moments for clamped ends (first derivatives given).
fn solve_clamped(h: &[f64], d: &[f64], s0: f64, sn: f64) -> Vec<f64> {
    let n = h.len();
    let size = n + 1;
    let mut sub = vec![0.0; size];
    let mut diag = vec![0.0; size];
    let mut sup = vec![0.0; size];
    let mut rhs = vec![0.0; size];
    diag[0] = 2.0 * h[0];
    sup[0] = h[0];
    rhs[0] = 6.0 * (d[0] - s0);
    for i in 1..n {
        sub[i] = h[i - 1];
        diag[i] = 2.0 * (h[i - 1] + h[i]);
        sup[i] = h[i];
        rhs[i] = 6.0 * (d[i] - d[i - 1]);
    }
    sub[n] = h[n - 1];
    diag[n] = 2.0 * h[n - 1];
    rhs[n] = 6.0 * (sn - d[n - 1]);
    solve_tridiagonal(&sub, &diag, &sup, &mut rhs);
    rhs
}

/// Moments for periodic ends: a cyclic tridiagonal system in `M_0..M_{n-1}` (`M_n = M_0`),
/// solved by the Sherman-Morrison correction of the Thomas algorithm.
fn solve_periodic(h: &[f64], d: &[f64]) -> Vec<f64> {
    let n = h.len();
    // Row i couples M_{i-1}, M_i, M_{i+1} (indices mod n); the interval before knot 0 is h_{n-1}.
    let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
    let mut sub = vec![0.0; n];
    let mut diag = vec![0.0; n];
    let mut sup = vec![0.0; n];
    let mut rhs = vec![0.0; n];
    for i in 0..n {
        let hp = h[prev(i)];
        sub[i] = hp;
        diag[i] = 2.0 * (hp + h[i]);
        sup[i] = h[i];
        rhs[i] = 6.0 * (d[i] - d[prev(i)]);
    }
    let mut m = if n == 2 {
        // Both off-diagonal couplings land on the same neighbour: a plain 2x2 system.
        let (a, b) = (diag[0], sup[0] + sub[0]);
        let (c, e) = (sup[1] + sub[1], diag[1]);
        let det = a * e - b * c;
        vec![(rhs[0] * e - b * rhs[1]) / det, (a * rhs[1] - c * rhs[0]) / det]
    } else {
        // A = T + u v^T with corner entries alpha = A[0][n-1] = sub[0], beta = A[n-1][0] = sup[n-1].
        let alpha = sub[0];
        let beta = sup[n - 1];
        let gamma = -diag[0];
        let mut dmod = diag.clone();
        dmod[0] -= gamma;
        dmod[n - 1] -= alpha * beta / gamma;
        let mut sub_t = sub.clone();
        let mut sup_t = sup.clone();
        sub_t[0] = 0.0;
        sup_t[n - 1] = 0.0;
        let mut x = rhs.clone();
        solve_tridiagonal(&sub_t, &dmod, &sup_t, &mut x);
        let mut u = vec![0.0; n];
        u[0] = gamma;
        u[n - 1] = beta;
        solve_tridiagonal(&sub_t, &dmod, &sup_t, &mut u);
        let v0 = 1.0;
        let vn = alpha / gamma;
        let factor = (v0 * x[0] + vn * x[n - 1]) / (1.0 + v0 * u[0] + vn * u[n - 1]);
        for (xi, ui) in x.iter_mut().zip(&u) {
            *xi -= factor * ui;
        }
        x
    };
    m.push(m[0]);
    m
}

/// Thomas algorithm; `rhs` is overwritten with the solution. The systems built here are
/// strictly diagonally dominant (all `h > 0`), so no pivoting is needed.
fn solve_tridiagonal(sub: &[f64], diag: &[f64], sup: &[f64], rhs: &mut [f64]) {
    let n = diag.len();
    let mut c = vec![0.0; n];
    let mut beta = diag[0];
    c[0] = sup[0] / beta;
    rhs[0] /= beta;
    for i in 1..n {
        beta = diag[i] - sub[i] * c[i - 1];
        c[i] = sup[i] / beta;
        rhs[i] = (rhs[i] - sub[i] * rhs[i - 1]) / beta;
    }
    for i in (0..n - 1).rev() {
        rhs[i] -= c[i] * rhs[i + 1];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn natural_spline_reproduces_a_line() {
        let x = [0.0, 0.3, 1.1, 2.0];
        let y: Vec<f64> = x.iter().map(|t| 2.0 * t - 1.0).collect();
        let s = CubicSpline::try_new(&x, &y, EndCondition::Natural).unwrap();
        for t in [0.0, 0.5, 1.7, 2.0] {
            assert!((s.sample(t) - (2.0 * t - 1.0)).abs() < 1e-14);
            assert!((s.derivative(t) - 2.0).abs() < 1e-13);
        }
    }

    #[test]
    fn clamped_spline_reproduces_a_cubic() {
        let f = |t: f64| t * t * t - 2.0 * t * t + 0.5;
        let df = |t: f64| 3.0 * t * t - 4.0 * t;
        let x = [-1.0, -0.2, 0.4, 1.5, 2.0];
        let y: Vec<f64> = x.iter().map(|&t| f(t)).collect();
        let s = CubicSpline::try_new(
            &x,
            &y,
            EndCondition::Clamped {
                start_slope: df(-1.0),
                end_slope: df(2.0),
            },
        )
        .unwrap();
        for t in [-1.0, -0.7, 0.0, 1.0, 1.9] {
            assert!((s.sample(t) - f(t)).abs() < 1e-12, "{t}");
            assert!((s.second_derivative(t) - (6.0 * t - 4.0)).abs() < 1e-11);
        }
    }

    #[test]
    fn periodic_spline_is_periodic_in_value_slope_and_curvature() {
        let x: Vec<f64> = (0..=7).map(|i| f64::from(i) * 0.9).collect();
        let mut y: Vec<f64> = x.iter().map(|t| (t * 1.3).sin() + 0.2 * t).collect();
        y[7] = y[0];
        let s = CubicSpline::try_new(&x, &y, EndCondition::Periodic).unwrap();
        let (a, b) = (s.eval(0.0), s.eval(x[7] - 1e-12));
        assert!((a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9 && (a.2 - b.2).abs() < 1e-8);
        assert!((s.sample(0.4) - s.sample(0.4 + 6.3)).abs() < 1e-12);
    }

    #[test]
    fn bad_input_is_named() {
        assert_eq!(
            CubicSpline::try_new(&[0.0, 1.0, 1.0], &[0.0; 3], EndCondition::Natural),
            Err(SplineError::NotIncreasing {
                index: 2,
                prev: 1.0,
                next: 1.0
            })
        );
        assert!(matches!(
            CubicSpline::try_new(&[0.0, f64::NAN], &[0.0; 2], EndCondition::Natural),
            Err(SplineError::NotFinite { index: 1, .. })
        ));
        assert!(matches!(
            CubicSpline::try_new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 2.0], EndCondition::Periodic),
            Err(SplineError::NotPeriodic { .. })
        ));
    }
}
