//! Subdivision by knot insertion (Boehm's algorithm on homogeneous points): inserting a
//! knot leaves the surface unchanged; inserting it up to the degree splits the surface
//! there into two that together are exactly the original, each on its own part of the
//! parameter range. [`quarter`] splits at the Greville abscissae of the middle control
//! points in `u` and `v` (the parameters where those points "lie"), giving the four
//! sub-surfaces of one subdivision level.

use glam::DVec4;

use super::surface::{Direction, NurbsSurface, span};

/// Inserts `t` once into the curve of homogeneous points `ctrl` (degree `p`, `knots`):
/// the new knots and points.
fn insert_curve(p: usize, knots: &[f64], ctrl: &[DVec4], t: f64) -> (Vec<f64>, Vec<DVec4>) {
    let k = span(p, knots, t);
    let n = ctrl.len();
    let points = (0..=n)
        .map(|i| {
            if i + p <= k {
                ctrl[i]
            } else if i <= k {
                let a = (t - knots[i]) / (knots[i + p] - knots[i]);
                ctrl[i - 1] * (1.0 - a) + ctrl[i] * a
            } else {
                ctrl[i - 1]
            }
        })
        .collect();
    let mut new_knots = knots.to_vec();
    new_knots.insert(k + 1, t);
    (new_knots, points)
}

/// The lines of the net along `dir` (columns for `u`, rows for `v`), each a curve.
fn lines(s: &NurbsSurface, dir: Direction) -> Vec<Vec<DVec4>> {
    let [nu, nv] = s.count();
    let net = s.net();
    match dir {
        Direction::U => (0..nv).map(|j| (0..nu).map(|i| net[i * nv + j]).collect()).collect(),
        Direction::V => (0..nu).map(|i| net[i * nv..(i + 1) * nv].to_vec()).collect(),
    }
}

/// A surface from its lines along `dir` (the inverse of [`lines`]).
fn from_lines(s: &NurbsSurface, dir: Direction, knots: Vec<f64>, lines: &[Vec<DVec4>]) -> NurbsSurface {
    let mut all = s.knots().clone();
    all[dir.index()] = knots;
    let along = lines.first().map_or(0, Vec::len);
    let (count, net) = match dir {
        Direction::U => {
            let nv = lines.len();
            let net = (0..along).flat_map(|i| lines.iter().map(move |l| l[i])).collect();
            ([along, nv], net)
        }
        Direction::V => ([lines.len(), along], lines.concat()),
    };
    NurbsSurface::from_parts(s.degree(), all, count, net)
}

/// `s` with the knot `t` inserted once in `dir` (the same surface, one more line of control
/// points). `t` must lie strictly inside the parameter range, with a multiplicity below the
/// degree; otherwise `s` is returned unchanged.
pub fn insert_knot(s: &NurbsSurface, dir: Direction, t: f64) -> NurbsSurface {
    let d = dir.index();
    let p = s.degree()[d];
    let knots = &s.knots()[d];
    let (lo, hi) = s.range(dir);
    let multiplicity = knots.iter().filter(|&&k| k == t).count();
    if !(t > lo && t < hi) || multiplicity >= p {
        return s.clone();
    }
    let mut new_knots = Vec::new();
    let inserted: Vec<Vec<DVec4>> = lines(s, dir)
        .iter()
        .map(|l| {
            let (k, q) = insert_curve(p, knots, l, t);
            new_knots = k;
            q
        })
        .collect();
    from_lines(s, dir, new_knots, &inserted)
}

/// Splits `s` at `t` in `dir` (strictly inside the range) into the part below `t` and the
/// part above it, each clamped, on the original parameters: `t` is inserted up to the
/// degree, and the control line through which the surface then passes is shared.
pub fn split_at(s: &NurbsSurface, dir: Direction, t: f64) -> Option<(NurbsSurface, NurbsSurface)> {
    let d = dir.index();
    let p = s.degree()[d];
    let (lo, hi) = s.range(dir);
    if !(t > lo && t < hi) {
        return None;
    }
    let mut full = s.clone();
    while full.knots()[d].iter().filter(|&&k| k == t).count() < p {
        full = insert_knot(&full, dir, t);
    }
    let knots = &full.knots()[d];
    let a = knots.iter().position(|&k| k == t)?;
    let lines = lines(&full, dir);
    let mut left_knots = knots[..a + p].to_vec();
    left_knots.push(t);
    let mut right_knots = vec![t];
    right_knots.extend_from_slice(&knots[a..]);
    let left: Vec<Vec<DVec4>> = lines.iter().map(|l| l[..a].to_vec()).collect();
    let right: Vec<Vec<DVec4>> = lines.iter().map(|l| l[a - 1..].to_vec()).collect();
    Some((
        from_lines(&full, dir, left_knots, &left),
        from_lines(&full, dir, right_knots, &right),
    ))
}

/// The parameter where the middle of the control net lies in `dir`: the Greville abscissa
/// (the mean of the `degree` knots after a point's index) of the middle control point, or,
/// for an even count, the mean of the two middle points' abscissae (the paper inserts a
/// point between them); the middle of the range when that is not strictly inside it.
pub fn middle_parameter(s: &NurbsSurface, dir: Direction) -> f64 {
    let d = dir.index();
    let p = s.degree()[d];
    let n = s.count()[d];
    let knots = &s.knots()[d];
    let greville = |m: usize| knots[m + 1..=m + p].iter().sum::<f64>() / p as f64;
    let g = 0.5 * (greville((n - 1) / 2) + greville(n / 2));
    let (lo, hi) = s.range(dir);
    if g > lo && g < hi { g } else { 0.5 * (lo + hi) }
}

/// One subdivision level: `s` split at the middle parameters in `u` and in `v` into four
/// sub-surfaces (low u low v, low u high v, high u low v, high u high v).
pub fn quarter(s: &NurbsSurface) -> Option<[NurbsSurface; 4]> {
    let (tu, tv) = (middle_parameter(s, Direction::U), middle_parameter(s, Direction::V));
    let (low, high) = split_at(s, Direction::U, tu)?;
    let (a, b) = split_at(&low, Direction::V, tv)?;
    let (c, d) = split_at(&high, Direction::V, tv)?;
    Some([a, b, c, d])
}
