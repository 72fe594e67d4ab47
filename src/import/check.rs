//! Checking and repairing a garment from a file: the exact counts before, the collision
//! layers (detection by partition, response by partition rules, edge and face rounds), the
//! exact counts after, and what the user's file becomes.

use std::collections::BTreeMap;

use glam::DVec3;
use serde::Serialize;

use super::garment::{ImportNotes, ImportedGarment};
use crate::collision::BodyIndex;
use crate::collision::{Collision, CollisionOptions, DetectState, Quality, collide, quality};

/// Check settings.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckOptions {
    /// The gap a repaired vertex stands off the skin, m (default 0.002: a thin fabric).
    pub ease: f64,
    /// The collision layers' settings (default: drape's).
    pub collision: CollisionOptions,
}

impl Default for CheckOptions {
    fn default() -> Self {
        Self {
            ease: 0.002,
            collision: CollisionOptions::default(),
        }
    }
}

/// Counts in one body region (partition A-G).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct RegionCounts {
    /// Vertices inside.
    pub inside: usize,
    /// Edges crossing the skin.
    pub crossing: usize,
    /// Faces a body edge passes through.
    pub pierced: usize,
}

/// The exact state of a garment against the body.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Counts {
    /// Garment vertices inside the body.
    pub inside_vertices: usize,
    /// Garment edges crossing the body's surface.
    pub crossing_edges: usize,
    /// Garment faces a body edge passes through.
    pub pierced_faces: usize,
    /// The deepest vertex inside, m (0 when none), and where it is (the file's vertex,
    /// 1-based, and its position, m).
    pub deepest_m: f64,
    /// The deepest vertex (1-based, as in the file) and its position.
    pub deepest_at: Option<(usize, [f64; 3])>,
    /// The least signed distance of a vertex to the skin, m (negative inside).
    pub vertex_clearance_m: f64,
    /// The least distance of any point of a face to the skin, m (0 where one is pierced).
    pub face_clearance_m: f64,
    /// The counts by body region (partition letter), regions with none left out.
    pub regions: BTreeMap<&'static str, RegionCounts>,
}

impl Counts {
    /// No vertex inside, no edge crossing, no face pierced.
    pub fn is_clear(&self) -> bool {
        self.inside_vertices == 0 && self.crossing_edges == 0 && self.pierced_faces == 0
    }

    fn new(q: &Quality, index: &BodyIndex, partition: &[usize], garment: &ImportedGarment) -> Self {
        let m = &garment.mesh;
        let letter = |v: u32| {
            partition
                .get(v as usize)
                .and_then(|&k| index.partitions.get(k))
                .map_or("?", |p| p.id.letter())
        };
        let mut regions: BTreeMap<&'static str, RegionCounts> = BTreeMap::new();
        for &v in &q.inside {
            regions.entry(letter(v)).or_default().inside += 1;
        }
        for &e in &q.crossing {
            regions.entry(letter(m.edges[e as usize][0])).or_default().crossing += 1;
        }
        for &f in &q.pierced {
            regions
                .entry(letter(m.mesh.triangles[f as usize][0]))
                .or_default()
                .pierced += 1;
        }
        let deepest = q
            .inside
            .iter()
            .map(|&v| (v, q.clearance.get(v as usize).copied().unwrap_or(0.0)))
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        let file_vertex = |v: u32| garment.to_mesh.iter().position(|&x| x == v).map_or(0, |i| i + 1);
        Self {
            inside_vertices: q.penetrating_vertices,
            crossing_edges: q.crossing_edges,
            pierced_faces: q.pierced_faces,
            deepest_m: deepest.map_or(0.0, |(_, d)| -d.min(0.0)),
            deepest_at: deepest.map(|(v, _)| (file_vertex(v), m.mesh.positions[v as usize].to_array())),
            vertex_clearance_m: q
                .clearance
                .iter()
                .filter(|c| c.is_finite())
                .fold(f64::INFINITY, |a, &c| a.min(c)),
            face_clearance_m: q.face_clearance_m,
            regions,
        }
    }
}

/// How a check ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The garment was clear as read.
    Clear,
    /// It was not, and the repair left it clear.
    Repaired,
    /// The repair could not clear it.
    NotClear,
}

impl Status {
    /// The process exit code `drape check-garment` gives: 0 clear, 1 repaired, 4 not.
    pub fn exit_code(self) -> u8 {
        match self {
            Self::Clear => 0,
            Self::Repaired => 1,
            Self::NotClear => 4,
        }
    }
}

/// Compute times, ms (wall clock: never in compared data).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct CheckTimings {
    /// The counts before.
    pub before_ms: f64,
    /// Detection, response and the exact check after.
    pub repair_ms: f64,
}

/// What a check found and did.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CheckReport {
    /// The file's name.
    pub file: String,
    /// What reading it found and repaired.
    pub notes: ImportNotes,
    /// The garment as read.
    pub before: Counts,
    /// After the repair.
    pub after: Counts,
    /// File vertices the repair moved, and the farthest move, m.
    pub moved_vertices: usize,
    /// The farthest move, m.
    pub max_move_m: f64,
    /// The ease the repair stood vertices off at, m.
    pub ease_m: f64,
    /// The outcome.
    pub status: Status,
    /// Compute times.
    pub timings: CheckTimings,
}

/// A check's result: the report, the collision (for the recording), and the file's
/// vertices after the repair with which of them moved.
#[derive(Clone, Debug)]
pub struct Checked {
    /// The report.
    pub report: CheckReport,
    /// The collision of the garment.
    pub collision: Collision,
    /// The file's vertex positions after the repair (as read when the garment was clear).
    pub positions: Vec<DVec3>,
    /// Which file vertices moved.
    pub moved: Vec<bool>,
}

/// Counts, repairs and counts again.
pub fn check(garment: &ImportedGarment, index: &BodyIndex, options: &CheckOptions) -> Checked {
    let m = &garment.mesh;
    let start = std::time::Instant::now();
    let pos = &m.mesh.positions;
    let before_q = quality(index, pos, pos, &m.edges, &[])
        .with_faces(index, pos, &m.mesh.triangles, None)
        .with_face_clearance(index, pos, &m.mesh.triangles, options.ease, None);
    let before_ms = start.elapsed().as_secs_f64() * 1e3;
    let start = std::time::Instant::now();
    let mut state = DetectState::default();
    let collision = collide(index, m, options.ease, &options.collision, &mut state);
    let repair_ms = start.elapsed().as_secs_f64() * 1e3;
    let partition = &collision.detection.partition;
    let before = Counts::new(&before_q, index, partition, garment);
    // A garment clear as read is kept as read: its counts after are its counts before.
    let after = if before.is_clear() {
        before.clone()
    } else {
        Counts::new(&collision.quality, index, partition, garment)
    };
    let (status, (positions, moved)) = if before.is_clear() {
        (Status::Clear, garment.file_positions(pos))
    } else if after.is_clear() {
        (Status::Repaired, garment.file_positions(&collision.mesh.positions))
    } else {
        (Status::NotClear, garment.file_positions(&collision.mesh.positions))
    };
    let max_move_m = garment
        .doc
        .contents
        .positions
        .iter()
        .zip(&positions)
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    let report = CheckReport {
        file: garment.doc.name.clone(),
        notes: garment.notes.clone(),
        before,
        after,
        moved_vertices: moved.iter().filter(|m| **m).count(),
        max_move_m,
        ease_m: collision.ease,
        status,
        timings: CheckTimings { before_ms, repair_ms },
    };
    Checked {
        report,
        collision,
        positions,
        moved,
    }
}
