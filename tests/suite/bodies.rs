//! Every body, every accepted edit: the demo session and the drag session run on each of the
//! five shipped bodies end every step with no vertex inside and no edge crossing by the
//! exact quality check, and the last step of each by the brute-force truth (winding number
//! for every vertex, every edge against every body triangle); every responded vertex of
//! that step meets its gap by the test's own distance; and no step's response grows an
//! edge by more than its length, or the ease where that is more (lifting edges, not
//! flinging their ends). The same for M1, the display mesh: clear after every step by the
//! exact check, the last by brute force. After every step, no body edge passes through a
//! face of M0 or M1, by a brute force written here ([`super::common::faces_pierced_by`]).
//! The sleeved sessions (the shirt, the sleeved jumpsuit) are checked by brute force at
//! every step.

use std::path::Path;

use drape::collision::{Collision, ground_truth};
use drape::mesh::TriMesh;
use drape::session::{
    CollisionPart, CollisionStage, RunOptions, SinkError, StageInfo, StageSink, parse_session, run_session,
};

/// One step's collision, with M0's edges and its positions before the response.
struct StepCollision {
    step: usize,
    collision: Collision,
    edges: Vec<[u32; 2]>,
    before: Vec<glam::DVec3>,
}

/// Each step's collision, and each step's M1 (positions after its collision, edges).
#[derive(Default)]
struct Collisions(Vec<StepCollision>, Vec<StepM1>);

/// One step's M1: the step, its collision, its edges and its faces.
type StepM1 = (usize, drape::m1::M1Collision, Vec<[u32; 2]>, Vec<[u32; 3]>);

impl StageSink for Collisions {
    fn m1(&mut self, info: &StageInfo, stage: drape::session::M1Stage<'_>) -> Result<(), SinkError> {
        let o = stage.outcome;
        self.1.push((
            info.step,
            o.collision.clone(),
            o.m1.edges().to_vec(),
            o.m1.mesh.triangles.clone(),
        ));
        Ok(())
    }

    fn collision(&mut self, info: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        if stage.part == CollisionPart::Respond {
            let o = stage.outcome;
            self.0.push(StepCollision {
                step: info.step,
                collision: o.collision.clone(),
                edges: o.garment.edges.to_vec(),
                before: o.garment.mesh.positions.clone(),
            });
        }
        Ok(())
    }
}

/// The response may lift an edge's ends, not fling them: no edge grows by more than its own
/// length before the response (ends longer than twice it), or than the response's ease where
/// that is more (a lift moves an end by about the ease: an edge of a millimetre whose one
/// end is lifted grows by that much), measured here from the two meshes.
const MOST_GROWTH: f64 = 1.0;

/// Runs `session` on `body`; checks every step and the last one by brute force.
fn check(session: &str, body: &Path) {
    check_steps(session, body, false);
}

/// Runs `session` on `body`; checks every step, by brute force as well where `brute` (else
/// the last step only).
fn check_steps(session: &str, body: &Path, brute: bool) {
    let text = std::fs::read_to_string(session).expect("session");
    let parsed = parse_session(&text, session, Path::new(".")).expect("parses");
    let options = RunOptions {
        body_override: Some(body.to_path_buf()),
        ..RunOptions::default()
    };
    let mut sink = Collisions::default();
    let report = run_session(&parsed, &options, &mut [&mut sink]);
    let name = format!("{} on {}", session, body.display());
    assert!(report.error.is_none(), "{name}: {:?}", report.error);
    let unmet: Vec<_> = report
        .shortfalls
        .iter()
        .filter(|(_, s)| matches!(s, drape::session::Shortfall::Guarantee { .. }))
        .collect();
    assert!(unmet.is_empty(), "{name}: {unmet:?}");
    for StepCollision {
        step,
        collision: c,
        edges,
        before,
    } in &sink.0
    {
        let q = &c.quality;
        assert_eq!(
            (q.penetrating_vertices, q.crossing_edges, q.pierced_faces),
            (0, 0, 0),
            "{name}: step {step} leaves vertices inside, edges crossing or faces pierced"
        );
        let after = &c.mesh.positions;
        // The largest growth of an edge, as a share of what it may grow by.
        let (growth, at) = edges
            .iter()
            .map(|&[a, b]| {
                let (a, b) = (a as usize, b as usize);
                let was = before[a].distance(before[b]);
                (
                    (after[a].distance(after[b]) - was) / was.max(c.ease),
                    [before[a], before[b], after[a], after[b]],
                )
            })
            .fold((0.0, [glam::DVec3::ZERO; 4]), |w, x| if x.0 > w.0 { x } else { w });
        assert!(
            growth <= MOST_GROWTH,
            "{name}: step {step} grows an edge by {growth:.2} times its length (or the ease), at {at:?}"
        );
    }
    let StepCollision {
        step,
        collision: last,
        edges,
        ..
    } = sink.0.last().expect("a collision");
    let mesh = drape::body::BodyMesh::load(&drape::body::BodySource::File(body.to_path_buf()), 1.0).expect("loads");
    let truth = ground_truth(&mesh.mesh, &last.mesh.positions, edges);
    assert_eq!(
        truth.inside_count(),
        0,
        "{name}: step {step}, vertices inside by the winding number"
    );
    assert_eq!(
        truth.crossing_count(),
        0,
        "{name}: step {step}, edges crossing a body triangle"
    );
    let body_mesh: &TriMesh = &mesh.mesh;
    super::collision::assert_meets_the_ease(last, body_mesh);
    if brute {
        for StepCollision {
            step, collision, edges, ..
        } in &sink.0
        {
            let truth = ground_truth(&mesh.mesh, &collision.mesh.positions, edges);
            assert_eq!(
                (truth.inside_count(), truth.crossing_count()),
                (0, 0),
                "{name}: step {step}, M0 by brute force"
            );
        }
        for (step, m1, edges, _) in &sink.1 {
            let truth = ground_truth(&mesh.mesh, &m1.positions, edges);
            assert_eq!(
                (truth.inside_count(), truth.crossing_count()),
                (0, 0),
                "{name}: step {step}, M1 by brute force"
            );
        }
    }
    // M1 (the demo's scene asks for it): clear after every step by the exact check, and
    // after the last by brute force.
    for (step, m1, _, triangles) in &sink.1 {
        let q = &m1.quality;
        assert_eq!(
            (q.penetrating_vertices, q.crossing_edges, q.pierced_faces),
            (0, 0, 0),
            "{name}: step {step} leaves M1 inside, crossing or pierced"
        );
        let pierced = super::common::faces_pierced_by(&mesh.mesh, &m1.positions, triangles);
        assert!(
            pierced.is_empty(),
            "{name}: step {step}, M1 faces pierced by body edges: {pierced:?}"
        );
    }
    for StepCollision { step, collision, .. } in &sink.0 {
        let pierced = super::common::faces_pierced_by(&mesh.mesh, &collision.mesh.positions, &collision.mesh.triangles);
        assert!(
            pierced.is_empty(),
            "{name}: step {step}, M0 faces pierced by body edges: {pierced:?}"
        );
    }
    if let Some((step, m1, edges, _)) = sink.1.last() {
        let truth = ground_truth(&mesh.mesh, &m1.positions, edges);
        assert_eq!(
            (truth.inside_count(), truth.crossing_count()),
            (0, 0),
            "{name}: step {step}, M1 by brute force"
        );
    }
}

#[test]
fn the_demo_leaves_every_body_clear() {
    for body in super::common::shipped_bodies() {
        check("assets/sessions/demo.drape", &body);
    }
}

/// The demo has M1 and crosses flipped edges into the body before M1's collision on some
/// step: the M1 checks above are not empty.
#[test]
fn the_demo_has_m1_edges_to_clear() {
    let text = std::fs::read_to_string("assets/sessions/demo.drape").expect("demo");
    let parsed = parse_session(&text, "demo", Path::new(".")).expect("parses");
    let mut sink = Collisions::default();
    let report = run_session(&parsed, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none());
    assert!(!sink.1.is_empty(), "the demo logs no M1");
    assert!(
        sink.1.iter().any(|(_, m1, _, _)| m1.crossing_before > 0),
        "no step's M1 crossed the body before its collision"
    );
}

#[test]
fn the_drag_session_leaves_every_body_clear() {
    for body in super::common::shipped_bodies() {
        check("assets/sessions/drags.drape", &body);
    }
}

/// The shirt session (long sleeves, stand collar: dimension edits on the sleeves, drags of a
/// whole elbow ring and a cuff point, the sleeves lifted, the collar raised, undo) on every
/// body: every accepted step, M0 and M1, clear by brute force.
#[test]
fn the_shirt_session_leaves_every_body_clear_at_every_step() {
    for body in super::common::shipped_bodies() {
        check_steps("assets/sessions/shirt.drape", &body, true);
    }
}

/// The sleeved jumpsuit session (short sleeves, the ease down to 4 mm, the cap ring pushed
/// up into the armpit, the sleeves closed in towards the torso) on every body: every
/// accepted step, M0 and M1, clear by brute force.
#[test]
fn the_sleeved_jumpsuit_session_leaves_every_body_clear_at_every_step() {
    for body in super::common::shipped_bodies() {
        check_steps("assets/sessions/sleeves.drape", &body, true);
    }
}
