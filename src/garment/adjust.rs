//! Loose fit and the combined adjustment (\[frame\] sections 2.4-2.5).
//!
//! Straightening: below a ring that must not change (its anchor is a virtual control point
//! of the contour), a loose contour becomes the straight line from that point to the
//! lowest one, the lowest pushed outward just enough that no ring in between has to move
//! inward. The rings whose anchors moved are then deformed in their own frame: centre `O`
//! and the anchors; each anchor's displacement is the maximum in its direction, and the
//! points between two anchors move in linear proportion to their angle about `O`.

use glam::{DVec2, DVec3};

use super::ease::deformation_centre;
use crate::geom::Plane;

/// Straightens a contour part (\[frame\] section 2.4, loose garments): `points[0]` (m) is
/// fixed, the last may move along `outward[last]` (a horizontal unit vector), the ones
/// between move onto the line at their own height. Returns the new positions, m.
pub fn straighten(points: &[DVec3], outward: &[DVec3]) -> Vec<DVec3> {
    let n = points.len();
    if n < 2 {
        return points.to_vec();
    }
    let (top, bottom) = (points[0], points[n - 1]);
    let span = bottom.y - top.y;
    let at = |y: f64| if span != 0.0 { (y - top.y) / span } else { 0.0 };
    // Offset beyond ring k of the line through `bottom + delta outward[n-1]`:
    // base_k + delta t_k (outward[n-1] . outward[k]); the line must not pass inside any ring.
    let mut delta: f64 = 0.0;
    for k in 1..n - 1 {
        let t = at(points[k].y);
        let line = top + (bottom - top) * t;
        let base = (line - points[k]).dot(outward[k]);
        let gain = t * outward[n - 1].dot(outward[k]);
        if base < 0.0 && gain > 1e-12 {
            delta = delta.max(-base / gain);
        }
    }
    let end = bottom + outward[n - 1] * delta;
    points
        .iter()
        .enumerate()
        .map(|(k, p)| match k {
            0 => *p,
            k if k == n - 1 => end,
            _ => top + (end - top) * at(p.y),
        })
        .collect()
}

/// The combined adjustment of \[frame\] section 2.5: deforms a ring's control points (m, in
/// `plane`) so that its anchors (`anchors`: indices into `control`, in ring order) move by
/// `moves` (m); every other point moves by the linear blend of the two anchor moves around
/// it, weighted by its angle about the deformation centre between them:
/// `d(p) = (1 - s) d_a + s d_b`, `s = angle(a, p) / angle(a, b)`.
pub fn combined_adjustment(control: &[DVec3], anchors: &[usize], moves: &[DVec3], plane: &Plane) -> Vec<DVec3> {
    let flat: Vec<DVec2> = control.iter().map(|p| plane.project(*p)).collect();
    let o = deformation_centre(&flat);
    let angle = |p: DVec2| (p.y - o.y).atan2(p.x - o.x);
    let tau = std::f64::consts::TAU;
    let base = angle(flat[anchors[0]]);
    let rel = |p: DVec2| (angle(p) - base).rem_euclid(tau);
    let marks: Vec<f64> = anchors.iter().map(|&i| rel(flat[i])).collect();
    let m = anchors.len();
    control
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if let Some(k) = anchors.iter().position(|&a| a == i) {
                return *p + moves[k];
            }
            let x = rel(flat[i]);
            let k = (0..m).rev().find(|&k| marks[k] <= x).unwrap_or(0);
            let (a0, a1) = (marks[k], if k + 1 < m { marks[k + 1] } else { tau });
            let w = if a1 > a0 {
                ((x - a0) / (a1 - a0)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            *p + moves[k] * (1.0 - w) + moves[(k + 1) % m] * w
        })
        .collect()
}
