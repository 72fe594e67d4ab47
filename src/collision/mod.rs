//! Mesh-layer collision of the garment with the body (\[collide\] sections 4 and 5):
//! partitioned detection (point-face or line-line by partition, BVH, inert points, patch
//! skipping), the response along each partition's constrained direction, the quality
//! measured afterwards, and the brute-force ground truth.
//!
//! Data flow of one step: [`GarmentMesh::from_framework`] (M0 with the roles the rules
//! read) -> [`detect()`] (hits, with [`DetectState`] carried between steps) -> [`respond()`]
//! (moved vertices and the rule of each) -> [`respond_edges`] (edges through the body
//! lifted) -> [`respond_faces`] (faces the body pokes through lifted, then the edges at
//! their corners) -> [`quality()`] and [`Quality::with_faces`] (what is left inside,
//! crossing edges, pierced faces, ease error): the whole surface certified. The body side
//! is built once per body and shared with the garment:
//! [`BodyIndex::new`] (in [`crate::body::index`]).

pub mod detect;
pub mod edges;
pub mod faces;
pub mod line_line;
pub mod point_face;
pub mod poke;
mod push;
pub mod quality;
pub mod response;
pub mod reuse;
pub mod types;
pub mod verify;

use std::collections::BTreeMap;

use glam::DVec3;

pub use crate::body::index::{BodyIndex, Nearest, PartitionIndex};
pub use crate::body::slices::{CentreChoice, Centres, SliceOptions, SliceStack};
pub use detect::{Acceleration, DetectOptions, DetectState, Detection, GarmentInput, Skip, detect};
pub use edges::{KnownClearance, respond_edges};
pub use faces::{pierced_faces, respond_faces};
pub use point_face::{PointFace, Reach, Search, point_face};
pub use quality::{Quality, quality, quality_reusing};
pub use response::{AppliedRule, Response, ResponseOptions, VertexRoles, respond, response_ease};
pub use reuse::{Reuse, Reused};
pub use types::{Hit, SKIN, VertexDistance};
pub use verify::{GroundTruth, Misses, VerifyReport, changed_verdicts, compare, ground_truth};

use crate::garment::{CurveRef, Framework};
use crate::mesh::TriMesh;

/// All collision settings.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct CollisionOptions {
    /// Detection.
    pub detect: DetectOptions,
    /// Response.
    pub response: ResponseOptions,
    /// Body slices.
    pub slices: SliceOptions,
    /// Measure the quality of every vertex and edge, and test every edge in the first edge
    /// round, each step (`--quality full`). Default value: false: only the
    /// vertices and edges whose positions changed since they were last measured (see
    /// [`reuse`]); the figures are the same.
    pub full_quality: bool,
}

/// M0 with what detection and response need to know about each vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct GarmentMesh {
    /// The mesh.
    pub mesh: TriMesh,
    /// The patch of each face (shared with M0, like the edges and the openings).
    pub face_patch: std::sync::Arc<Vec<u32>>,
    /// Undirected edges.
    pub edges: std::sync::Arc<Vec<[u32; 2]>>,
    /// Unit vertex normals (area-weighted mean of the incident face normals, world frame).
    pub normals: Vec<DVec3>,
    /// Vertices on an opening.
    pub boundary: std::sync::Arc<Vec<bool>>,
    /// For vertices on a garment ring, the ring plane's normal.
    pub ring_normal: Vec<Option<DVec3>>,
    /// Patches of each vertex, ascending (shared with M0, and by the meshes of the same
    /// faces).
    pub vertex_patches: std::sync::Arc<Vec<Vec<u32>>>,
    /// Curves of each patch.
    pub patch_curves: Vec<Vec<CurveRef>>,
    /// Control points of every curve.
    pub controls: BTreeMap<String, Vec<DVec3>>,
}

impl GarmentMesh {
    /// From M0 of a framework on a body of height `height`.
    pub fn from_framework(fw: &Framework, height: f64) -> Self {
        let m0 = &fw.m0;
        // Openings: the ends of edges with a face on one side only (found with M0's faces).
        let boundary = std::sync::Arc::clone(&m0.boundary);
        let tol = 1e-9 * height;
        let ring_normal = m0
            .mesh
            .positions
            .iter()
            .map(|p| {
                fw.rings
                    .iter()
                    .find(|r| r.plane.signed_distance(*p).abs() <= tol)
                    .map(|r| r.plane.normal)
            })
            .collect();
        let patch_curves = m0
            .patch_names
            .iter()
            .map(|name| {
                fw.patches
                    .iter()
                    .find(|p| &p.name == name)
                    .map_or_else(Vec::new, |p| p.curves.clone())
            })
            .collect();
        Self {
            normals: m0.mesh.vertex_normals(),
            mesh: m0.mesh.clone(),
            face_patch: std::sync::Arc::clone(&m0.face_patch),
            edges: std::sync::Arc::clone(&m0.edges),
            boundary,
            ring_normal,
            vertex_patches: std::sync::Arc::clone(&m0.vertex_patches),
            patch_curves,
            controls: fw.curve_controls(),
        }
    }

    /// The view detection reads.
    pub fn input(&self) -> GarmentInput<'_> {
        GarmentInput {
            positions: &self.mesh.positions,
            normals: &self.normals,
            edges: &self.edges,
            vertex_patches: &self.vertex_patches,
            patch_curves: &self.patch_curves,
            controls: &self.controls,
        }
    }

    /// The roles response reads.
    pub fn roles(&self) -> VertexRoles<'_> {
        VertexRoles {
            normals: &self.normals,
            boundary: &self.boundary,
            ring_normal: &self.ring_normal,
            pinned: &[],
        }
    }
}

/// Compute time of each phase of a collision, ms (wall clock: for metrics, never logged
/// into compared data).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CollisionTimings {
    /// Detection, ms.
    pub detect: f64,
    /// Vertex response, ms.
    pub respond: f64,
    /// Edge rounds, ms.
    pub respond_edges: f64,
    /// The quality check of vertices and edges, ms.
    pub quality: f64,
    /// Face rounds (and the edge rounds at the corners they lift), ms.
    pub respond_faces: f64,
    /// The quality check of the faces, ms.
    pub check_faces: f64,
    /// The faces' clearance, ms.
    pub face_clearance: f64,
}

/// One step's collision of a garment mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    /// What detection found.
    pub detection: Detection,
    /// The ease responses stand off at, m.
    pub ease: f64,
    /// What response did: penetrating vertices by vertex, then the edge rounds.
    pub responses: Vec<Response>,
    /// Edges crossing the body at the start of each edge round (the first: after the
    /// vertex response).
    pub edge_rounds: Vec<usize>,
    /// Faces pierced by the body at the start of each face round (see [`faces`]).
    pub face_rounds: Vec<usize>,
    /// The faces pierced after the edge rounds, before the face rounds lifted them:
    /// those the first face round found, and those a check before found pierced and whose
    /// corners have not moved since.
    pub pierced_before_rounds: Vec<u32>,
    /// The edges (their ends) crossing the body after the vertex response, before the edge
    /// rounds lifted them.
    pub crossing_before_rounds: Vec<[u32; 2]>,
    /// The mesh after response.
    pub mesh: TriMesh,
    /// Quality after response.
    pub quality: Quality,
    /// Compute time per phase.
    pub timings: CollisionTimings,
    /// What the edge rounds and the quality check took from the last steps.
    pub reused: Reused,
}

fn timed<T>(slot: &mut f64, f: impl FnOnce() -> T) -> T {
    let start = std::time::Instant::now();
    let out = f();
    *slot = start.elapsed().as_secs_f64() * 1e3;
    out
}

/// Detects, responds (vertices, then edge rounds) and measures the quality.
pub fn collide(
    index: &BodyIndex,
    garment: &GarmentMesh,
    garment_ease: f64,
    options: &CollisionOptions,
    state: &mut DetectState,
) -> Collision {
    let mut timings = CollisionTimings::default();
    let detection = timed(&mut timings.detect, || {
        detect(index, &garment.input(), &options.detect, state)
    });
    let ease = response_ease(index, garment_ease, &options.response);
    let roles = garment.roles();
    let (mut positions, mut responses) = timed(&mut timings.respond, || {
        respond(
            index,
            &garment.mesh.positions,
            &detection.hits,
            &roles,
            ease,
            &options.response,
        )
    });
    // The full check forgets what earlier steps measured, so it measures everything (and
    // remembers it for the next step).
    let mut reused = Reused::default();
    if options.full_quality {
        state.reuse.clear();
    }
    // Every vertex's distance after the vertex response (those not known from earlier
    // steps): the edge rounds test no edge its ends' distances show clear, and
    // the quality check takes the distances of the vertices the rounds leave in place.
    let measured = timed(&mut timings.respond_edges, || {
        quality::measure_vertices(index, &positions, Some(&state.reuse))
    });
    let free = measured.free();
    let known = KnownClearance {
        at: &measured.at,
        free: &free,
    };
    let mut rounds_ms = 0.0;
    let (edge_responses, edge_rounds, first_round) = timed(&mut rounds_ms, || {
        respond_edges(
            index,
            &mut positions,
            &garment.edges,
            &detection.partition,
            &roles,
            ease,
            &options.response,
            Some((&mut state.reuse, &mut reused)),
            Some(known),
        )
    });
    timings.respond_edges += rounds_ms;
    responses.extend(edge_responses);
    let triangles = &garment.mesh.triangles;
    let (face_rounds, pierced_before_rounds) = timed(&mut timings.respond_faces, || {
        let known = KnownClearance {
            at: &measured.at,
            free: &free,
        };
        let rounds = step_face_rounds(
            index,
            (garment, &mut positions),
            (&detection.partition, &roles),
            ease,
            &options.response,
            (&mut state.reuse, known),
        );
        responses.extend(rounds.lifts);
        (rounds.found, rounds.first)
    });
    if options.full_quality {
        // Nor what the edge rounds just found.
        state.reuse.clear();
    }
    let quality = timed(&mut timings.quality, || {
        quality_reusing(
            index,
            &garment.mesh.positions,
            &positions,
            &garment.edges,
            &responses,
            &mut state.reuse,
            &mut reused,
            Some(&measured),
        )
    });
    let quality = timed(&mut timings.check_faces, || {
        quality.with_faces(index, &positions, triangles, Some(&mut state.reuse))
    });
    let quality = timed(&mut timings.face_clearance, || {
        quality.with_face_clearance(index, &positions, triangles, ease, Some(&mut state.reuse))
    });
    Collision {
        detection,
        ease,
        responses,
        edge_rounds,
        face_rounds,
        pierced_before_rounds,
        crossing_before_rounds: first_round,
        mesh: TriMesh {
            positions,
            triangles: garment.mesh.triangles.clone(),
        },
        quality,
        timings,
        reused,
    }
}

/// The face rounds of a step on `positions` (the garment after its vertex and edge
/// responses): the faces the step's rounds have not tested, or whose corners moved since a
/// check found them clear, lifted where pierced; the first round's verdicts kept in `reuse`.
fn step_face_rounds(
    index: &BodyIndex,
    (garment, positions): (&GarmentMesh, &mut [DVec3]),
    (partition, roles): (&[usize], &VertexRoles<'_>),
    ease: f64,
    options: &ResponseOptions,
    (reuse, known): (&mut Reuse, KnownClearance<'_>),
) -> faces::FaceRounds {
    let triangles = &garment.mesh.triangles;
    reuse.begin_pass(positions, &garment.edges);
    reuse.begin_faces(triangles);
    let check: Vec<u32> = (0..triangles.len() as u32)
        .filter(|&f| reuse.face(f as usize, triangles[f as usize]) != Some(false))
        .collect();
    let rounds = respond_faces(
        index,
        positions,
        (triangles, &garment.edges),
        check.clone(),
        partition,
        roles,
        ease,
        options,
        Some(known),
    );
    // The first round's verdicts, at the pass begun before it (a face whose corners
    // the rounds move since is tested again by the check).
    for &f in &check {
        reuse.set_face(f as usize, rounds.first.binary_search(&f).is_ok());
    }
    rounds
}
