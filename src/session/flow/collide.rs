//! The mesh-layer collision every step that makes an M0 ends with (garment, set, drag),
//! its figures, and its stages (which `undo` emits again for the state it restores); then
//! M1, when the scene asks for it.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::body::Body;
use crate::collision::{self, AppliedRule, BodyIndex, Collision, VerifyReport};
use crate::session::emit::StepScope;
use crate::session::options::StepContext;
use crate::session::stage::{CollisionOutcome, CollisionPart, CollisionStage, GarmentPart, GarmentStage, Stage};
use crate::session::state::GarmentState;

/// The figures of a collision.
#[derive(Serialize)]
struct CollisionFigures<'a> {
    /// Vertices inside the body after response (exact check over the whole body).
    penetrating_vertices: usize,
    /// Edges crossing the body after response.
    crossing_edges: usize,
    /// Faces the body pokes through after response (a body edge through them).
    pierced_faces: usize,
    /// The least distance from the body to any point of a face, and to any vertex, m.
    face_clearance_m: f64,
    vertex_clearance_m: f64,
    /// Faces pierced at the start of each face round (the first: after the edge rounds).
    pierced_faces_by_round: &'a [usize],
    /// Moves made by the face rounds.
    face_responses: usize,
    /// Deepest vertex left inside, m.
    max_depth_m: f64,
    /// Mean depth of the vertices left inside, m.
    mean_depth_m: f64,
    /// Vertices tested by detection.
    tested_vertices: usize,
    /// Vertices skipped as inert.
    skipped_inert: usize,
    /// Vertices skipped with their patches.
    skipped_patch: usize,
    /// Patches skipped.
    patches_skipped: usize,
    /// Vertices detection found inside.
    hits: usize,
    /// Deepest hit before response, m.
    depth_before_max_m: f64,
    /// Hits per partition letter.
    hits_by_partition: BTreeMap<&'static str, usize>,
    /// Vertices tested point-face and line-line.
    tested_by_method: TestedByMethod,
    /// Vertices moved by the vertex response.
    responses: usize,
    /// Moves made by the edge rounds.
    edge_responses: usize,
    /// Moves per response rule (rules that moved nothing left out).
    responses_by_rule: BTreeMap<&'static str, usize>,
    /// Edges crossing at the start of each edge round.
    crossing_edges_by_round: &'a [usize],
    /// The gap responses stand off at, m.
    response_ease_m: f64,
    /// Largest and mean ease error of the moved vertices, m.
    max_ease_error_m: f64,
    mean_ease_error_m: f64,
    /// Farthest a vertex was moved, m, and the largest stretch of an edge (after / before).
    max_move_m: f64,
    max_stretch: f64,
    /// With `--verify`: the brute-force check.
    #[serde(skip_serializing_if = "Option::is_none")]
    verify: Option<&'a VerifyReport>,
    /// No vertex inside, no edge crossing and no face pierced after the response.
    guarantee_met: bool,
    /// What the quality check and the first edge round did not measure again (the same
    /// positions as before; none with `--quality full`).
    reused: collision::Reused,
}

#[derive(Serialize)]
struct TestedByMethod {
    point_face: usize,
    line_line: usize,
}

impl<'a> CollisionFigures<'a> {
    fn new(index: &BodyIndex, c: &'a Collision, verify: Option<&'a VerifyReport>) -> Self {
        let d = &c.detection;
        let q = &c.quality;
        let hits_by_partition = index
            .partitions
            .iter()
            .enumerate()
            .map(|(k, p)| (p.id.letter(), d.hits.iter().filter(|h| h.partition == k).count()))
            .collect();
        let responses_by_rule = AppliedRule::ALL
            .into_iter()
            .map(|rule| (rule.name(), c.responses.iter().filter(|r| r.rule == rule).count()))
            .filter(|(_, n)| *n > 0)
            .collect();
        Self {
            penetrating_vertices: q.penetrating_vertices,
            crossing_edges: q.crossing_edges,
            pierced_faces: q.pierced_faces,
            face_clearance_m: q.face_clearance_m,
            vertex_clearance_m: q
                .clearance
                .iter()
                .filter(|c| c.is_finite())
                .fold(f64::INFINITY, |a, &c| a.min(c)),
            pierced_faces_by_round: &c.face_rounds,
            face_responses: c.responses.iter().filter(|r| r.rule == AppliedRule::FaceLift).count(),
            max_depth_m: q.max_depth_m,
            mean_depth_m: q.mean_depth_m,
            tested_vertices: d.tested,
            skipped_inert: d.skipped_inert,
            skipped_patch: d.skipped_patch,
            patches_skipped: d.patches_skipped,
            hits: d.hits.len(),
            depth_before_max_m: d.hits.iter().map(|h| h.depth).fold(0.0, f64::max),
            hits_by_partition,
            tested_by_method: TestedByMethod {
                point_face: d.by_method[0],
                line_line: d.by_method[1],
            },
            responses: c.responses.iter().filter(|r| r.edge_round == 0).count(),
            edge_responses: c
                .responses
                .iter()
                .filter(|r| r.edge_round > 0 && r.rule != AppliedRule::FaceLift)
                .count(),
            responses_by_rule,
            crossing_edges_by_round: &c.edge_rounds,
            response_ease_m: c.ease,
            max_ease_error_m: q.max_ease_error_m,
            mean_ease_error_m: q.mean_ease_error_m,
            max_move_m: q.max_move_m,
            max_stretch: q.max_stretch,
            verify,
            guarantee_met: q.is_clear(),
            reused: c.reused,
        }
    }
}

/// Collides the new garment state's M0 with the body (then builds M1, when the scene asks
/// for it), records the figures and emits the stages: what every step that makes an M0
/// ends with. Returns what the response could not clear: `Some([inside, crossing,
/// pierced])` when vertices are left inside the body, edges crossing it or faces pierced by
/// it (the caller refuses an edit that leaves them, or reports a new garment that does).
#[must_use]
pub(in crate::session) fn collide_and_emit(
    scope: &mut StepScope<'_, '_, '_>,
    body: &Body,
    index: &BodyIndex,
    state: &mut GarmentState,
    cx: &StepContext<'_>,
) -> Option<Unclear> {
    let pushed = collide_garment(scope, (body, index), state, cx);
    if let Some(p) = &cx.session.scene.patterns {
        super::patterns::build_patterns(scope, state, p);
    }
    emit_collision(scope, state, index);
    if let Err(e) = pushed {
        return Some(Unclear::Surface(e.to_string()));
    }
    let q = &state.collision.as_ref()?.collision.quality;
    let latest = state
        .sculpted
        .as_ref()
        .map(|s| &s.collision)
        .or(state.m1.as_ref().map(|m| &m.collision));
    match latest.filter(|_| state.layered.is_some()) {
        // Worn over another garment, the latest mesh was pushed: its body check counts too.
        Some(l) if !l.quality.is_clear() => {
            return Some(Unclear::Body([
                l.inside_after.len(),
                l.crossing_after_edges.len(),
                l.pierced_after.len(),
            ]));
        }
        _ => {}
    }
    if !q.is_clear() {
        return Some(Unclear::Body([
            q.penetrating_vertices,
            q.crossing_edges,
            q.pierced_faces,
        ]));
    }
    super::layers::out_of_order(state).map(|(under, counts)| Unclear::Layers(under, counts))
}

/// What a step's collision could not clear.
pub(in crate::session) enum Unclear {
    /// Of the body: vertices inside, edges crossing it, faces it pierces.
    Body([usize; 3]),
    /// Of a garment under it (named): the certificate between them after the push.
    Layers(String, crate::layers::LayerCounts),
    /// The garment could not be pushed at all (not a manifold surface).
    Surface(String),
}

impl Unclear {
    /// The refusal's message, naming the limit.
    pub(in crate::session) fn message(&self) -> String {
        match self {
            Self::Body([inside, crossing, pierced]) => format!(
                "the garment cannot be kept clear of the body after this edit: {inside} vertices inside, {crossing} \
                 edges crossing it and {pierced} faces pierced by it after the response"
            ),
            Self::Layers(under, c) => format!(
                "the garment cannot be kept in front of '{under}' after this edit: {} vertices behind it, {} edges \
                 through it and {} faces pierced by it after the push",
                c.behind, c.outer_edges_through_inner, c.outer_faces_pierced
            ),
            Self::Surface(e) => format!("the garment cannot be layered: {e}"),
        }
    }
}

/// Collides a new garment's first M0 (`garment`, `garment mesh`): a shortfall has nothing to
/// fall back on, so the garment is kept and the shortfall reported loudly.
pub(in crate::session) fn collide_new(
    scope: &mut StepScope<'_, '_, '_>,
    body: &Body,
    index: &BodyIndex,
    next: &mut GarmentState,
    cx: &StepContext<'_>,
) {
    match collide_and_emit(scope, body, index, next, cx) {
        Some(Unclear::Body([inside, crossing, pierced])) => {
            scope.shortfalls.push(crate::session::emit::Shortfall::Guarantee {
                inside,
                crossing,
                pierced,
            });
        }
        Some(unclear) => scope
            .shortfalls
            .push(crate::session::emit::Shortfall::Layers(unclear.message())),
        None => {}
    }
}

/// The refusal of an edit whose M0 the response could not clear of the body (`unmet`:
/// vertices inside, edges crossing, faces pierced): the kept garment is emitted again after the attempt
/// ([`emit_kept`]), so that the last thing logged is what the session holds; returns the
/// message. The caller keeps the state and refuses the edit with it.
pub(in crate::session) fn unclear(
    scope: &mut StepScope<'_, '_, '_>,
    kept: &GarmentState,
    index: &BodyIndex,
    unmet: &Unclear,
) -> String {
    emit_kept(scope, kept, index);
    unmet.message()
}

/// Emits a garment state the session returns to (after an undo, or a refused attempt): its
/// re-surfaced parts (curves, patches, M0), then its collision and M1.
pub(in crate::session) fn emit_kept(scope: &mut StepScope<'_, '_, '_>, kept: &GarmentState, index: &BodyIndex) {
    if let Some(fw) = &kept.framework {
        for part in GarmentPart::RESURFACED {
            scope.emit(part.stage_name(), Stage::Garment(GarmentStage::Part(fw, part)));
        }
    }
    emit_collision(scope, kept, index);
}

/// Collides the state's M0 with the body and pushes it out in front of the garments under
/// it (`cx.below`), recording the figures in the step's metrics; then M1 and the sculpts,
/// their latest mesh pushed out in front of those under it too.
fn collide_garment(
    scope: &mut StepScope<'_, '_, '_>,
    (body, index): (&Body, &BodyIndex),
    state: &mut GarmentState,
    cx: &StepContext<'_>,
) -> Result<(), crate::layers::LayerError> {
    let (options, m1, below) = (cx.options, cx.session.scene.m1.as_ref(), cx.below);
    let garment = scope.timed("collision.mesh", || state.collision_mesh(index.height));
    let (Some(garment), Some(ease)) = (garment, state.ease()) else {
        return Ok(());
    };
    let mut collision = collision::collide(index, &garment, ease, &options.collision, &mut state.detect_memory());
    let layer_ease = crate::layers::PushOptions::default().ease;
    let pushed_m0 = (!below.is_empty())
        .then(|| {
            scope.timed("layers.push_m0", || {
                super::layers::push_m0(index, (&garment, &mut collision), below, layer_ease)
            })
        })
        .transpose()?;
    let t = collision.timings;
    for (name, ms) in [
        ("collision.detect", t.detect),
        ("collision.respond", t.respond),
        ("collision.respond_edges", t.respond_edges),
        ("collision.quality", t.quality),
        ("collision.respond_faces", t.respond_faces),
        ("collision.check_faces", t.check_faces),
        ("collision.face_clearance", t.face_clearance),
    ] {
        let key = scope.timing_key(name);
        scope.metrics.timings_ms.insert(key, ms);
    }
    // --verify checks the step's own quality check (partial unless --quality full) twice:
    // against a full check of every vertex and edge, and against the brute-force truth.
    let verify =
        options.verify.then(|| {
            let full = scope.timed("collision.quality_full", || {
                collision::quality(
                    index,
                    &garment.mesh.positions,
                    &collision.mesh.positions,
                    &garment.edges,
                    &collision.responses,
                )
                .with_faces(index, &collision.mesh.positions, &garment.mesh.triangles, None)
                .with_face_clearance(
                    index,
                    &collision.mesh.positions,
                    &garment.mesh.triangles,
                    collision.ease,
                    None,
                )
            });
            scope.timed("collision.verify", || {
                let (positions, triangles) = (&garment.mesh.positions, &garment.mesh.triangles);
                let before = collision::ground_truth(&body.mesh.mesh, positions, &garment.edges).with_faces(
                    &body.mesh.mesh,
                    positions,
                    triangles,
                );
                let after = collision::ground_truth(&body.mesh.mesh, &collision.mesh.positions, &garment.edges)
                    .with_faces(&body.mesh.mesh, &collision.mesh.positions, triangles);
                let surface = options.collision.detect.reach(index.height).surface;
                let on_skin = |v: usize| {
                    let p = garment.mesh.positions[v];
                    index.nearest(p, f64::INFINITY).is_some_and(|n| n.distance <= surface)
                };
                let mut report = collision::compare(&before, &collision.detection, &after, &collision.quality, on_skin);
                report.full_check_agrees = collision.quality == full;
                let unskipped = collision::detect(
                    index,
                    &garment.input(),
                    &options.collision.detect.clone().with_skipping(false),
                    &mut collision::DetectState::default(),
                );
                report.skips_changed = collision::changed_verdicts(&collision.detection, &unskipped);
                report
            })
        });
    scope.record(&CollisionFigures::new(index, &collision, verify.as_ref()));
    state.collision = Some(CollisionOutcome {
        garment,
        collision,
        verify,
        name: state.name(),
        source: state.file.as_ref().map(|f| f.imported.clone()),
    });
    state.m1 = None;
    if let Some(m1_options) = m1 {
        super::m1::build_m1(scope, body, index, state, options, m1_options);
    }
    super::sculpt::remake(scope, state, index, &options.collision);
    state.layered = None;
    if let Some(m0) = pushed_m0 {
        scope.timed("layers.push_latest", || {
            super::layers::finish(index, state, below, m0, layer_ease)
        })?;
        record_layers(scope, state);
    }
    Ok(())
}

/// The figures of a garment worn over others: per garment under it, the certificate before
/// and after each push.
pub(in crate::session) fn record_layers(scope: &mut StepScope<'_, '_, '_>, state: &GarmentState) {
    if let Some(l) = &state.layered {
        let pairs: BTreeMap<&str, &crate::session::stage::LayerPair> =
            l.pairs.iter().map(|p| (p.under.as_str(), p)).collect();
        let smallest = l
            .gaps
            .iter()
            .copied()
            .filter(|g| g.is_finite())
            .fold(f64::INFINITY, f64::min);
        #[derive(Serialize)]
        struct LayerFigures<'a> {
            /// Per garment under it: the pushes.
            over: BTreeMap<&'a str, &'a crate::session::stage::LayerPair>,
            /// The smallest gap of its latest mesh in front of the garment right under it, m.
            layer_gap_m: f64,
        }
        scope.record(&LayerFigures {
            over: pairs,
            layer_gap_m: smallest,
        });
    }
}

/// Emits the state's collision (detection, then response), if it has one.
pub(in crate::session) fn emit_collision(scope: &mut StepScope<'_, '_, '_>, state: &GarmentState, index: &BodyIndex) {
    if let Some(outcome) = &state.collision {
        for part in CollisionPart::ALL {
            scope.emit(
                part.stage_name(),
                Stage::Collision(CollisionStage { outcome, index, part }),
            );
        }
    }
    super::m1::emit_m1(scope, state);
    super::patterns::emit_patterns(scope, state);
    super::sculpt::emit(scope, state);
    if let Some(layered) = &state.layered {
        scope.emit("layers.push", Stage::Layers(layered));
    }
}
