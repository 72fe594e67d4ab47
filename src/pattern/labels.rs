//! Which feature curve each edge between two patches lies on.
//!
//! The patches' boundaries are samples of the feature curves, so an edge between two
//! patches lies on a curve: both its ends are on that curve's polyline and its middle near
//! it. For each such edge every curve is scored by the larger distance of the edge's two
//! ends, and the edge takes the nearest curve whose polyline also passes near the edge's
//! middle, with every other curve that runs along the same edge (the sleeve's armhole is
//! fitted through the strap's samples, so both lie on those edges). A curve farther from an
//! edge's ends than the edge is long is never its curve.

use glam::DVec3;

use crate::geom::closest::closest_on_segment;

/// The curves of the edges between patches.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EdgeCurves {
    /// Curve names, by index.
    pub names: Vec<String>,
    /// Every undirected edge between two faces of different patches (smaller vertex first,
    /// sorted), with the curves it lies on (indices into `names`, nearest first; empty when
    /// none is near).
    pub edges: Vec<([u32; 2], Vec<u32>)>,
}

impl EdgeCurves {
    /// The curves `edge` lies on (empty for an edge inside a patch, or on no curve).
    pub fn of(&self, edge: [u32; 2]) -> &[u32] {
        let key = [edge[0].min(edge[1]), edge[0].max(edge[1])];
        self.edges
            .binary_search_by(|(e, _)| e.cmp(&key))
            .map_or(&[], |k| &self.edges[k].1)
    }
}

/// A curve runs along an edge when its ends' distance is within this fraction of the
/// edge's length of the nearest curve's (the patches' boundary samples lie on their curves,
/// so the nearest is at about 0).
const ALONG: f64 = 0.02;

/// ... and the edge's middle is within this fraction of its length of the curve: a curve
/// bows away from its chord between two samples (a fitted armhole by up to a few percent of
/// the chord), but not by a quarter of it.
const BOW: f64 = 0.25;

/// Labels the edges between patches of a mesh (`face_patch` per triangle) with the curves
/// (`(name, polyline)`) they lie on, its vertices at `positions`: where the patches were
/// surfaced (their boundary samples on the curves), not where a collision moved them.
pub fn label_edges(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    face_patch: &[u32],
    curves: &[(String, Vec<DVec3>)],
) -> EdgeCurves {
    let mut half: Vec<([u32; 2], u32)> = triangles
        .iter()
        .zip(face_patch)
        .flat_map(|(t, &p)| (0..3).map(move |k| ([t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])], p)))
        .collect();
    half.sort_unstable();
    let mut between: Vec<[u32; 2]> = half
        .windows(2)
        .filter(|w| w[0].0 == w[1].0 && w[0].1 != w[1].1)
        .map(|w| w[0].0)
        .collect();
    between.dedup();
    let boxes: Vec<(DVec3, DVec3)> = curves
        .iter()
        .map(|(_, p)| {
            p.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), q| {
                (lo.min(*q), hi.max(*q))
            })
        })
        .collect();
    let edges = between
        .into_iter()
        .map(|e| {
            let (a, b) = (positions[e[0] as usize], positions[e[1] as usize]);
            let reach = a.distance(b);
            let mid = 0.5 * (a + b);
            // (ends, middle) distances of every curve near enough.
            let mut scored: Vec<(f64, f64, u32)> = curves
                .iter()
                .zip(&boxes)
                .enumerate()
                .filter(|(_, (_, (lo, hi)))| {
                    let (lo, hi) = (*lo - DVec3::splat(reach), *hi + DVec3::splat(reach));
                    [a, b].iter().all(|p| p.cmpge(lo).all() && p.cmple(hi).all())
                })
                .map(|(c, ((_, poly), _))| {
                    let ends = polyline_distance(poly, a).max(polyline_distance(poly, b));
                    (ends, polyline_distance(poly, mid), c as u32)
                })
                .filter(|&(ends, middle, _)| ends <= reach && middle <= BOW * reach)
                .collect();
            scored.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.2.cmp(&y.2)));
            let best = scored.first().map_or(0.0, |s| s.0);
            let on = scored
                .into_iter()
                .filter(|&(ends, _, _)| ends <= best + ALONG * reach)
                .map(|(_, _, c)| c)
                .collect();
            (e, on)
        })
        .collect();
    EdgeCurves {
        names: curves.iter().map(|(n, _)| n.clone()).collect(),
        edges,
    }
}

/// Distance from `p` to a polyline.
fn polyline_distance(poly: &[DVec3], p: DVec3) -> f64 {
    match poly {
        [] => f64::INFINITY,
        [q] => q.distance(p),
        _ => poly
            .windows(2)
            .map(|w| closest_on_segment(p, w[0], w[1]).0.distance(p))
            .fold(f64::INFINITY, f64::min),
    }
}
