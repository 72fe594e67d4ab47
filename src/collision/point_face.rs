//! The point-face test (\[collide\] 4.2, figure 8): from the garment vertex `p` along a body
//! triangle's normal `n`, the short segment `p - w2 n .. p + w1 n` is intersected with the
//! triangle; a hit on the outward side means `p` lies behind the skin, inside the body.
//!
//! The segment hits the triangle exactly when `p` projects into it along `n`, that is
//! when the nearest point of that triangle lies inside its face. Where the segment misses
//! every triangle (a point in the normal cone of a concave edge or vertex, as in the
//! armpit or the crotch) the nearest edge or vertex decides with its angle-weighted
//! pseudo-normal. That makes the test exact for a closed body: it answers inside exactly
//! when the point is inside, up to the reach `w1` below the skin.

use glam::DVec3;

use crate::body::index::{BodyIndex, Nearest};

/// Which triangles the test looks at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Search {
    /// Every body triangle, one by one (the reference).
    Brute,
    /// Partition `k`'s triangles, one by one.
    Partition(usize),
    /// Partition `k`'s triangles through its BVH.
    PartitionBvh(usize),
}

/// How far the test looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reach {
    /// `w1`: depth below the skin still detected, m.
    pub inside: f64,
    /// `w2`: distance above the skin within which a vertex is reported near, m.
    pub outside: f64,
    /// Distances up to this count as on the surface (neither in nor out), m.
    pub surface: f64,
}

/// What the test found for one vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointFace {
    /// The nearest body point within reach.
    pub nearest: Option<Nearest>,
    /// Whether the vertex lies inside (deeper than the surface tolerance, within `w1`).
    pub inside: bool,
}

impl PointFace {
    /// Distance to the surface if outside, m (at least the reach when nothing was near).
    pub fn clearance(&self, reach: &Reach) -> f64 {
        match self.nearest {
            Some(n) if !self.inside => n.distance,
            Some(_) => 0.0,
            None => reach.inside.max(reach.outside),
        }
    }
}

/// The point-face test of `p`.
pub fn point_face(index: &BodyIndex, search: Search, p: DVec3, reach: &Reach) -> PointFace {
    let r = reach.inside.max(reach.outside);
    let nearest = match search {
        Search::Brute => index
            .nearest_among(p, index.shell_triangles())
            .filter(|n| n.distance <= r),
        Search::Partition(k) => index
            .nearest_among(p, index.partitions[k].triangles.iter().copied())
            .filter(|n| n.distance <= r),
        Search::PartitionBvh(k) => index.nearest_in_partition(k, p, r),
    };
    let inside = nearest.is_some_and(|n| n.distance > reach.surface && n.distance <= reach.inside && n.signed(p) < 0.0);
    PointFace { nearest, inside }
}
