//! A rational B-spline surface: degrees, clamped knot vectors in `u` and `v`, and a net of
//! weighted control points, validated on construction; evaluated by de Boor's algorithm on
//! homogeneous points (rows in `v`, then the column in `u`).

use glam::{DVec3, DVec4};
use thiserror::Error;

/// A parameter direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// The first parameter (rows of the control net).
    U,
    /// The second parameter (columns).
    V,
}

impl Direction {
    /// 0 for `u`, 1 for `v`.
    pub fn index(self) -> usize {
        match self {
            Self::U => 0,
            Self::V => 1,
        }
    }
}

impl std::fmt::Display for Direction {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::U => "u",
            Self::V => "v",
        })
    }
}

/// Why a surface is not valid.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum NurbsError {
    /// Degree 0.
    #[error("degree in {0} must be at least 1")]
    Degree(Direction),
    /// Too few control points for the degree.
    #[error("{count} control points in {dir} are too few for degree {degree} (at least {need})")]
    TooFewPoints {
        /// Direction.
        dir: Direction,
        /// Points given.
        count: usize,
        /// Degree.
        degree: usize,
        /// Points needed.
        need: usize,
    },
    /// The net does not hold count_u x count_v points or weights.
    #[error("the net has {got} {what}, expected {count_u} x {count_v} = {expected}")]
    NetSize {
        /// Points or weights.
        what: &'static str,
        /// Given.
        got: usize,
        /// Points in u.
        count_u: usize,
        /// Points in v.
        count_v: usize,
        /// Expected.
        expected: usize,
    },
    /// The knot vector has the wrong length.
    #[error("knot vector in {dir} has {got} knots, expected {expected} (points + degree + 1)")]
    KnotCount {
        /// Direction.
        dir: Direction,
        /// Given.
        got: usize,
        /// Expected.
        expected: usize,
    },
    /// A knot is not finite or decreases.
    #[error("knot vector in {dir}: knot {index} = {value} is not finite or is less than the one before")]
    KnotOrder {
        /// Direction.
        dir: Direction,
        /// Index.
        index: usize,
        /// Value.
        value: f64,
    },
    /// Not clamped (the first and last knots not repeated degree + 1 times), or an empty
    /// parameter range.
    #[error(
        "knot vector in {dir} must be clamped: its first and last knots repeated degree + 1 = {need} times, over a non-empty range"
    )]
    NotClamped {
        /// Direction.
        dir: Direction,
        /// Multiplicity needed.
        need: usize,
    },
    /// An interior knot repeated more than the degree.
    #[error("knot vector in {dir}: interior knot {value} is repeated {count} times, more than the degree {degree}")]
    Multiplicity {
        /// Direction.
        dir: Direction,
        /// The knot.
        value: f64,
        /// Its multiplicity.
        count: usize,
        /// Degree.
        degree: usize,
    },
    /// A control point or weight is not finite, or a weight is not positive.
    #[error("control point ({i}, {j}): {what}")]
    BadPoint {
        /// Row.
        i: usize,
        /// Column.
        j: usize,
        /// What is wrong.
        what: String,
    },
}

/// A rational B-spline surface on clamped knot vectors.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    degree: [usize; 2],
    knots: [Vec<f64>; 2],
    count: [usize; 2],
    /// Homogeneous control points `(w x, w y, w z, w)`, row-major: `i * count_v + j`.
    net: Vec<DVec4>,
}

fn check_knots(dir: Direction, degree: usize, count: usize, knots: &[f64]) -> Result<(), NurbsError> {
    if degree == 0 {
        return Err(NurbsError::Degree(dir));
    }
    if count < degree + 1 {
        return Err(NurbsError::TooFewPoints {
            dir,
            count,
            degree,
            need: degree + 1,
        });
    }
    if knots.len() != count + degree + 1 {
        return Err(NurbsError::KnotCount {
            dir,
            got: knots.len(),
            expected: count + degree + 1,
        });
    }
    for (index, &value) in knots.iter().enumerate() {
        if !value.is_finite() || (index > 0 && value < knots[index - 1]) {
            return Err(NurbsError::KnotOrder { dir, index, value });
        }
    }
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    let clamped = knots[..=degree].iter().all(|&k| k == first)
        && knots[knots.len() - degree - 1..].iter().all(|&k| k == last)
        && first < last;
    if !clamped {
        return Err(NurbsError::NotClamped { dir, need: degree + 1 });
    }
    let interior = &knots[degree + 1..knots.len() - degree - 1];
    for run in interior.chunk_by(|a, b| a == b) {
        if run.len() > degree {
            return Err(NurbsError::Multiplicity {
                dir,
                value: run[0],
                count: run.len(),
                degree,
            });
        }
    }
    Ok(())
}

/// The span `k` with `knots[k] <= t < knots[k + 1]` (the last non-empty span at the end of
/// the range; `t` is clamped into the range).
pub(crate) fn span(degree: usize, knots: &[f64], t: f64) -> usize {
    let n = knots.len() - degree - 1; // control points
    let t = t.clamp(knots[degree], knots[n]);
    if t >= knots[n] {
        return (degree..n).rev().find(|&k| knots[k] < knots[k + 1]).unwrap_or(degree);
    }
    // Largest k in [degree, n - 1] with knots[k] <= t.
    let upper = knots[degree..=n].partition_point(|&k| k <= t);
    (degree + upper - 1).min(n - 1)
}

/// De Boor's algorithm on homogeneous points `ctrl` (of the curve with `knots`) at `t`.
pub(crate) fn de_boor(degree: usize, knots: &[f64], ctrl: &[DVec4], t: f64) -> DVec4 {
    let k = span(degree, knots, t);
    let t = t.clamp(knots[degree], knots[ctrl.len()]);
    let mut d: Vec<DVec4> = (0..=degree).map(|j| ctrl[j + k - degree]).collect();
    for r in 1..=degree {
        for j in (r..=degree).rev() {
            let (lo, hi) = (knots[j + k - degree], knots[j + 1 + k - r]);
            let alpha = if hi > lo { (t - lo) / (hi - lo) } else { 0.0 };
            d[j] = d[j - 1] * (1.0 - alpha) + d[j] * alpha;
        }
    }
    d[degree]
}

impl NurbsSurface {
    /// A surface of degrees `degree` (u, v) on `knots` with `count[0] x count[1]` control
    /// `points` and `weights`, row-major (`i * count[1] + j`, `i` along `u`).
    pub fn new(
        degree: [usize; 2],
        knots: [Vec<f64>; 2],
        count: [usize; 2],
        points: &[DVec3],
        weights: &[f64],
    ) -> Result<Self, NurbsError> {
        check_knots(Direction::U, degree[0], count[0], &knots[0])?;
        check_knots(Direction::V, degree[1], count[1], &knots[1])?;
        let expected = count[0] * count[1];
        for (what, got) in [("points", points.len()), ("weights", weights.len())] {
            if got != expected {
                return Err(NurbsError::NetSize {
                    what,
                    got,
                    count_u: count[0],
                    count_v: count[1],
                    expected,
                });
            }
        }
        let mut net = Vec::with_capacity(expected);
        for (k, (p, &w)) in points.iter().zip(weights).enumerate() {
            let (i, j) = (k / count[1], k % count[1]);
            if !p.is_finite() {
                return Err(NurbsError::BadPoint {
                    i,
                    j,
                    what: format!("position {p} is not finite"),
                });
            }
            if !(w.is_finite() && w > 0.0) {
                return Err(NurbsError::BadPoint {
                    i,
                    j,
                    what: format!("weight {w} must be finite and positive"),
                });
            }
            net.push((*p * w).extend(w));
        }
        Ok(Self {
            degree,
            knots,
            count,
            net,
        })
    }

    /// A surface from parts already known to be valid (subdivision).
    pub(crate) fn from_parts(degree: [usize; 2], knots: [Vec<f64>; 2], count: [usize; 2], net: Vec<DVec4>) -> Self {
        Self {
            degree,
            knots,
            count,
            net,
        }
    }

    /// Degrees in u and v.
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// Knot vectors in u and v.
    pub fn knots(&self) -> &[Vec<f64>; 2] {
        &self.knots
    }

    /// Control points in u and v.
    pub fn count(&self) -> [usize; 2] {
        self.count
    }

    /// The homogeneous net `(w x, w y, w z, w)`, row-major.
    pub fn net(&self) -> &[DVec4] {
        &self.net
    }

    /// The control points (Euclidean), row-major.
    pub fn control_points(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.net.iter().map(|h| h.truncate() / h.w)
    }

    /// The parameter range in `dir`.
    pub fn range(&self, dir: Direction) -> (f64, f64) {
        let d = dir.index();
        let k = &self.knots[d];
        (k[self.degree[d]], k[self.count[d]])
    }

    /// The point at `(u, v)` (clamped into the parameter ranges).
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let [pu, pv] = self.degree;
        let [nu, nv] = self.count;
        let ku = span(pu, &self.knots[0], u);
        // Only the rows the u span needs.
        let column: Vec<DVec4> = (ku - pu..=ku)
            .map(|i| de_boor(pv, &self.knots[1], &self.net[i * nv..(i + 1) * nv], v))
            .collect();
        let mut full = vec![DVec4::ZERO; nu];
        full[ku - pu..=ku].copy_from_slice(&column);
        let h = de_boor(pu, &self.knots[0], &full, u);
        h.truncate() / h.w
    }
}
