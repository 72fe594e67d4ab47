//! Open 3D curves with local support: cubic Hermite spans on accumulated chord length, the
//! tangent at each point the derivative there of the parabola through it and its two
//! neighbours (Bessel tangents, de Boor, *A Practical Guide to Splines*, ch. IV).
//!
//! A span from point `k` to `k + 1` depends on points `k - 1 ..= k + 2` only (and on a given
//! end tangent at the curve's first or last span), so moving one point changes at most the
//! four spans about it, and the others keep their samples bit for bit: [`LocalSpline3::span_sample`]
//! reads nothing else. The curve is `C1` (the interpolating spline of [`super::ChordSpline3`]
//! is `C2`, but every span depends on every point).
//!
//! With `h_k = |P_{k+1} - P_k|` and `d_k = (P_{k+1} - P_k) / h_k`:
//!
//! ```text
//! interior  m_k = (h_k d_{k-1} + h_{k-1} d_k) / (h_{k-1} + h_k)
//! free ends m_0 = ((2 h_0 + h_1) d_0 - h_0 d_1) / (h_0 + h_1)           (and mirrored)
//! span k    P(t) = H00(t) P_k + H10(t) h_k m_k + H01(t) P_{k+1} + H11(t) h_k m_{k+1}
//! ```
//!
//! `m` is `dP/dl` at the points (close to unit length); a given end tangent is normalized,
//! as for [`super::ChordSpline3`].

use glam::DVec3;

use super::spline::SplineError;

/// An open curve through points, cubic Hermite spans with local support.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalSpline3 {
    points: Vec<DVec3>,
    /// `dP/dl` at each point.
    tangents: Vec<DVec3>,
    /// Accumulated chord length at each point.
    knots: Vec<f64>,
}

/// The Hermite basis at `t` and its derivative: `[H00, H10, H01, H11]`.
fn basis(t: f64) -> ([f64; 4], [f64; 4]) {
    let (t2, t3) = (t * t, t * t * t);
    (
        [
            2.0 * t3 - 3.0 * t2 + 1.0,
            t3 - 2.0 * t2 + t,
            3.0 * t2 - 2.0 * t3,
            t3 - t2,
        ],
        [
            6.0 * t2 - 6.0 * t,
            3.0 * t2 - 4.0 * t + 1.0,
            6.0 * t - 6.0 * t2,
            3.0 * t2 - 2.0 * t,
        ],
    )
}

impl LocalSpline3 {
    /// Builds the curve through `points`, with the end tangents `start` and `end` where
    /// given (free ends otherwise).
    ///
    /// # Failures
    /// Fewer than 2 points ([`SplineError::TooFewKnots`]), a non-finite coordinate or end
    /// tangent ([`SplineError::NotFinite`], [`SplineError::SlopeNotFinite`]), or two
    /// consecutive points that coincide ([`SplineError::NotIncreasing`], with the index of
    /// the second one).
    pub fn try_new(points: &[DVec3], start: Option<DVec3>, end: Option<DVec3>) -> Result<Self, SplineError> {
        let n = points.len();
        if n < 2 {
            return Err(SplineError::TooFewKnots {
                kind: "local",
                needed: 2,
                got: n,
            });
        }
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            let p = points[index];
            return Err(SplineError::NotFinite { index, x: p.x, y: p.y });
        }
        for t in [start, end].into_iter().flatten() {
            if !t.is_finite() {
                return Err(SplineError::SlopeNotFinite {
                    start: start.map_or(0.0, |s| s.length()),
                    end: end.map_or(0.0, |e| e.length()),
                });
            }
        }
        let h: Vec<f64> = points.windows(2).map(|w| w[0].distance(w[1])).collect();
        let mut knots = Vec::with_capacity(n);
        let mut acc = 0.0;
        knots.push(acc);
        for (i, &hi) in h.iter().enumerate() {
            let next = acc + hi;
            if next <= acc {
                return Err(SplineError::NotIncreasing {
                    index: i + 1,
                    prev: acc,
                    next,
                });
            }
            acc = next;
            knots.push(acc);
        }
        let d = |k: usize| (points[k + 1] - points[k]) / h[k];
        let last = n - 1;
        let tangents = (0..n)
            .map(|k| match k {
                0 => match start {
                    Some(s) => s.normalize_or_zero(),
                    None if n == 2 => d(0),
                    None => ((2.0 * h[0] + h[1]) * d(0) - h[0] * d(1)) / (h[0] + h[1]),
                },
                k if k == last => match end {
                    Some(e) => e.normalize_or_zero(),
                    None if n == 2 => d(0),
                    None => {
                        let (h0, h1) = (h[k - 2], h[k - 1]);
                        ((2.0 * h1 + h0) * d(k - 1) - h1 * d(k - 2)) / (h0 + h1)
                    }
                },
                k => (h[k] * d(k - 1) + h[k - 1] * d(k)) / (h[k - 1] + h[k]),
            })
            .collect();
        Ok(Self {
            points: points.to_vec(),
            tangents,
            knots,
        })
    }

    /// Total chord length (the parameter range is `[0, length]`).
    pub fn length(&self) -> f64 {
        self.knots[self.knots.len() - 1]
    }

    /// The parameters of the points (accumulated chord lengths).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The point of span `k` (from point `k` to `k + 1`) at `t` in `[0, 1]`: computed from
    /// that span's two points and tangents alone.
    pub fn span_sample(&self, k: usize, t: f64) -> DVec3 {
        let (b, _) = basis(t);
        let (p0, p1) = (self.points[k], self.points[k + 1]);
        // The chord from the points, not `knots[k + 1] - knots[k]`: the knots accumulate
        // every chord below, so their difference would change in its last bits with them.
        let h = p0.distance(p1);
        b[0] * p0 + b[1] * h * self.tangents[k] + b[2] * p1 + b[3] * h * self.tangents[k + 1]
    }

    /// The span holding `l` and where in it, `t` in `[0, 1]` (clamped to the curve).
    fn locate(&self, l: f64) -> (usize, f64) {
        let spans = self.knots.len() - 1;
        let k = self.knots.partition_point(|&x| x <= l).clamp(1, spans) - 1;
        let (a, b) = (self.knots[k], self.knots[k + 1]);
        (k, ((l - a) / (b - a)).clamp(0.0, 1.0))
    }

    /// `P(l)`, at accumulated chord length `l` (m in drape).
    pub fn sample(&self, l: f64) -> DVec3 {
        let (k, t) = self.locate(l);
        self.span_sample(k, t)
    }

    /// `dP/dl`, unitless (close to unit length).
    pub fn derivative(&self, l: f64) -> DVec3 {
        let (k, t) = self.locate(l);
        let (_, db) = basis(t);
        let (p0, p1) = (self.points[k], self.points[k + 1]);
        let h = p0.distance(p1);
        (db[0] * p0 + db[2] * p1) / h + db[1] * self.tangents[k] + db[3] * self.tangents[k + 1]
    }

    /// Each span split into `k` equal parameter steps: `k * spans + 1` points.
    pub fn subdivide(&self, k: usize) -> Vec<DVec3> {
        let k = k.max(1);
        let spans = self.points.len() - 1;
        let mut out: Vec<DVec3> = (0..spans)
            .flat_map(|i| (0..k).map(move |s| (i, s as f64 / k as f64)))
            .map(|(i, t)| self.span_sample(i, t))
            .collect();
        out.push(self.points[spans]);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wavy(n: usize) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let y = 0.1 * i as f64 + 0.013 * (i * i % 5) as f64;
                DVec3::new(0.2 * (1.3 * y).sin(), y, 0.1 * (2.1 * y).cos())
            })
            .collect()
    }

    #[test]
    fn passes_through_its_points_and_lies_on_a_line_through_collinear_ones() {
        let pts = wavy(7);
        let c = LocalSpline3::try_new(&pts, None, None).unwrap();
        for (k, p) in pts.iter().enumerate() {
            assert!(c.sample(c.knots()[k]).distance(*p) < 1e-15, "point {k}");
        }
        // Unevenly spaced points on a line: the curve is the line, at l from the start
        // (every chord is along it, so every tangent is the unit direction).
        let dir = DVec3::new(0.3, 0.8, -0.2).normalize();
        let at = [0.0, 0.1, 0.35, 0.4, 0.9];
        let line: Vec<DVec3> = at.iter().map(|&s| DVec3::new(1.0, 2.0, 3.0) + dir * s).collect();
        let c = LocalSpline3::try_new(&line, None, None).unwrap();
        for i in 0..=90 {
            let l = 0.01 * i as f64;
            assert!(
                c.sample(l).distance(DVec3::new(1.0, 2.0, 3.0) + dir * l) < 1e-14,
                "l = {l}"
            );
        }
    }

    #[test]
    fn moving_a_point_keeps_every_span_but_the_four_about_it_bit_for_bit() {
        let pts = wavy(9);
        let c = LocalSpline3::try_new(&pts, Some(DVec3::Y), None).unwrap();
        for j in 0..pts.len() {
            let mut moved = pts.clone();
            moved[j] += DVec3::new(0.01, -0.004, 0.02);
            let m = LocalSpline3::try_new(&moved, Some(DVec3::Y), None).unwrap();
            for k in 0..pts.len() - 1 {
                let same = (0..=8).all(|s| c.span_sample(k, s as f64 / 8.0) == m.span_sample(k, s as f64 / 8.0));
                let near = k + 2 >= j && k <= j + 1;
                assert_eq!(same, !near, "span {k} with point {j} moved");
            }
        }
    }

    #[test]
    fn the_tangent_is_continuous_and_matches_finite_differences() {
        let pts = wavy(6);
        let c = LocalSpline3::try_new(&pts, None, Some(DVec3::new(0.1, 1.0, 0.0))).unwrap();
        let eps = 1e-6;
        for &l in &c.knots()[1..c.knots().len() - 1] {
            let left = (c.sample(l) - c.sample(l - eps)) / eps;
            let right = (c.sample(l + eps) - c.sample(l)) / eps;
            assert!(left.distance(right) < 1e-4, "kink at l = {l}: {left} against {right}");
            assert!(c.derivative(l).distance(0.5 * (left + right)) < 1e-5);
        }
        let end = c.derivative(c.length());
        assert!(end.distance(DVec3::new(0.1, 1.0, 0.0).normalize()) < 1e-12);
        // A circle: the Bessel tangents' error is third order in the spacing.
        let circle: Vec<DVec3> = (0..13)
            .map(|i| {
                let a = 0.5 * i as f64 / 12.0 * std::f64::consts::PI;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let c = LocalSpline3::try_new(&circle, Some(DVec3::Y), Some(-DVec3::X)).unwrap();
        for p in c.subdivide(10) {
            assert!((p.length() - 1.0).abs() < 2e-5, "{p}: radius {}", p.length());
        }
    }

    #[test]
    fn bad_points_are_refused() {
        let err = |pts: &[DVec3]| LocalSpline3::try_new(pts, None, None).unwrap_err();
        assert!(matches!(err(&[DVec3::ZERO]), SplineError::TooFewKnots { got: 1, .. }));
        assert!(matches!(
            err(&[DVec3::ZERO, DVec3::X, DVec3::X]),
            SplineError::NotIncreasing { index: 2, .. }
        ));
        assert!(matches!(
            err(&[DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0)]),
            SplineError::NotFinite { index: 1, .. }
        ));
        assert!(matches!(
            LocalSpline3::try_new(&[DVec3::ZERO, DVec3::X], Some(DVec3::INFINITY), None),
            Err(SplineError::SlopeNotFinite { .. })
        ));
    }
}
