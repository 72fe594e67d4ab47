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

/// The non-zero basis functions of span `k` at `t` and their derivatives up to order `n`:
/// `out[r][j]` is the `r`-th derivative of `N_{k-p+j}` (The NURBS Book, algorithm A2.3).
pub(crate) fn basis_derivatives(p: usize, knots: &[f64], k: usize, t: f64, n: usize) -> Vec<Vec<f64>> {
    let mut ndu = vec![vec![0.0; p + 1]; p + 1];
    let (mut left, mut right) = (vec![0.0; p + 1], vec![0.0; p + 1]);
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[k + 1 - j];
        right[j] = knots[k + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            // Lower triangle: knot differences; upper: basis functions.
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let mut out = vec![vec![0.0; p + 1]; n + 1];
    for j in 0..=p {
        out[0][j] = ndu[j][p];
    }
    let mut a = [vec![0.0; p + 1], vec![0.0; p + 1]];
    for r in 0..=p {
        let (mut s1, mut s2) = (0, 1);
        a[0][0] = 1.0;
        for order in 1..=n.min(p) {
            let mut d = 0.0;
            let (rk, pk) = (r as isize - order as isize, p - order);
            if r >= order {
                let rk = rk as usize;
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if (r as isize - 1) <= pk as isize {
                order - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                d += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][order] = -a[s1][order - 1] / ndu[pk + 1][r];
                d += a[s2][order] * ndu[r][pk];
            }
            out[order][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for (order, row) in out.iter_mut().enumerate().take(n.min(p) + 1).skip(1) {
        for value in row.iter_mut() {
            *value *= factor;
        }
        factor *= (p - order) as f64;
    }
    out
}

/// A surface point with its first and second partial derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceJet {
    /// The point.
    pub point: DVec3,
    /// d/du.
    pub du: DVec3,
    /// d/dv.
    pub dv: DVec3,
    /// d²/du².
    pub duu: DVec3,
    /// d²/du dv.
    pub duv: DVec3,
    /// d²/dv².
    pub dvv: DVec3,
}

impl NurbsSurface {
    /// The point and its partial derivatives up to the second at `(u, v)` (clamped into the
    /// ranges): derivatives of the homogeneous surface from the basis functions'
    /// derivatives, then the quotient rule (The NURBS Book, algorithm A4.4). A derivative
    /// of order above the degree is zero.
    pub fn jet(&self, u: f64, v: f64) -> SurfaceJet {
        let [pu, pv] = self.degree;
        let nv = self.count[1];
        let (u0, u1) = self.range(Direction::U);
        let (v0, v1) = self.range(Direction::V);
        let (u, v) = (u.clamp(u0, u1), v.clamp(v0, v1));
        let (ku, kv) = (span(pu, &self.knots[0], u), span(pv, &self.knots[1], v));
        let bu = basis_derivatives(pu, &self.knots[0], ku, u, 2);
        let bv = basis_derivatives(pv, &self.knots[1], kv, v, 2);
        // h[a][b]: the homogeneous derivative of order a in u and b in v.
        let mut h = [[DVec4::ZERO; 3]; 3];
        for (a, row) in h.iter_mut().enumerate() {
            for (b, cell) in row.iter_mut().enumerate().take(3 - a) {
                let mut sum = DVec4::ZERO;
                for (i, nu_i) in bu[a].iter().enumerate() {
                    let row = &self.net[(ku - pu + i) * nv + kv - pv..][..=pv];
                    let line: DVec4 = row.iter().zip(&bv[b]).map(|(h, n)| *h * *n).sum();
                    sum += line * *nu_i;
                }
                *cell = sum;
            }
        }
        let w = |a: usize, b: usize| h[a][b].w;
        let p = |a: usize, b: usize| h[a][b].truncate();
        let s = p(0, 0) / w(0, 0);
        let du = (p(1, 0) - s * w(1, 0)) / w(0, 0);
        let dv = (p(0, 1) - s * w(0, 1)) / w(0, 0);
        let duu = (p(2, 0) - 2.0 * du * w(1, 0) - s * w(2, 0)) / w(0, 0);
        let dvv = (p(0, 2) - 2.0 * dv * w(0, 1) - s * w(0, 2)) / w(0, 0);
        let duv = (p(1, 1) - du * w(0, 1) - dv * w(1, 0) - s * w(1, 1)) / w(0, 0);
        SurfaceJet {
            point: s,
            du,
            dv,
            duu,
            duv,
            dvv,
        }
    }
}

impl NurbsSurface {
    /// The surface under the affine map `x -> m x + t` (exact: a NURBS surface is affinely
    /// invariant, so mapping the control points maps every point).
    pub fn mapped(&self, m: glam::DMat3, t: DVec3) -> Self {
        let net = self
            .net
            .iter()
            .map(|h| ((m * (h.truncate() / h.w) + t) * h.w).extend(h.w))
            .collect();
        Self { net, ..self.clone() }
    }

    /// The surface sampled on an `nu x nv` grid of parameters, uniform over both ranges:
    /// positions row-major (`a * nv + b`, `a` along `u`) and two triangles per cell.
    pub fn grid(&self, nu: usize, nv: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let (nu, nv) = (nu.max(2), nv.max(2));
        let (u0, u1) = self.range(Direction::U);
        let (v0, v1) = self.range(Direction::V);
        let at = |k: usize, n: usize, lo: f64, hi: f64| lo + (hi - lo) * k as f64 / (n - 1) as f64;
        let positions = (0..nu)
            .flat_map(|a| (0..nv).map(move |b| (a, b)))
            .map(|(a, b)| self.point(at(a, nu, u0, u1), at(b, nv, v0, v1)))
            .collect();
        let mut triangles = Vec::with_capacity(2 * (nu - 1) * (nv - 1));
        for a in 0..nu - 1 {
            for b in 0..nv - 1 {
                let k = (a * nv + b) as u32;
                let (right, down) = (k + 1, k + nv as u32);
                triangles.push([k, down, right]);
                triangles.push([right, down, down + 1]);
            }
        }
        (positions, triangles)
    }
}
