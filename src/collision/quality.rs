//! Quality after response, measured rather than assumed (\[collide\] 6, figure 14): garment
//! vertices still inside the body and how deep, edges that cross the body although both
//! their ends are outside, and how far the moved vertices stand from the ease.

use glam::DVec3;

use super::response::Response;
use super::reuse::{Reuse, Reused};
use super::types::{NO_TRIANGLE, SKIN, VertexDistance, check_reach};
use crate::body::index::BodyIndex;
use crate::par::par_map;

/// Quality figures of a garment mesh against the body.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Quality {
    /// Vertices inside the body (exact test over the whole body).
    pub penetrating_vertices: usize,
    /// Deepest of them, m.
    pub max_depth_m: f64,
    /// Their mean depth, m.
    pub mean_depth_m: f64,
    /// Edges that meet the body surface.
    pub crossing_edges: usize,
    /// Faces the body pokes through (an edge of the body passes through them; see
    /// [`super::faces`]); 0 where the faces were not checked.
    pub pierced_faces: usize,
    /// The face clearance: the least distance from the body to any point of a garment face,
    /// m (0 where a face is pierced; the least vertex clearance where the faces were not
    /// measured). At most the least vertex clearance, which is a point of a face.
    pub face_clearance_m: f64,
    /// Largest `|distance - ease|` over the moved vertices, m.
    pub max_ease_error_m: f64,
    /// Mean of it, m.
    pub mean_ease_error_m: f64,
    /// Farthest any vertex was moved by the response, m.
    pub max_move_m: f64,
    /// Largest ratio of an edge's length after the response to its length before (1 when
    /// nothing was stretched).
    pub max_stretch: f64,
    /// The penetrating vertices.
    #[serde(skip)]
    pub inside: Vec<u32>,
    /// The crossing edges (indices into the edge list).
    #[serde(skip)]
    pub crossing: Vec<u32>,
    /// The pierced faces (indices into the face list), ascending.
    #[serde(skip)]
    pub pierced: Vec<u32>,
    /// The faces nearer the body than the ease (or than the least vertex clearance, where
    /// that is more), with their least distance to it, m, ascending by face (see
    /// [`super::faces::faces_nearer`]).
    #[serde(skip)]
    pub near_faces: Vec<(u32, f64)>,
    /// Each vertex's signed distance to the body, m (negative inside; infinite where not
    /// measured): the garment's clearance, for fit maps.
    #[serde(skip)]
    pub clearance: Vec<f64>,
    /// Each vertex's nearest body triangle within a fifth of the body's height
    /// ([`NO_TRIANGLE`] where none, or not measured).
    #[serde(skip)]
    pub nearest: Vec<u32>,
}

/// Distances measured during a step before the quality check (the collision measures its
/// vertices after the vertex response, for the edge rounds): the check takes a vertex's
/// distance from here when the vertex still stands at `at`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Measured {
    /// Where each vertex stood, m.
    pub at: Vec<DVec3>,
    /// Its distance there, as the check measures it.
    pub distance: Vec<VertexDistance>,
}

impl Quality {
    /// Checks the faces `triangles` too ([`super::faces::pierced_faces`], with this
    /// check's vertex distances): the whole surface certified.
    pub fn with_faces(
        mut self,
        index: &BodyIndex,
        positions: &[DVec3],
        triangles: &[[u32; 3]],
        reuse: Option<&mut Reuse>,
    ) -> Self {
        self.pierced = super::faces::pierced_faces(index, positions, triangles, &self.free(), reuse);
        self.pierced_faces = self.pierced.len();
        self
    }

    /// Measures the faces' clearance ([`Self::face_clearance_m`], [`Self::near_faces`]) down
    /// to `ease` (m), after [`Self::with_faces`]: the faces a lower bound from their
    /// corners' distances lets nearer than the ease, or than the least vertex clearance
    /// where that is more, are measured exactly; no other face can be nearer.
    /// With `reuse`, the faces whose corners did not move since they were measured with the
    /// same cap are not measured again (the same figures).
    pub fn with_face_clearance(
        mut self,
        index: &BodyIndex,
        positions: &[DVec3],
        triangles: &[[u32; 3]],
        ease: f64,
        reuse: Option<&mut Reuse>,
    ) -> Self {
        let least_vertex = self
            .clearance
            .iter()
            .filter(|c| c.is_finite())
            .fold(f64::INFINITY, |a, &c| a.min(c.max(0.0)));
        let cap = ease.max(least_vertex);
        let free = self.free();
        self.near_faces = super::faces::faces_nearer(index, positions, triangles, (&free, &self.pierced), cap, reuse);
        self.face_clearance_m = self
            .near_faces
            .iter()
            .map(|&(_, d)| d)
            .fold(least_vertex.min(cap), f64::min);
        self
    }

    /// No vertex inside, no edge crossing and no face pierced.
    pub fn is_clear(&self) -> bool {
        self.penetrating_vertices == 0 && self.crossing_edges == 0 && self.pierced_faces == 0
    }

    /// How far from the surface each vertex stood at least, m (zero where not measured).
    pub fn free(&self) -> Vec<f64> {
        self.clearance
            .iter()
            .map(|c| if c.is_finite() { c.abs() } else { 0.0 })
            .collect()
    }

    /// The vertex distances this check measured, as [`Measured`] at `positions` (those it
    /// measured them at); a vertex it did not measure matches no position.
    pub fn measured(&self, positions: &[DVec3]) -> Measured {
        let at = positions
            .iter()
            .zip(&self.clearance)
            .map(|(&p, c)| if c.is_finite() { p } else { DVec3::NAN })
            .collect();
        let distance = self
            .clearance
            .iter()
            .zip(&self.nearest)
            .map(|(&signed, &triangle)| VertexDistance { signed, triangle })
            .collect();
        Measured { at, distance }
    }
}

impl Measured {
    /// The distance of vertex `v` at `p`, if measured there.
    pub fn distance(&self, v: usize, p: DVec3) -> Option<VertexDistance> {
        (self.at.get(v) == Some(&p)).then(|| self.distance[v])
    }

    /// How far from the surface each vertex stood at least, m.
    pub fn free(&self) -> Vec<f64> {
        self.distance.iter().map(|d| d.signed.abs()).collect()
    }
}

/// The quality check's distance of `p` (within a fifth of the body's height), searched up
/// from where this thread's last such search ended: the check asks vertex after vertex, so
/// that lies next to the answer (the same answer as a search from the root).
fn distance_at(index: &BodyIndex, p: DVec3) -> VertexDistance {
    VertexDistance::from_nearest(index, p, index.nearest_next(p, check_reach(index)).as_ref())
}

/// Every vertex's distance at `positions`, as the quality check measures it; those `reuse`
/// knows at the same position are taken from it (and not written to it).
pub fn measure_vertices(index: &BodyIndex, positions: &[DVec3], reuse: Option<&Reuse>) -> Measured {
    let mut known: Vec<Option<VertexDistance>> = positions
        .iter()
        .enumerate()
        .map(|(v, &p)| reuse.and_then(|r| r.distance(v, p)))
        .collect();
    let list: Vec<u32> = (0..positions.len() as u32)
        .filter(|&v| known[v as usize].is_none())
        .collect();
    let found = par_map(list.len(), |k| distance_at(index, positions[list[k] as usize]));
    for (&v, d) in list.iter().zip(found) {
        known[v as usize] = Some(d);
    }
    Measured {
        at: positions.to_vec(),
        distance: known.into_iter().flatten().collect(),
    }
}

/// Measures `positions` (with `edges`) against the body; `responses` give the ease error and
/// `before` (the positions before the response) the moves and stretches.
pub fn quality(
    index: &BodyIndex,
    before: &[DVec3],
    positions: &[DVec3],
    edges: &[[u32; 2]],
    responses: &[Response],
) -> Quality {
    let all: Vec<u32> = (0..positions.len() as u32).collect();
    quality_where(index, before, positions, &all, edges, responses, None)
}

/// [`quality`] over the vertices `vertices` and the edges `edges` only (the others are known:
/// M1's vertices and edges that are M0's, measured by M0's check). `inside` lists vertex
/// indices, `crossing` indices into `edges`; moves and stretches are over `vertices` and
/// `edges`. A vertex `measured` has at its position is not measured again.
pub fn quality_where(
    index: &BodyIndex,
    before: &[DVec3],
    positions: &[DVec3],
    vertices: &[u32],
    edges: &[[u32; 2]],
    responses: &[Response],
    measured: Option<&Measured>,
) -> Quality {
    measure(index, before, positions, vertices, edges, responses, None, measured)
}

/// [`quality`] measuring only what `reuse` does not know (vertices and edges at other
/// positions than when it was last measured) and what `measured` did not measure this step
/// at the same positions, and remembering both: the same figures as the full check, bit for
/// bit. (`counts` tells what came from earlier steps.)
#[allow(clippy::too_many_arguments)]
pub fn quality_reusing(
    index: &BodyIndex,
    before: &[DVec3],
    positions: &[DVec3],
    edges: &[[u32; 2]],
    responses: &[Response],
    reuse: &mut Reuse,
    counts: &mut Reused,
    measured: Option<&Measured>,
) -> Quality {
    let all: Vec<u32> = (0..positions.len() as u32).collect();
    measure(
        index,
        before,
        positions,
        &all,
        edges,
        responses,
        Some((reuse, counts)),
        measured,
    )
}

#[allow(clippy::too_many_arguments)]
fn measure(
    index: &BodyIndex,
    before: &[DVec3],
    positions: &[DVec3],
    vertices: &[u32],
    edges: &[[u32; 2]],
    responses: &[Response],
    mut reuse: Option<(&mut Reuse, &mut Reused)>,
    measured: Option<&Measured>,
) -> Quality {
    let reach = check_reach(index);
    let surface = SKIN * index.height;
    let mut q = Quality::default();
    let mut depth_sum = 0.0;
    // Distance to the body (`reach` where nothing is nearer) of the vertices measured and
    // the ends of the edges.
    let mut needed = vec![false; positions.len()];
    for &v in vertices.iter().chain(edges.iter().flatten()) {
        needed[v as usize] = true;
    }
    let mut signed = vec![reach; positions.len()];
    let mut nearest = vec![NO_TRIANGLE; positions.len()];
    let mut list: Vec<u32> = Vec::new();
    for v in 0..positions.len() {
        if !needed[v] {
            continue;
        }
        match reuse.as_ref().and_then(|(r, _)| r.distance(v, positions[v])) {
            Some(d) => (signed[v], nearest[v]) = (d.signed, d.triangle),
            None => list.push(v as u32),
        }
    }
    let found = par_map(list.len(), |k| {
        let v = list[k] as usize;
        let p = positions[v];
        measured
            .and_then(|m| m.distance(v, p))
            .unwrap_or_else(|| distance_at(index, p))
    });
    for (&v, s) in list.iter().zip(found) {
        (signed[v as usize], nearest[v as usize]) = (s.signed, s.triangle);
        if let Some((r, _)) = &mut reuse {
            r.set_distance(positions.len(), v as usize, positions[v as usize], s);
        }
    }
    if let Some((_, counts)) = &mut reuse {
        counts.vertices = needed.iter().filter(|n| **n).count() - list.len();
    }
    q.clearance = (0..positions.len())
        .map(|v| if needed[v] { signed[v] } else { f64::INFINITY })
        .collect();
    q.nearest = nearest;
    let mut measured: Vec<u32> = vertices.to_vec();
    measured.sort_unstable();
    measured.dedup();
    for &v in &measured {
        let (v, s) = (v as usize, signed[v as usize]);
        if s < -surface {
            q.penetrating_vertices += 1;
            q.max_depth_m = q.max_depth_m.max(-s);
            depth_sum += -s;
            q.inside.push(v as u32);
        }
    }
    if q.penetrating_vertices > 0 {
        q.mean_depth_m = depth_sum / q.penetrating_vertices as f64;
    }
    // An edge can meet the surface only if the balls free of it around its ends do not
    // cover it: |d(a)| + |d(b)| <= |ab|.
    let ends_at = |e: usize| edges[e].map(|v| positions[v as usize]);
    let known: Vec<Option<bool>> = match &mut reuse {
        Some((r, _)) => {
            r.begin_pass(positions, edges);
            (0..edges.len()).map(|e| r.check_verdict(e, edges[e])).collect()
        }
        None => vec![None; edges.len()],
    };
    let hits = par_map(edges.len(), |e| {
        known[e].unwrap_or_else(|| {
            let [a, b] = edges[e];
            let [pa, pb] = ends_at(e);
            signed[a as usize].abs() + signed[b as usize].abs() <= pa.distance(pb) && index.segment_hits(pa, pb)
        })
    });
    if let Some((r, counts)) = &mut reuse {
        counts.quality_edges = known.iter().filter(|k| k.is_some()).count();
        // Every edge gets this check's verdict: those it took still stand at the ends
        // they were given at, and those from a round become the check's own.
        for (e, hit) in hits.iter().enumerate() {
            r.set_crossing(e, *hit);
        }
    }
    for (e, hit) in hits.into_iter().enumerate() {
        if hit {
            q.crossing_edges += 1;
            q.crossing.push(e as u32);
        }
    }
    q.max_move_m = measured
        .iter()
        .map(|&v| before[v as usize].distance(positions[v as usize]))
        .fold(0.0, f64::max);
    q.max_stretch = edges
        .iter()
        .filter_map(|&[a, b]| {
            let was = before[a as usize].distance(before[b as usize]);
            (was > 0.0).then(|| positions[a as usize].distance(positions[b as usize]) / was)
        })
        .fold(1.0, f64::max);
    if !responses.is_empty() {
        let errs = responses.iter().map(|r| r.ease_error.abs());
        q.max_ease_error_m = errs.clone().fold(0.0, f64::max);
        q.mean_ease_error_m = errs.sum::<f64>() / responses.len() as f64;
    }
    q
}
