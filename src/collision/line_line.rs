//! The line-line test (\[collide\] 4.2, figure 9a), for legs and abdomen: in the horizontal
//! section nearest the vertex's height, the vertex's short segment along its normal,
//! `p - w2 n .. p + w1 n` (the normal's horizontal part), is intersected with the body's
//! ring polylines. From a point outside every loop the first crossing either way enters a
//! loop, from a point inside it leaves one; so the nearest crossing's side gives the
//! verdict, and its distance to the crossed edge the depth.
//!
//! The test is cheap (a few hundred 2D edges) and approximate: it reads the section at the
//! nearest slice height, not the vertex's own, and it misses points deeper than `w1`
//! along the normal. The error it really makes is measured against the exact test (see
//! the collision benchmark and `--verify`).

use glam::{DVec2, DVec3};

use super::point_face::Reach;
use crate::body::slices::{Slice, flat};
use crate::geom::polygon;

/// What the line-line test found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineLine {
    /// Index of the slice read.
    pub slice: usize,
    /// Inside (the nearest crossing leaves a loop).
    pub inside: bool,
    /// Distance from the vertex to the crossed edge's line (in the section), m.
    pub depth: f64,
    /// The crossing point (at the slice's height), m (world frame).
    pub foot: DVec3,
    /// Outward unit normal of the crossed edge (horizontal, world frame).
    pub normal: DVec3,
    /// Distance in the section from the vertex to the nearest loop edge, m (a lower bound on
    /// how far it can move in this slice before the verdict can change).
    pub clearance: f64,
}

fn cross_segment(p: DVec2, d: DVec2, a: DVec2, b: DVec2) -> Option<f64> {
    let e = b - a;
    let den = d.perp_dot(e);
    if den == 0.0 {
        return None;
    }
    let w = a - p;
    let t = w.perp_dot(e) / den;
    let s = w.perp_dot(d) / den;
    (0.0..=1.0).contains(&s).then_some(t)
}

fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let len2 = e.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(e) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + e * t)
}

/// The line-line test of `p` with (3D) normal `normal` in slice `slice` (index `k`).
/// A normal with no horizontal part is replaced by the direction from the ring's global
/// centre, then by `+z`.
pub fn line_line(slice: &Slice, k: usize, p: DVec3, normal: DVec3, reach: &Reach) -> LineLine {
    let q = flat(p);
    let mut d = flat(normal).normalize_or_zero();
    if d == DVec2::ZERO {
        d = slice
            .centres
            .map_or(DVec2::ZERO, |c| (q - c.global).normalize_or_zero());
    }
    if d == DVec2::ZERO {
        d = DVec2::Y;
    }
    let mut best: Option<(f64, DVec2)> = None;
    let mut clearance = f64::INFINITY;
    for l in &slice.loops {
        let n = l.points.len();
        for i in 0..n {
            let (a, b) = (l.points[i], l.points[(i + 1) % n]);
            clearance = clearance.min(segment_distance(q, a, b));
            if let Some(t) = cross_segment(q, d, a, b)
                && t >= -reach.outside
                && t <= reach.inside
                && best.is_none_or(|(bt, _)| t.abs() < bt.abs())
            {
                best = Some((t, l.edge_normal(i)));
            }
        }
    }
    let at = |v: DVec2| DVec3::new(v.x, slice.y, v.y);
    match best {
        Some((t, n)) => {
            let depth = t.abs() * d.dot(n).abs();
            let inside = t * d.dot(n) > 0.0 && depth > reach.surface;
            LineLine {
                slice: k,
                inside,
                depth: if inside { depth } else { 0.0 },
                foot: at(q + d * t),
                normal: DVec3::new(n.x, 0.0, n.y),
                clearance: if inside { 0.0 } else { clearance },
            }
        }
        None => LineLine {
            slice: k,
            inside: false,
            depth: 0.0,
            foot: at(q),
            normal: DVec3::ZERO,
            // Deeper than the reach: missed, and never skipped later.
            clearance: if slice.loops.iter().any(|l| polygon::contains(&l.points, q)) {
                0.0
            } else {
                clearance
            },
        },
    }
}
