//! The certificate between two layers: an outer garment over an inner one. Counted
//! exactly where it matters (a segment through a triangle by Shewchuk's `orient3d`, the side
//! of a face likewise): outer vertices behind the inner surface, outer edges through inner
//! faces, inner edges through outer faces, and the smallest gap of the outer in front of
//! the inner.

use std::cmp::Ordering;

use glam::DVec3;
use serde::Serialize;

use super::surface::LayerSurface;
use crate::geom::closest::Feature;
use crate::geom::predicates::{segment_crosses_triangle, side};
use crate::mesh::topology::undirected_edges;

/// How an outer garment meets the inner one under it.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct LayerCounts {
    /// Outer vertices behind the inner surface (on the body's side of it, where the nearest
    /// inner point is not on an opening).
    pub behind: usize,
    /// Outer edges passing through an inner face.
    pub outer_edges_through_inner: usize,
    /// Outer faces an inner edge passes through.
    pub outer_faces_pierced: usize,
    /// The smallest signed gap of an outer vertex in front of the inner surface (over the
    /// vertices whose nearest inner point is not on an opening), m; infinite when none.
    pub smallest_gap: f64,
}

impl LayerCounts {
    /// Whether the layers are in order: nothing behind, nothing through.
    pub fn clear(&self) -> bool {
        self.behind == 0 && self.outer_edges_through_inner == 0 && self.outer_faces_pierced == 0
    }
}

/// Whether `p` is behind the inner surface, and its signed gap (`None`: beside the inner,
/// its nearest point on an opening, or no surface). Nearest to a face's inside, the side
/// is decided exactly.
pub(super) fn gap(inner: &LayerSurface, p: DVec3) -> Option<(bool, f64)> {
    let near = inner.nearest(p)?;
    if near.on_opening {
        return None;
    }
    let behind = if near.feature == Feature::Face {
        let tri = inner.mesh.triangles[near.triangle as usize].map(|i| inner.mesh.positions[i as usize]);
        side(tri[0], tri[1], tri[2], p) == Ordering::Less
    } else {
        // Nearest to an edge or a corner: its pseudo-normal tells the side.
        near.signed < 0.0
    };
    Some((behind, near.signed))
}

/// The signed gap of `p` in front of the inner surface, m (negative behind it; `None`:
/// beside it, its nearest point on an opening).
pub fn signed_gap(inner: &LayerSurface, p: DVec3) -> Option<f64> {
    gap(inner, p).map(|(_, signed)| signed)
}

/// The certificate of `outer` over `inner`.
pub fn certify_layers(inner: &LayerSurface, outer: &LayerSurface) -> LayerCounts {
    let mut counts = LayerCounts {
        smallest_gap: f64::INFINITY,
        ..LayerCounts::default()
    };
    for &p in &outer.mesh.positions {
        if let Some((behind, signed)) = gap(inner, p) {
            counts.behind += usize::from(behind);
            counts.smallest_gap = counts.smallest_gap.min(signed);
        }
    }
    counts.outer_edges_through_inner =
        crossing_edges(&outer.mesh.positions, &undirected_edges(&outer.mesh), inner).len();
    let mut pierced = vec![false; outer.mesh.triangles.len()];
    for [a, b] in undirected_edges(&inner.mesh) {
        let (p, q) = (inner.mesh.positions[a as usize], inner.mesh.positions[b as usize]);
        outer.along(p, q, |t, c| {
            if segment_crosses_triangle(p, q, *c) {
                pierced[t as usize] = true;
            }
        });
    }
    counts.outer_faces_pierced = pierced.iter().filter(|&&x| x).count();
    counts
}

/// The edges (of `positions`) that pass through a face of `surface`, in order.
pub(super) fn crossing_edges(positions: &[DVec3], edges: &[[u32; 2]], surface: &LayerSurface) -> Vec<[u32; 2]> {
    edges
        .iter()
        .copied()
        .filter(|&[a, b]| {
            let (p, q) = (positions[a as usize], positions[b as usize]);
            let mut crosses = false;
            surface.along(p, q, |_, c| crosses |= segment_crosses_triangle(p, q, *c));
            crosses
        })
        .collect()
}
