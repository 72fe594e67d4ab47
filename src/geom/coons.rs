//! Bilinearly blended Coons patches (\[frame\] section 4): the surface of a region bounded by
//! four curves.
//!
//! With boundaries `c0(u)` (v = 0), `c1(u)` (v = 1), `d0(v)` (u = 0), `d1(v)` (u = 1) and
//! corners `P00 = c0(0) = d0(0)`, `P10 = c0(1) = d1(0)`, `P01 = c1(0) = d0(1)`,
//! `P11 = c1(1) = d1(1)`:
//!
//! ```text
//! S(u, v) = (1 - v) c0(u) + v c1(u) + (1 - u) d0(v) + u d1(v)
//!         - [(1 - u)(1 - v) P00 + u (1 - v) P10 + (1 - u) v P01 + u v P11]
//! ```
//!
//! (Coons 1967; Farin, *Curves and Surfaces for CAGD*, chapter 22.) The patch interpolates
//! all four boundaries exactly and reproduces bilinear patches and planes.

use glam::DVec3;
use thiserror::Error;

/// A curve on the parameter range `[0, 1]`.
pub trait ParametricCurve {
    /// The point at parameter `t`.
    fn sample(&self, t: f64) -> DVec3;
}

impl<F: Fn(f64) -> DVec3> ParametricCurve for F {
    fn sample(&self, t: f64) -> DVec3 {
        self(t)
    }
}

/// Boundaries whose corners do not meet.
#[derive(Debug, Error, Clone, PartialEq)]
#[error(
    "Coons boundaries do not meet at corner {corner}: {a:?} and {b:?} are {distance:e} m apart (tolerance {tolerance:e} m)"
)]
pub struct CornerMismatch {
    /// `P00`, `P10`, `P01` or `P11`.
    pub corner: &'static str,
    /// The point on the u-curve (input units, m in drape).
    pub a: [f64; 3],
    /// The point on the v-curve (input units).
    pub b: [f64; 3],
    /// Their distance (input units).
    pub distance: f64,
    /// The tolerance used (input units).
    pub tolerance: f64,
}

/// A Coons patch over four boundary curves.
pub struct CoonsPatch<C> {
    /// `c0(u)`: the boundary at `v = 0`.
    pub bottom: C,
    /// `c1(u)`: the boundary at `v = 1`.
    pub top: C,
    /// `d0(v)`: the boundary at `u = 0`.
    pub left: C,
    /// `d1(v)`: the boundary at `u = 1`.
    pub right: C,
    corners: [DVec3; 4],
}

impl<C: ParametricCurve> CoonsPatch<C> {
    /// Builds the patch; the corners of the u-curves and v-curves must agree within
    /// `tolerance` (metres). The u-curves' corners are used.
    pub fn try_new(bottom: C, top: C, left: C, right: C, tolerance: f64) -> Result<Self, CornerMismatch> {
        let checks = [
            ("P00", bottom.sample(0.0), left.sample(0.0)),
            ("P10", bottom.sample(1.0), right.sample(0.0)),
            ("P01", top.sample(0.0), left.sample(1.0)),
            ("P11", top.sample(1.0), right.sample(1.0)),
        ];
        for (corner, a, b) in checks {
            let distance = a.distance(b);
            // Written so that a NaN distance fails the check too.
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            if !(distance <= tolerance) {
                return Err(CornerMismatch {
                    corner,
                    a: a.to_array(),
                    b: b.to_array(),
                    distance,
                    tolerance,
                });
            }
        }
        let corners = [checks[0].1, checks[1].1, checks[2].1, checks[3].1];
        Ok(Self {
            bottom,
            top,
            left,
            right,
            corners,
        })
    }

    /// `S(u, v)` for `u, v` in `0..=1` (input units, m in drape), by the bilinearly blended Coons
    /// formula of the module docs.
    pub fn sample(&self, u: f64, v: f64) -> DVec3 {
        let [p00, p10, p01, p11] = self.corners;
        let ruled_u = self.bottom.sample(u) * (1.0 - v) + self.top.sample(u) * v;
        let ruled_v = self.left.sample(v) * (1.0 - u) + self.right.sample(v) * u;
        let bilinear = p00 * ((1.0 - u) * (1.0 - v)) + p10 * (u * (1.0 - v)) + p01 * ((1.0 - u) * v) + p11 * (u * v);
        ruled_u + ruled_v - bilinear
    }

    /// Samples on a regular `(nu + 1) x (nv + 1)` grid in `(u, v)`, row by row in `v`.
    pub fn grid(&self, nu: usize, nv: usize) -> Vec<DVec3> {
        let (nu, nv) = (nu.max(1), nv.max(1));
        let mut out = Vec::with_capacity((nu + 1) * (nv + 1));
        for j in 0..=nv {
            let v = j as f64 / nv as f64;
            for i in 0..=nu {
                out.push(self.sample(i as f64 / nu as f64, v));
            }
        }
        out
    }
}
