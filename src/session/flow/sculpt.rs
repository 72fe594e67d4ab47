//! Sculpts made on the garment's latest mesh: the mesh a sculpt starts from, its pick
//! resolved, the push or pull made and collided, its figures; and the sculpts made again
//! after every rebuild (`remake`), which the collision flow calls.

use crate::collision::{BodyIndex, CollisionOptions, response_ease};
use crate::m1::{M0Collided, RefinedInput, collide_refined, partition_through};
use crate::mesh::TriMesh;
use crate::mesh::topology::undirected_edges;
use crate::sculpt::{Drag, SculptError, SculptOptions, measure};
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::format::SculptAt;
use crate::session::stage::{SculptOutcome, SculptStage, Stage};
use crate::session::state::GarmentState;
use glam::DVec3;
use serde::Serialize;

/// The mesh a sculpt is made on, collided, with what its collision left.
pub(in crate::session) struct Base {
    layer: &'static str,
    mesh: TriMesh,
    partition: Vec<usize>,
    ring_normal: Vec<Option<DVec3>>,
    pub(in crate::session) inside: Vec<u32>,
    pub(in crate::session) crossing: Vec<[u32; 2]>,
    /// Its faces the body pierced (indices into `mesh.triangles`).
    pub(in crate::session) pierced: Vec<u32>,
}

/// The garment's latest mesh: the last sculpt, else M1, else M0 (`None` before a garment
/// is collided).
pub(in crate::session) fn base(state: &GarmentState) -> Option<Base> {
    if let Some(s) = &state.sculpted {
        return Some(Base {
            layer: "sculpt",
            mesh: s.mesh(),
            partition: s.partition.clone(),
            ring_normal: s.ring_normal.clone(),
            inside: s.collision.inside_after.clone(),
            crossing: s.collision.crossing_after_edges.clone(),
            pierced: s.collision.pierced_after.clone(),
        });
    }
    let m0 = state.collision.as_ref()?;
    let partition = &m0.collision.detection.partition;
    if let Some(m1) = &state.m1 {
        let n = m1.collision.positions.len();
        let mut ring_normal = m0.garment.ring_normal.clone();
        ring_normal.resize(n, None);
        return Some(Base {
            layer: "M1",
            mesh: TriMesh {
                positions: m1.collision.positions.clone(),
                triangles: m1.m1.mesh.triangles.clone(),
            },
            partition: partition_through(&m1.m1.anchor, partition),
            ring_normal,
            inside: m1.collision.inside_after.clone(),
            crossing: m1.collision.crossing_after_edges.clone(),
            pierced: m1.collision.pierced_after.clone(),
        });
    }
    Some(Base {
        layer: "M0",
        mesh: m0.collision.mesh.clone(),
        partition: partition.clone(),
        ring_normal: m0.garment.ring_normal.clone(),
        inside: m0.collision.quality.inside.clone(),
        crossing: m0
            .collision
            .quality
            .crossing
            .iter()
            .map(|&e| m0.garment.edges[e as usize])
            .collect(),
        pierced: m0.collision.quality.pierced.clone(),
    })
}

/// The pick point of `at` on the garment `state` (a control point where it now stands).
pub(in crate::session) fn resolve(state: &GarmentState, at: &SculptAt) -> Result<DVec3, StepError> {
    match at {
        SculptAt::Point(p) => Ok(*p),
        SculptAt::Control(name) => state
            .framework
            .as_ref()
            .and_then(|fw| fw.control_points().into_iter().find(|(n, _)| n == name))
            .map(|(_, p)| p)
            .ok_or_else(|| StepError::NoControlPoint(name.clone())),
    }
}

/// Makes one sculpt on `base` and collides it.
pub(in crate::session) fn apply(
    scope: &mut StepScope<'_, '_, '_>,
    base: Base,
    (drag, options): (&Drag, &SculptOptions),
    index: &BodyIndex,
    ease: f64,
    collision: &CollisionOptions,
    count: usize,
) -> Result<SculptOutcome, SculptError> {
    // A vertex must not end inside the body or nearer to it than the response's ease.
    let stand_off = response_ease(index, ease, &collision.response);
    let reach = 0.2 * index.height;
    let keep_out = |p: DVec3| index.nearest(p, reach).is_some_and(|n| n.signed(p) < stand_off);
    let sculpt = scope.timed("sculpt.refine", || {
        crate::sculpt::sculpt_clear_of(&base.mesh, drag, options, Some(&keep_out))
    })?;
    let refined = &sculpt.refined;
    let mut moved: Vec<u32> = sculpt.displacement.offsets.iter().map(|&(v, _)| v).collect();
    moved.extend(&refined.smoothed);
    moved.sort_unstable();
    moved.dedup();
    let edges = undirected_edges(&refined.mesh);
    let collided = scope.timed("sculpt.collide", || {
        let input = RefinedInput {
            positions: &refined.mesh.positions,
            triangles: &refined.mesh.triangles,
            edges: &edges,
            base_vertices: refined.base_vertices,
            moved: &moved,
            anchor: &refined.anchor,
        };
        let left = M0Collided {
            inside: &base.inside,
            crossing: &base.crossing,
            triangles: &base.mesh.triangles,
            pierced: &base.pierced,
            partition: &base.partition,
            ring_normal: &base.ring_normal,
            measured: None,
        };
        collide_refined(index, &input, &left, ease, collision)
    });
    let partition = partition_through(&refined.anchor, &base.partition);
    let mut ring_normal = base.ring_normal.clone();
    ring_normal.resize(refined.mesh.positions.len(), None);
    Ok(SculptOutcome {
        drag: *drag,
        layer: base.layer,
        base: base.mesh,
        sculpt,
        collision: collided,
        partition,
        ring_normal,
        count,
    })
}

/// The figures of a sculpt.
#[derive(Serialize)]
struct SculptFigures<'a> {
    /// The mesh it was made on: M0, M1 or sculpt.
    sculpt_layer: &'a str,
    /// The pick, snapped to the mesh, m, and how far the given point was from it.
    sculpt_pick_m: [f64; 3],
    sculpt_pick_distance_m: f64,
    /// Vertices the drag moved, those of them stopped at the body (their offset shortened
    /// to end at the ease), and faces with a moved corner (the region).
    sculpt_moved_vertices: usize,
    sculpt_stopped_at_body: usize,
    sculpt_region_faces: usize,
    /// Refinement threshold, m.
    sculpt_epsilon_m: f64,
    /// Active faces at the start of each level, and per level the faces split 1 -> 4
    /// (red) and bisected (green).
    sculpt_active_by_level: Vec<usize>,
    sculpt_red_green_by_level: Vec<[usize; 2]>,
    /// Stopped at the level limit above epsilon.
    sculpt_level_limit_reached: bool,
    /// Faces before and after.
    sculpt_faces_before: usize,
    sculpt_faces: usize,
    sculpt_vertices: usize,
    /// Over the region after refinement and collision: longest edge (m), smallest angle
    /// (degrees), mean normal turn between adjacent faces (degrees).
    sculpt_max_edge_m: f64,
    sculpt_min_angle_deg: f64,
    sculpt_smoothness_deg: f64,
    /// Vertices the collision tested (new and moved), those inside before the response,
    /// the moves it made, and what is left inside and crossing after it.
    sculpt_tested: usize,
    sculpt_hits: usize,
    sculpt_crossing_before: usize,
    sculpt_responses: usize,
    sculpt_penetrating_vertices: usize,
    sculpt_crossing_edges: usize,
    /// Faces pierced by the body after the response.
    sculpt_pierced_faces: usize,
    /// With `--verify`: the sculpted mesh by brute force (winding number for every vertex,
    /// every edge against every body triangle).
    #[serde(skip_serializing_if = "Option::is_none")]
    sculpt_verify: Option<SculptVerify>,
}

/// A sculpt checked by brute force (`--verify`).
#[derive(Serialize)]
pub(in crate::session) struct SculptVerify {
    pub(in crate::session) inside: usize,
    pub(in crate::session) crossing: usize,
    pub(in crate::session) pierced: usize,
}

pub(in crate::session) fn record(
    scope: &mut StepScope<'_, '_, '_>,
    outcome: &SculptOutcome,
    verify: Option<SculptVerify>,
) {
    let s = &outcome.sculpt;
    let c = &outcome.collision;
    let mesh = outcome.mesh();
    let m = measure(&mesh, &s.refined.region);
    scope.record(&SculptFigures {
        sculpt_layer: outcome.layer,
        sculpt_pick_m: s.displacement.pick.point.to_array(),
        sculpt_pick_distance_m: s.displacement.pick.distance,
        sculpt_moved_vertices: s.displacement.offsets.len(),
        sculpt_stopped_at_body: s.displacement.stopped,
        sculpt_region_faces: s.displacement.region.len(),
        sculpt_epsilon_m: s.epsilon,
        sculpt_active_by_level: s.refined.levels.iter().map(|l| l.active.len()).collect(),
        sculpt_red_green_by_level: s.refined.levels.iter().map(|l| [l.red, l.green]).collect(),
        sculpt_level_limit_reached: s.refined.limited,
        sculpt_faces_before: outcome.base.triangles.len(),
        sculpt_faces: mesh.triangles.len(),
        sculpt_vertices: mesh.positions.len(),
        sculpt_max_edge_m: m.max_edge_m,
        sculpt_min_angle_deg: m.min_angle_deg,
        sculpt_smoothness_deg: m.smoothness,
        sculpt_tested: c.tested,
        sculpt_hits: c.hits,
        sculpt_crossing_before: c.crossing_before,
        sculpt_responses: c.responses.len(),
        sculpt_penetrating_vertices: c.quality.penetrating_vertices,
        sculpt_crossing_edges: c.quality.crossing_edges,
        sculpt_pierced_faces: c.quality.pierced_faces,
        sculpt_verify: verify,
    });
}

/// Makes the garment's sculpts again on its new mesh (after a rebuild), in order. A
/// sculpt that can no longer be made (its pick now too far from the garment) is left out
/// and named in the figures.
pub(in crate::session) fn remake(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut GarmentState,
    index: &BodyIndex,
    collision: &CollisionOptions,
) {
    state.sculpted = None;
    if state.sculpts.is_empty() {
        return;
    }
    let Some(ease) = state.ease() else {
        return;
    };
    let mut left_out = Vec::new();
    let sculpts = state.sculpts.clone();
    for (k, (at, drag, options)) in sculpts.iter().enumerate() {
        let Some(base) = base(state) else {
            return;
        };
        let made = resolve(state, at).map_err(|e| e.to_string()).and_then(|at| {
            let drag = Drag { at, ..*drag };
            apply(scope, base, (&drag, options), index, ease, collision, k + 1).map_err(|e| e.to_string())
        });
        match made {
            Ok(outcome) => state.sculpted = Some(outcome),
            Err(e) => left_out.push(format!("sculpt {}: {e}", k + 1)),
        }
    }
    if let Some(outcome) = &state.sculpted {
        record(scope, outcome, None);
    }
    /// Sculpts made again after the rebuild.
    #[derive(Serialize)]
    struct Remade {
        sculpts_remade: usize,
        #[serde(skip_serializing_if = "Vec::is_empty")]
        sculpts_left_out: Vec<String>,
    }
    scope.record(&Remade {
        sculpts_remade: sculpts.len() - left_out.len(),
        sculpts_left_out: left_out,
    });
}

/// Emits the state's sculpt, if it has one.
pub(in crate::session) fn emit(scope: &mut StepScope<'_, '_, '_>, state: &GarmentState) {
    if let Some(outcome) = &state.sculpted {
        scope.emit(
            "garment.sculpt",
            Stage::Sculpt(SculptStage {
                outcome: Some(outcome),
                refused: None,
            }),
        );
    }
}

/// After an undo that takes a sculpt away: the viewer's sculpt is cleared.
pub(in crate::session) fn emit_cleared(scope: &mut StepScope<'_, '_, '_>) {
    scope.emit(
        "garment.sculpt",
        Stage::Sculpt(SculptStage {
            outcome: None,
            refused: None,
        }),
    );
}
