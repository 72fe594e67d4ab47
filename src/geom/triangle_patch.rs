//! Three-sided patches (\[frame\] section 4: a surface bounded by three curves), by Nielson's
//! side-vertex method (Nielson 1979; Farin, *Curves and Surfaces for CAGD*, chapter 22).
//!
//! With boundaries `c0` from `V0` to `V1`, `c1` from `V1` to `V2` and `c2` from `V2` to `V0`,
//! each on `[0, 1]`, and barycentric coordinates `b = (b0, b1, b2)`: for each corner `Vi` the
//! side-vertex line runs from `Vi` to the point of the opposite side where the line through
//! `Vi` meets it, and `Pi` follows that line by a cubic Hermite curve in `bi`, its end
//! derivatives blended from the sides' (see `along_line`),
//!
//! ```text
//! Pi(b) = H(Ci(b_k / (b_j + b_k)), Vi; bi)               (Ci the side opposite Vi, from Vj to Vk)
//! S(b)  = sum_i wi Pi(b),  wi = (b_j b_k)^2 / ((b0 b1)^2 + (b1 b2)^2 + (b2 b0)^2)
//! ```
//!
//! On a side (`bi = 0`), the two side-vertex lines ending there give the side's own point and
//! the third weight is 0: the patch interpolates all three boundaries exactly. With straight
//! sides parametrised uniformly each `Pi` is the affine point `b0 V0 + b1 V1 + b2 V2`, so a
//! flat triangle is reproduced exactly. At a corner the weights are 0/0: the corner
//! itself is taken there. Unlike a four-sided patch with one side collapsed to a point, no
//! row of the patch's sampling shrinks to a point, so its triangles have no degenerate
//! normals at the apex.

use glam::DVec3;

use super::coons::{CornerMismatch, ParametricCurve};

/// A three-sided patch over three boundary curves, corner to corner.
pub struct TrianglePatch<C> {
    /// The sides: `V0 -> V1`, `V1 -> V2`, `V2 -> V0`.
    pub sides: [C; 3],
    corners: [DVec3; 3],
}

impl<C: ParametricCurve> TrianglePatch<C> {
    /// Builds the patch; each side must end where the next begins, within `tolerance`
    /// (metres). The sides' start points are the corners.
    pub fn try_new(sides: [C; 3], tolerance: f64) -> Result<Self, CornerMismatch> {
        const NAMES: [&str; 3] = ["V1", "V2", "V0"];
        for k in 0..3 {
            let (a, b) = (sides[k].sample(1.0), sides[(k + 1) % 3].sample(0.0));
            let distance = a.distance(b);
            // Written so that a NaN distance fails the check too.
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            if !(distance <= tolerance) {
                return Err(CornerMismatch {
                    corner: NAMES[k],
                    a: a.to_array(),
                    b: b.to_array(),
                    distance,
                    tolerance,
                });
            }
        }
        let corners = [sides[0].sample(0.0), sides[1].sample(0.0), sides[2].sample(0.0)];
        Ok(Self { sides, corners })
    }

    /// The point of side `i` (the side opposite corner `(i + 2) % 3`) at `t`.
    fn side(&self, i: usize, t: f64) -> DVec3 {
        self.sides[i].sample(t.clamp(0.0, 1.0))
    }

    /// The derivative of the boundary leaving corner `i` towards corner `j` at `Vi`, by its
    /// side's parameter (central differences of the side's samples).
    fn leaving(&self, i: usize, j: usize) -> DVec3 {
        const H: f64 = 1e-5;
        if j == (i + 1) % 3 {
            (self.side(i, H) - self.side(i, 0.0)) / H
        } else {
            // Side j runs from Vj to Vi: leaving Vi is going back along it.
            (self.side(j, 1.0 - H) - self.side(j, 1.0)) / H
        }
    }

    /// The point at `tau` of corner `i`'s side-vertex line through the opposite side's
    /// point at `s`: the cubic Hermite curve from that point (`tau = 0`) to `Vi` (`tau = 1`),
    /// its end derivatives' directions blended from the sides' at the corners (at `Vi`, the
    /// two sides leaving it, weighted `1 - s` and `s`; at the opposite side, the sides leaving
    /// its ends towards `Vi`, weighted alike), their lengths the line's chord. Straight sides
    /// give the straight line.
    fn along_line(&self, i: usize, s: f64, tau: f64) -> DVec3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let start = self.side(j, s);
        let end = self.corners[i];
        // Directions blended from the sides, lengths the line's chord: a long side's
        // derivative on a short line would overshoot (straight sides give the chord itself).
        let chord = start.distance(end);
        let d_start = (self.leaving(j, i) * (1.0 - s) + self.leaving(k, i) * s).normalize_or_zero() * chord;
        let d_end = -(self.leaving(i, j) * (1.0 - s) + self.leaving(i, k) * s).normalize_or_zero() * chord;
        let (t2, t3) = (tau * tau, tau * tau * tau);
        start * (2.0 * t3 - 3.0 * t2 + 1.0)
            + d_start * (t3 - 2.0 * t2 + tau)
            + end * (-2.0 * t3 + 3.0 * t2)
            + d_end * (t3 - t2)
    }

    /// `S(b)` for barycentric coordinates `b` (non-negative, summing to 1), by the formula
    /// of the module docs.
    pub fn sample(&self, b: [f64; 3]) -> DVec3 {
        let [b0, b1, b2] = b;
        // A corner: the weights are 0/0 there.
        if let Some(k) = b.iter().position(|&bk| bk >= 1.0 - 1e-15) {
            return self.corners[k];
        }
        // Corner i's side-vertex point: the opposite side is side (i + 1) % 3, running from
        // corner (i + 1) % 3 to corner (i + 2) % 3; the line through Vi meets it at
        // s = b_{i+2} / (b_{i+1} + b_{i+2}), and runs from there (tau = 0) to Vi (tau = bi).
        let point = |i: usize| -> DVec3 {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let s = b[k] / (b[j] + b[k]);
            self.along_line(i, s, b[i])
        };
        let w = [(b1 * b2).powi(2), (b2 * b0).powi(2), (b0 * b1).powi(2)];
        let total: f64 = w.iter().sum();
        if total <= 0.0 {
            // On a side (one coordinate 0, away from the corners): that side's point.
            let i = (0..3).find(|&i| b[i] <= 0.0).unwrap_or(0);
            return point(i);
        }
        (0..3).map(|i| point(i) * (w[i] / total)).sum()
    }

    /// Samples on the triangular grid of `n` segments per side, row by row away from side
    /// `c0`: row `r` (`0..=n`) holds `n - r + 1` points, at `b = (1 - i/n - r/n, i/n, r/n)` for
    /// `i` in `0..=n - r`. Row 0 is side `c0` (`V0` to `V1`), row `n` is `V2`.
    pub fn grid(&self, n: usize) -> Vec<DVec3> {
        let n = n.max(1);
        let mut out = Vec::with_capacity((n + 1) * (n + 2) / 2);
        for r in 0..=n {
            for i in 0..=n - r {
                let b1 = i as f64 / n as f64;
                let b2 = r as f64 / n as f64;
                out.push(self.sample([(1.0 - b1 - b2).max(0.0), b1, b2]));
            }
        }
        out
    }
}

/// The triangles of [`TrianglePatch::grid`]`(n)`, indices into its points, oriented like the
/// corners `V0, V1, V2`: `n^2` triangles.
pub fn triangle_grid(n: usize) -> Vec<[u32; 3]> {
    let n = n.max(1);
    let start = |r: usize| (0..r).map(|q| n - q + 1).sum::<usize>();
    let mut out = Vec::with_capacity(n * n);
    for r in 0..n {
        let (row, next) = (start(r), start(r + 1));
        for i in 0..n - r {
            let (a, b, c) = (row + i, row + i + 1, next + i);
            out.push([a as u32, b as u32, c as u32]);
            if i + 1 < n - r {
                out.push([b as u32, next as u32 + i as u32 + 1, c as u32]);
            }
        }
    }
    out
}
