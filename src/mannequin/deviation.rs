//! Distance from refined points to the dress form's true surface.
//!
//! A fine tessellation of the form (parry3d `TriMesh` with its BVH) finds the nearest
//! triangle, whose corner parameters give a start `(s, t)`; Gauss-Newton on the analytic
//! surface then minimizes `|P(s, t) - q|^2` with `s` kept in `[0, 1]`. The result is the
//! distance to the true surface, not to its tessellation.

use glam::DVec3;
use parry3d::query::PointQueryWithLocation;

use super::dress_form::{DressForm, Region, ring_angle};
use crate::convergence::{Stop, record};

/// Max and RMS of a set of distances.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ErrorStats {
    /// Largest distance, m.
    pub max_m: f64,
    /// Root mean square distance, m.
    pub rms_m: f64,
    /// Number of points.
    pub count: usize,
}

impl ErrorStats {
    /// Statistics of the given distances.
    pub fn of(values: impl Iterator<Item = f64>) -> Self {
        let (mut max_m, mut sum_sq, mut count) = (0.0_f64, 0.0, 0usize);
        for v in values {
            max_m = max_m.max(v);
            sum_sq += v * v;
            count += 1;
        }
        Self {
            max_m,
            rms_m: if count > 0 { (sum_sq / count as f64).sqrt() } else { 0.0 },
            count,
        }
    }
}

/// The true surface with a search structure.
pub struct TrueSurface {
    form: DressForm,
    mesh: parry3d::shape::TriMesh,
    /// `(s, t)` of each triangle's corners, `t` unwrapped across the seam.
    corner_params: Vec<[(f64, f64); 3]>,
}

const SEARCH_LAYERS: usize = 240;
/// Most Gauss-Newton steps of a closest-point search on the true surface.
const GAUSS_NEWTON_STEPS: usize = 30;
/// A Gauss-Newton step shorter than this (parameter units) has converged.
const GAUSS_NEWTON_TOLERANCE: f64 = 1e-13;
const SEARCH_POINTS: usize = 288;

impl TrueSurface {
    /// Tessellates the form for the nearest-triangle search.
    pub fn new(form: &DressForm) -> Self {
        let (ns, nt) = (SEARCH_LAYERS, SEARCH_POINTS);
        let param = |i: usize, j: usize| (i as f64 / (ns - 1) as f64, ring_angle(j, nt));
        let mut vertices = Vec::with_capacity(ns * nt);
        for i in 0..ns {
            for j in 0..nt {
                let (s, t) = param(i, j);
                vertices.push(form.point(s, t).as_vec3());
            }
        }
        let mut indices = Vec::with_capacity(2 * ns * nt);
        let mut corner_params = Vec::with_capacity(2 * ns * nt);
        let id = |i: usize, j: usize| (i * nt + j % nt) as u32;
        for i in 0..ns - 1 {
            for j in 0..nt {
                for corners in [
                    [(i, j), (i, j + 1), (i + 1, j + 1)],
                    [(i, j), (i + 1, j + 1), (i + 1, j)],
                ] {
                    indices.push(corners.map(|(a, b)| id(a, b)));
                    corner_params.push(corners.map(|(a, b)| param(a, b)));
                }
            }
        }
        // The grid is regular and non-degenerate, so the builder cannot fail on it.
        let mesh = parry3d::shape::TriMesh::new(vertices, indices).unwrap_or_else(|e| {
            unreachable!("dress form tessellation rejected: {e:?}");
        });
        Self {
            form: *form,
            mesh,
            corner_params,
        }
    }

    /// Distance of each point to the true surface, and the region of its foot point.
    pub fn deviations(&self, points: &[DVec3]) -> (Vec<f64>, Vec<Region>) {
        points.iter().map(|q| self.distance(*q)).unzip()
    }

    /// Distance of `q` to the true surface and the region of the nearest point.
    pub fn distance(&self, q: DVec3) -> (f64, Region) {
        let (projection, (triangle, _)) = self.mesh.project_local_point_and_get_location(q.as_vec3(), false);
        let foot = projection.point.as_dvec3();
        let params = self.corner_params[triangle as usize];
        let [a, b, c] = params.map(|(s, t)| self.form.point(s, t));
        let w = barycentric(foot, a, b, c);
        let mut s = w[0] * params[0].0 + w[1] * params[1].0 + w[2] * params[2].0;
        let mut t = w[0] * params[0].1 + w[1] * params[1].1 + w[2] * params[2].1;
        let mut best = self.form.point(s, t).distance(q);
        let mut stop = (Stop::IterationLimit, GAUSS_NEWTON_STEPS, 0.0);
        for step in 0..GAUSS_NEWTON_STEPS {
            let r = self.form.point(s, t) - q;
            let (ps, pt) = self.form.tangents(s, t);
            let (a11, a12, a22) = (ps.dot(ps), ps.dot(pt), pt.dot(pt));
            let (g1, g2) = (ps.dot(r), pt.dot(r));
            let det = a11 * a22 - a12 * a12;
            if det.abs() <= f64::MIN_POSITIVE {
                stop = (Stop::Stalled, step, stop.2);
                break;
            }
            let ds = -(a22 * g1 - a12 * g2) / det;
            let dt = -(a11 * g2 - a12 * g1) / det;
            let mut scale = 1.0;
            let mut improved = false;
            for _ in 0..8 {
                let (s1, t1) = ((s + scale * ds).clamp(0.0, 1.0), t + scale * dt);
                let d1 = self.form.point(s1, t1).distance(q);
                if d1 <= best {
                    (s, t, best, improved) = (s1, t1, d1, true);
                    break;
                }
                scale *= 0.5;
            }
            let moved = (ds * scale).abs() + (dt * scale).abs();
            stop.2 = moved;
            if moved < GAUSS_NEWTON_TOLERANCE {
                stop = (Stop::Converged, step + 1, moved);
                break;
            }
            if !improved {
                stop = (Stop::Stalled, step + 1, moved);
                break;
            }
        }
        record("mannequin.gauss_newton", stop.0, stop.1, stop.2);
        (best, Region::of(s))
    }
}

/// Barycentric coordinates of `p` (projected into the triangle's plane), clamped to it.
fn barycentric(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> [f64; 3] {
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let (d00, d01, d11, d20, d21) = (v0.dot(v0), v0.dot(v1), v1.dot(v1), v2.dot(v0), v2.dot(v1));
    let det = d00 * d11 - d01 * d01;
    if det.abs() <= f64::MIN_POSITIVE {
        return [1.0, 0.0, 0.0];
    }
    let v = ((d11 * d20 - d01 * d21) / det).clamp(0.0, 1.0);
    let w = ((d00 * d21 - d01 * d20) / det).clamp(0.0, 1.0 - v);
    [1.0 - v - w, v, w]
}
