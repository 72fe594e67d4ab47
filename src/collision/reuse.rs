//! What a collision remembers between steps so that it measures only what a step could
//! have changed: the signed distance of each vertex where the quality check last measured
//! it, and for each edge whether it crossed the body at the ends it had when last tested
//! (by the quality check, and by the first edge round, whose tests differ).
//!
//! A remembered answer is used only where the positions are the same, bit for bit: a
//! distance and a crossing depend on nothing else (the body is fixed for a session), so
//! the answers are exactly those a full check gives. An edit moves only the patches whose
//! curves changed, and the response moves only the vertices near the body, so most of a
//! garment is the same from step to step.

use glam::DVec3;

use super::quality::VertexDistance;

/// Remembered answers, by vertex and by edge (the same garment topology).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Reuse {
    /// Per vertex: where its distance was measured, and the distance.
    distance: Vec<Option<(DVec3, VertexDistance)>>,
    /// Per edge: its ends when the quality check tested it, and whether it met the body.
    crossing: Vec<Option<([DVec3; 2], bool)>>,
    /// Per edge: its ends when the first edge round tested it; it did not cross then.
    clear_in_round: Vec<Option<[DVec3; 2]>>,
}

/// How much a step took from [`Reuse`] (for the metrics).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Reused {
    /// Vertices whose signed distance was not measured again.
    pub vertices: usize,
    /// Edges the quality check did not test again.
    pub quality_edges: usize,
    /// Edges the first edge round did not test again.
    pub round_edges: usize,
}

impl Reuse {
    /// Forgets everything (the full check: everything is measured again).
    pub fn clear(&mut self) {
        *self = Self::default();
    }

    /// The distance of vertex `v` at `p`, if it was measured there.
    pub fn distance(&self, v: usize, p: DVec3) -> Option<VertexDistance> {
        match self.distance.get(v) {
            Some(Some((at, s))) if *at == p => Some(*s),
            _ => None,
        }
    }

    /// Whether edge `e` with ends `ends` meets the body, if it was tested there.
    pub fn crossing(&self, e: usize, ends: [DVec3; 2]) -> Option<bool> {
        match self.crossing.get(e) {
            Some(Some((at, hit))) if *at == ends => Some(*hit),
            _ => None,
        }
    }

    /// Whether the first edge round found edge `e` clear of the body at these ends.
    pub fn clear_in_round(&self, e: usize, ends: [DVec3; 2]) -> bool {
        matches!(self.clear_in_round.get(e), Some(Some(at)) if *at == ends)
    }

    /// Remembers the distance of vertex `v` at `p`.
    pub fn set_distance(&mut self, vertices: usize, v: usize, p: DVec3, s: VertexDistance) {
        if self.distance.len() != vertices {
            self.distance = vec![None; vertices];
        }
        self.distance[v] = Some((p, s));
    }

    /// Remembers whether edge `e` at `ends` meets the body.
    pub fn set_crossing(&mut self, edges: usize, e: usize, ends: [DVec3; 2], hit: bool) {
        if self.crossing.len() != edges {
            self.crossing = vec![None; edges];
        }
        self.crossing[e] = Some((ends, hit));
    }

    /// Remembers the first edge round's verdict on edge `e` at `ends`.
    pub fn set_round(&mut self, edges: usize, e: usize, ends: [DVec3; 2], clear: bool) {
        if self.clear_in_round.len() != edges {
            self.clear_in_round = vec![None; edges];
        }
        self.clear_in_round[e] = clear.then_some(ends);
    }
}
