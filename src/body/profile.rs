//! Horizontal sections of the body with the measures landmark detection needs.

use glam::{DVec2, DVec3};

use super::BodyMesh;
use crate::geom::{Plane, polygon};

/// A closed horizontal section loop with its measures (2D coordinates are `(x, z)`).
#[derive(Clone, Debug)]
pub struct MeasuredLoop {
    /// The loop's points (y constant), counter-clockwise seen from above, front-most first.
    pub points: Vec<DVec3>,
    /// `(x, z)` of each point, m (world frame seen from above).
    pub flat: Vec<DVec2>,
    /// Enclosed area, m^2.
    pub area: f64,
    /// Perimeter, m.
    pub girth: f64,
    /// Perimeter of the convex hull (what a tape measure reads), m.
    pub tape_girth: f64,
    /// Area centroid `(x, z)`, m.
    pub centroid: DVec2,
    /// Smallest `(x, z)` of the points, m.
    pub min: DVec2,
    /// Largest `(x, z)` of the points, m.
    pub max: DVec2,
}

impl MeasuredLoop {
    /// Measures a closed loop.
    pub fn new(points: Vec<DVec3>) -> Self {
        let flat: Vec<DVec2> = points.iter().map(|p| DVec2::new(p.x, p.z)).collect();
        let (min, max) = flat.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        Self {
            area: polygon::signed_area(&flat).abs(),
            girth: polygon::perimeter(&flat),
            tape_girth: polygon::hull_perimeter(&flat),
            centroid: polygon::centroid(&flat),
            min,
            max,
            flat,
            points,
        }
    }

    /// Whether `(x, z)` lies inside.
    pub fn contains(&self, p: DVec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all() && polygon::contains(&self.flat, p)
    }

    /// The section's height `y`, m.
    pub fn y(&self) -> f64 {
        self.points.first().map_or(0.0, |p| p.y)
    }

    /// The point with the largest `z` (front-most), m.
    pub fn front_point(&self) -> DVec3 {
        self.extreme(|p| p.z)
    }

    /// The point maximizing `key`, m (world frame).
    pub fn extreme(&self, key: impl Fn(&DVec3) -> f64) -> DVec3 {
        self.points
            .iter()
            .copied()
            .max_by(|a, b| key(a).total_cmp(&key(b)))
            .unwrap_or(DVec3::ZERO)
    }
}

/// The closed, outer (not nested in another), non-degenerate loops of the body at height `y`.
/// Degenerate means an area below `1e-9` of `scale^2` (a plane grazing a vertex).
pub fn outer_loops(body: &BodyMesh, y: f64, scale: f64) -> Vec<MeasuredLoop> {
    let loops: Vec<MeasuredLoop> = body
        .section(&Plane::horizontal(y))
        .into_iter()
        .filter(|l| l.closed && l.points.len() >= 3)
        .map(|l| MeasuredLoop::new(l.points))
        .filter(|l| l.area > 1e-9 * scale * scale)
        .collect();
    let nested: Vec<bool> = loops
        .iter()
        .enumerate()
        .map(|(i, inner)| {
            loops
                .iter()
                .enumerate()
                .any(|(j, outer)| i != j && outer.area > inner.area && outer.contains(inner.flat[0]))
        })
        .collect();
    loops
        .into_iter()
        .zip(nested)
        .filter(|(_, n)| !n)
        .map(|(l, _)| l)
        .collect()
}

/// Index of the loop containing `p`, else of the loop whose centroid is nearest.
pub fn loop_at(loops: &[MeasuredLoop], p: DVec2) -> Option<usize> {
    loops.iter().position(|l| l.contains(p)).or_else(|| {
        (0..loops.len()).min_by(|&a, &b| {
            loops[a]
                .centroid
                .distance_squared(p)
                .total_cmp(&loops[b].centroid.distance_squared(p))
        })
    })
}
