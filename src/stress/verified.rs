//! What `drape stress --verify` adds up over a session's collisions.

use serde::{Deserialize, Serialize};

use crate::collision::Misses;

/// The collisions of a session checked (`drape stress --verify`): detection and the quality
/// check against the brute-force ground truth, and the step's quality check (partial: only
/// what moved) against a full one of every vertex and edge, with the time of each.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
pub struct Verified {
    /// Collisions checked.
    pub collisions: usize,
    /// Garment vertices and edges checked, summed over them.
    pub vertices: usize,
    /// Garment edges checked, summed.
    pub edges: usize,
    /// Vertices inside before the response (the truth), summed.
    #[serde(default)]
    pub inside: usize,
    /// Vertices inside before the response that detection did not report.
    pub missed: usize,
    /// The missed by cause.
    #[serde(default)]
    pub missed_by: Misses,
    /// Verdicts the inert and patch skips changed (against a detection testing every vertex).
    #[serde(default)]
    pub skips_changed: usize,
    /// Vertices detection reported that were not inside.
    pub false_hits: usize,
    /// Steps whose quality check did not find exactly the truth's inside vertices and
    /// crossing edges.
    pub wrong_quality: Vec<usize>,
    /// Steps whose quality check differed in anything from a full one.
    pub partial_differs: Vec<usize>,
    /// The step's quality check, ms, per collision.
    pub quality_ms: Vec<f64>,
    /// The full check of the same positions, ms, per collision.
    pub full_quality_ms: Vec<f64>,
}

impl Verified {
    /// Adds the collisions of `other`.
    pub fn absorb(&mut self, other: Verified) {
        self.collisions += other.collisions;
        self.vertices += other.vertices;
        self.edges += other.edges;
        self.inside += other.inside;
        self.missed += other.missed;
        self.missed_by.add(&other.missed_by);
        self.skips_changed += other.skips_changed;
        self.false_hits += other.false_hits;
        self.wrong_quality.extend(other.wrong_quality);
        self.partial_differs.extend(other.partial_differs);
        self.quality_ms.extend(other.quality_ms);
        self.full_quality_ms.extend(other.full_quality_ms);
    }
}
