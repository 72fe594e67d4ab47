//! M1's collision (\[collide\] section 3.1): M0 has been collided; M1 is collided only where
//! it differs from M0. Its new vertices (and old ones the smoothing moved) are tested
//! exactly against the whole body, those inside are pushed out by their partition's rule
//! (the partition of the M0 vertex they descend from), and the edge rounds lift M1's
//! crossing edges by moving only those vertices: M0's vertices stay where M0's collision
//! put them, so M1 and M0 agree on them. Then the exact quality check runs over all of M1.

use glam::DVec3;

use super::M1;
use crate::collision::{
    BodyIndex, CollisionOptions, Hit, Quality, Response, VertexRoles, quality, respond, respond_edges, response_ease,
};
use crate::par::par_map;

/// M1 after its collision.
#[derive(Clone, Debug, PartialEq)]
pub struct M1Collision {
    /// Vertices tested (those M0 does not have).
    pub tested: usize,
    /// Of those, inside the body before the response.
    pub hits: usize,
    /// M1's edges crossing the body before the response (exact).
    pub crossing_before: usize,
    /// Those edges.
    pub crossing_before_edges: Vec<[u32; 2]>,
    /// The moves made (vertex response, then the edge rounds).
    pub responses: Vec<Response>,
    /// Edges crossing at the start of each edge round.
    pub edge_rounds: Vec<usize>,
    /// M1's positions after the response.
    pub positions: Vec<DVec3>,
    /// The exact check over all of M1 after the response.
    pub quality: Quality,
}

/// Collides M1 (whose M0 vertices are already collided): only the vertices M0 does not
/// have move. `partition` is M0's vertex partition (from its detection), `ring_normal`
/// M0's ring roles; `garment_ease` the garment's ease.
pub fn collide_m1(
    index: &BodyIndex,
    m1: &M1,
    partition: &[usize],
    ring_normal: &[Option<DVec3>],
    garment_ease: f64,
    options: &CollisionOptions,
) -> M1Collision {
    let reach = 0.2 * index.height;
    let positions = &m1.mesh.positions;
    let tested = m1.differs_from_m0();
    let m1_partition: Vec<usize> = m1
        .anchor
        .iter()
        .map(|&a| partition.get(a as usize).copied().unwrap_or(0))
        .collect();
    let hits: Vec<Hit> = par_map(tested.len(), |k| {
        let v = tested[k];
        let p = positions[v as usize];
        let near = index.nearest(p, reach)?;
        let signed = near.signed(p);
        (signed < 0.0).then(|| Hit {
            vertex: v,
            partition: m1_partition[v as usize],
            method: crate::body::DetectionMethod::PointFace,
            depth: -signed,
            foot: near.foot,
            normal: near.normal,
            triangle: Some(near.triangle),
        })
    })
    .into_iter()
    .flatten()
    .collect();
    let normals = m1.mesh.vertex_normals();
    let boundary = vec![false; positions.len()];
    let mut rings: Vec<Option<DVec3>> = ring_normal.to_vec();
    rings.resize(positions.len(), None);
    let mut pinned = vec![true; m1.m0_vertices];
    pinned.resize(positions.len(), false);
    for &v in &m1.smoothed {
        pinned[v as usize] = false;
    }
    let roles = VertexRoles {
        normals: &normals,
        boundary: &boundary,
        ring_normal: &rings,
        pinned: &pinned,
    };
    let edges = m1.edges();
    let before = quality(index, positions, positions, &edges, &[]);
    let crossing_before_edges: Vec<[u32; 2]> = before.crossing.iter().map(|&e| edges[e as usize]).collect();
    let ease = response_ease(index, garment_ease, &options.response);
    let (mut moved, mut responses) = respond(index, positions, &hits, &roles, ease, &options.response);
    let (edge_responses, edge_rounds, _) = respond_edges(
        index,
        &mut moved,
        &edges,
        &m1_partition,
        &roles,
        ease,
        &options.response,
    );
    responses.extend(edge_responses);
    let quality = quality(index, positions, &moved, &edges, &responses);
    M1Collision {
        tested: tested.len(),
        hits: hits.len(),
        crossing_before: crossing_before_edges.len(),
        crossing_before_edges,
        responses,
        edge_rounds,
        positions: moved,
        quality,
    }
}
