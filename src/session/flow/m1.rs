//! M1 at the end of every step that collides M0 (garment, set, drag; `undo` emits it again):
//! the patches selected, the sqrt(3) refinement, M1's own collision, the cut lines rebuilt
//! on it, and their figures. Runs only when the scene has an `m1` statement.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::body::Body;
use crate::collision::BodyIndex;
use crate::m1::{self, M0Collided, M1Options, SelectInput, SelectMemory, Selection, cut};
use crate::session::emit::StepScope;
use crate::session::options::RunOptions;
use crate::session::stage::{M1Outcome, M1Stage, Stage};
use crate::session::state::GarmentState;

/// The figures of M1.
#[derive(Serialize)]
struct M1Figures<'a> {
    /// M1's vertices and faces.
    m1_vertices: usize,
    m1_faces: usize,
    /// Refined patches: `total`, and per rule the patches it selected (a patch may be
    /// selected by several).
    m1_patches_refined: BTreeMap<&'static str, usize>,
    /// Vertices M1's collision tested (those M0 does not have).
    m1_new_vertices_tested: usize,
    /// Of those, inside the body before M1's response.
    m1_hits: usize,
    /// M1's edges crossing the body before its response.
    m1_crossing_edges_before: usize,
    /// Crossing edges at the start of each of M1's edge rounds.
    m1_crossing_edges_by_round: &'a [usize],
    /// Moves M1's response made.
    m1_responses: usize,
    /// After M1's response, by the exact check over all of M1.
    m1_penetrating_vertices: usize,
    m1_crossing_edges: usize,
    /// M1's faces the body pierced before its face rounds, and after its response.
    m1_pierced_faces_before: usize,
    m1_pierced_faces: usize,
    /// Pierced faces at the start of each of M1's face rounds.
    m1_pierced_faces_by_round: &'a [usize],
    /// Cut lines rebuilt on M1.
    m1_cut_lines: usize,
    /// With `--verify`: M1 after its collision by brute force (winding number for every
    /// vertex, every edge against every body triangle).
    #[serde(skip_serializing_if = "Option::is_none")]
    m1_verify: Option<M1Verify>,
}

/// M1 by brute force.
#[derive(Serialize)]
struct M1Verify {
    inside: usize,
    crossing: usize,
    pierced: usize,
}

/// Builds and collides M1 over the state's collided M0, and rebuilds the cut lines on it.
pub(in crate::session) fn build_m1(
    scope: &mut StepScope<'_, '_, '_>,
    body: &Body,
    index: &BodyIndex,
    state: &mut GarmentState,
    options: &RunOptions,
    m1_options: &M1Options,
) {
    let (Some(ease), Some(outcome)) = (state.ease(), &state.collision) else {
        return;
    };
    let m0 = &outcome.collision.mesh;
    let face_patch = &outcome.garment.face_patch;
    let patches = state.patch_count();
    // The last selection's memory, taken (and dropped once read: it is replaced).
    let last = state.m0_select.take().filter(|_| !options.full_m1);
    let (measured, selection, memory) = scope.timed("m1.select", || {
        // M0's distances as its quality check measured them: the selection and M1's check
        // read them.
        let measured = outcome.collision.quality.measured(&m0.positions);
        let input = SelectInput {
            mesh: m0,
            face_patch,
            patches,
            standard: state.standard.as_ref().map(|s| s.as_slice()),
            measured: Some(&measured),
            edges: None,
        };
        let (selection, memory) = select_patches(input, last.as_deref(), index, m1_options);
        (measured, selection, std::sync::Arc::new(memory))
    });
    drop(last);
    let edges = std::sync::Arc::clone(memory.edges());
    state.m0_select = Some(memory);
    let previous = state.m1_shape.as_ref().filter(|_| !options.full_m1);
    let (built, shape, made) = scope.timed("m1.subdivide", || {
        m1::subdivide(m0, &edges, face_patch, selection, m1_options, previous)
    });
    state.m1_shape = shape;
    let m0_crossing: Vec<[u32; 2]> = outcome
        .collision
        .quality
        .crossing
        .iter()
        .map(|&e| outcome.garment.edges[e as usize])
        .collect();
    let collided = M0Collided {
        measured: Some(&measured),
        inside: &outcome.collision.quality.inside,
        crossing: &m0_crossing,
        triangles: &m0.triangles,
        pierced: &outcome.collision.quality.pierced,
        partition: &outcome.collision.detection.partition,
        ring_normal: &outcome.garment.ring_normal,
    };
    let reuse = state.m1_reuse.as_deref().filter(|_| !options.full_m1);
    let (collision, reuse, patches_collided) = scope.timed("m1.collide", || {
        let shape = state.m1_shape.as_ref();
        m1::collide_m1_patches(index, &built, &collided, ease, &options.collision, reuse, shape)
    });
    state.m1_reuse = Some(std::sync::Arc::new(reuse));
    let (cuts, cuts_on_m0) = scope.timed("m1.cuts", || {
        let on_m1 = state
            .cuts
            .iter()
            .map(|c| cut::rebuild(Some(&built), &m0.triangles, &collision.positions, c))
            .collect();
        let on_m0 = state
            .cuts
            .iter()
            .map(|c| cut::rebuild(None, &m0.triangles, &m0.positions, c))
            .collect();
        (on_m1, on_m0)
    });
    let verify = options.verify.then(|| {
        scope.timed("m1.verify", || {
            let truth = crate::collision::ground_truth(&body.mesh.mesh, &collision.positions, built.edges())
                .with_faces(&body.mesh.mesh, &collision.positions, &built.mesh.triangles);
            M1Verify {
                inside: truth.inside_count(),
                crossing: truth.crossing_count(),
                pierced: truth.pierced_count(),
            }
        })
    });
    let mut refined = built.selection.by_rule();
    refined.insert("total", built.selection.count());
    scope.record(&M1Figures {
        m1_vertices: built.mesh.positions.len(),
        m1_faces: built.mesh.triangles.len(),
        m1_patches_refined: refined,
        m1_new_vertices_tested: collision.tested,
        m1_hits: collision.hits,
        m1_crossing_edges_before: collision.crossing_before,
        m1_crossing_edges_by_round: &collision.edge_rounds,
        m1_responses: collision.responses.len(),
        m1_penetrating_vertices: collision.quality.penetrating_vertices,
        m1_crossing_edges: collision.quality.crossing_edges,
        m1_pierced_faces_before: collision.pierced_before,
        m1_pierced_faces: collision.quality.pierced_faces,
        m1_pierced_faces_by_round: &collision.face_rounds,
        m1_cut_lines: state.cuts.len(),
        m1_verify: verify,
    });
    record_m1_work(scope, patches_collided, made);
    state.m1 = Some(M1Outcome {
        m1: built,
        collision,
        stored: state.cuts.clone(),
        cuts,
        cuts_on_m0,
    });
}

/// The metrics' `work` of M1's build: the refined patches collided at this step (and the
/// vertices they tested) and those taken unchanged from the step before; 1 when M1's shape
/// was kept from the step before (only its vertices placed again), 1 when it was read from
/// the step over every patch.
fn record_m1_work(scope: &mut StepScope<'_, '_, '_>, patches_collided: m1::PatchCounts, made: m1::Made) {
    for (name, count) in [
        ("m1.patches_collided", patches_collided.collided),
        ("m1.patches_kept", patches_collided.kept),
        ("m1.vertices_collided", patches_collided.tested),
        ("m1.shape_kept", usize::from(made == m1::Made::ShapeKept)),
        ("m1.every_patch", usize::from(made == m1::Made::EveryPatch)),
    ] {
        let key = scope.timing_key(name);
        scope.metrics.record_work(key, count);
    }
}

/// The patches M1 refines, and what the selection read and found, patch by patch, for the
/// next step (with M0's edges and their faces: `last`'s while M0's faces are those they were
/// found in, as M1's shape is kept only with the same edges).
fn select_patches(
    input: SelectInput<'_>,
    last: Option<&SelectMemory>,
    index: &BodyIndex,
    m1_options: &M1Options,
) -> (Selection, SelectMemory) {
    let (selection, memory) = m1::select_keeping(&input, index, &m1_options.select, last);
    if m1_options.all_patches {
        (Selection::all(input.patches), memory)
    } else {
        (selection, memory)
    }
}

/// Emits the state's M1, if it has one.
pub(in crate::session) fn emit_m1(scope: &mut StepScope<'_, '_, '_>, state: &GarmentState) {
    if let (Some(outcome), Some(m0)) = (&state.m1, &state.collision) {
        scope.emit("garment.m1", Stage::M1(M1Stage { outcome, m0 }));
    }
}
