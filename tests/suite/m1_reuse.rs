//! M1 made incrementally (M1's shape kept from the step before when M0's faces, patches and
//! refinement are the same, only its vertices placed again; M0's edges kept for the
//! selection; a refined patch whose input did not change takes its collision from the step
//! before) against M1 made whole at every step (`full_m1`): random drag and dimension
//! sessions on every shipped body give the same M1 at every step, bit for bit (mesh, every
//! field of the subdivision, positions after the collision, every figure and list of the
//! collision), and the incremental run really kept shapes and patches, and read M1 from its
//! step over every patch when only the refined patches changed.

use drape::session::{M1Stage, RunOptions, SinkError, StageInfo, StageSink, parse_session, run_session};

use super::common::{Lcg, shipped_bodies};

/// Every M1 a run logs, by step and layer (`None`: the innermost garment).
#[derive(Default)]
struct M1s(Vec<(usize, Option<String>, drape::session::M1Outcome)>);

impl StageSink for M1s {
    fn m1(&mut self, info: &StageInfo, stage: M1Stage<'_>) -> Result<(), SinkError> {
        self.0.push((info.step, info.layer.clone(), stage.outcome.clone()));
        Ok(())
    }
}

impl M1s {
    /// The last M1 of the innermost garment logged at `step`.
    fn last_at(&self, step: usize) -> drape::session::M1Outcome {
        let found = self.0.iter().rev().find(|(s, layer, _)| *s == step && layer.is_none());
        found
            .map(|(_, _, o)| o.clone())
            .unwrap_or_else(|| panic!("no M1 of the innermost garment logged at step {step}"))
    }
}

/// A position list's bits.
fn bits(positions: &[glam::DVec3]) -> Vec<[u64; 3]> {
    positions.iter().map(|p| p.to_array().map(f64::to_bits)).collect()
}

/// Asserts that M1 `a` is M1 `b`, bit for bit (`at` says where): its faces, their patches,
/// its positions before and after its collision, every field of the subdivision, the whole
/// collision (every figure and list) and the cut lines.
fn assert_same_m1(a: &drape::session::M1Outcome, b: &drape::session::M1Outcome, at: &str) {
    assert_eq!(a.m1.mesh.triangles, b.m1.mesh.triangles, "{at}: M1 faces");
    assert_eq!(a.m1.face_patch, b.m1.face_patch, "{at}: M1 face patches");
    assert_eq!(
        bits(&a.m1.mesh.positions),
        bits(&b.m1.mesh.positions),
        "{at}: M1 before its collision"
    );
    assert_eq!(a.m1, b.m1, "{at}: the subdivision, every field");
    assert_eq!(
        bits(&a.collision.positions),
        bits(&b.collision.positions),
        "{at}: M1 after its collision"
    );
    assert_eq!(a.collision, b.collision, "{at}: M1's collision, figures and lists");
    assert_eq!((&a.stored, &a.cuts), (&b.stored, &b.cuts), "{at}: cut lines");
}

/// A random session: a tight jumpsuit with M1, its ease tightened (so that M1's collision
/// has vertices to move), then drags of control points, dimension edits and undos drawn by
/// `rng`.
pub(super) fn random_session(body: &std::path::Path, rng: &mut Lcg, steps: usize) -> String {
    const POINTS: [&str; 6] = [
        "waist.front_left",
        "chest.front_left",
        "left_knee",
        "crotch.point",
        "waist.front",
        "right_thigh.inner",
    ];
    const DIMENSIONS: [(&str, f64); 3] = [("waist_girth", 0.04), ("hip_girth", 0.04), ("inseam", 0.05)];
    let mut text = format!(
        "drape 1\nbody \"{}\"\nunits m\nm1\ngarment jumpsuit fit=tight resolution=5\nset ease 0.004\n",
        body.display()
    );
    let pick = |n: usize, rng: &mut Lcg| ((rng.next() * n as f64) as usize).min(n - 1);
    for _ in 0..steps {
        match pick(10, rng) {
            0..=5 => {
                let point = POINTS[pick(POINTS.len(), rng)];
                let d: Vec<String> = (0..3).map(|_| format!("{:.4}", 0.03 * (rng.next() - 0.5))).collect();
                text += &format!("drag {point} by={}\n", d.join(","));
            }
            6..=7 => {
                let (dimension, range) = DIMENSIONS[pick(DIMENSIONS.len(), rng)];
                text += &format!("set {dimension} {:+.4}\n", range * (rng.next() - 0.5));
            }
            _ => text += "undo\n",
        }
    }
    text
}

/// Per step that made an M1: patches kept, 1 when its shape was kept, and 1 when it was read
/// from the step over every patch.
type Kept = Vec<(u64, u64, u64)>;

/// Runs `text`, M1 made incrementally or whole; the M1s and what each step kept.
fn run(text: &str, full_m1: bool) -> (Vec<(usize, drape::session::M1Outcome)>, Kept) {
    let session = parse_session(text, "reuse.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = M1s::default();
    let options = RunOptions {
        full_m1,
        ..RunOptions::default()
    };
    let report = run_session(&session, &options, &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}\n{text}", report.error);
    let kept = report
        .steps
        .iter()
        .filter_map(|m| {
            let work = |key: &str| m.work.get(key).and_then(|v| v.as_u64());
            Some((
                work("m1.patches_kept")?,
                work("m1.shape_kept")?,
                work("m1.every_patch")?,
            ))
        })
        .collect();
    (sink.0.into_iter().map(|(step, _, m1)| (step, m1)).collect(), kept)
}

#[test]
fn incremental_m1_equals_m1_made_whole_bit_for_bit_on_random_drag_and_dimension_sessions_on_every_body() {
    let mut rng = Lcg(0x6d31_7265_7573_6521);
    // M1's settings in turn: the default, two sqrt(3) steps (new vertices from new ones),
    // and Kobbelt's smoothing (old vertices move: the shape is never kept).
    let settings = ["m1", "m1 steps=2", "m1 smooth=kobbelt"];
    for (b, body) in shipped_bodies().into_iter().enumerate() {
        let m1 = settings[b % settings.len()];
        let text = random_session(&body, &mut rng, 8).replacen("\nm1\n", &format!("\n{m1}\n"), 1);
        assert!(text.contains(&format!("\n{m1}\n")), "{text}");
        let (incremental, kept) = run(&text, false);
        let (whole, kept_whole) = run(&text, true);
        let moved = |m1s: &[(usize, drape::session::M1Outcome)]| {
            m1s.iter().filter(|(_, o)| !o.collision.responses.is_empty()).count()
        };
        eprintln!(
            "{} ({m1}): {} M1s, {} with moves; (patches, shape) kept {kept:?}",
            body.display(),
            incremental.len(),
            moved(&incremental)
        );
        assert_eq!(incremental.len(), whole.len(), "{}: M1 stages", body.display());
        assert!(
            incremental.len() >= 4,
            "{}: too few M1s to compare\n{text}",
            body.display()
        );
        for ((step, a), (step_b, b)) in incremental.iter().zip(&whole) {
            let at = format!("{} step {step}\n{text}", body.display());
            assert_eq!(step, step_b, "{at}");
            assert_same_m1(a, b, &at);
        }
        // The runs differ in what they did: the whole one kept nothing, the incremental one
        // kept patches at some step (otherwise this test compared two full builds).
        assert!(
            kept_whole.iter().all(|&k| k == (0, 0, 0)),
            "{}: {kept_whole:?}",
            body.display()
        );
        assert!(
            kept.iter().any(|&(patches, _, _)| patches > 0),
            "{}: no patch kept {kept:?}\n{text}",
            body.display()
        );
        let smoothed = m1.contains("kobbelt");
        assert!(
            kept.iter().any(|&(_, shape, _)| shape == 1) != smoothed,
            "{}: shapes kept {kept:?}\n{text}",
            body.display()
        );
        // With one step and no smoothing, a change of the refined patches over the same M0
        // faces reads M1 from the step over every patch.
        assert!(
            kept.iter().any(|&(_, _, every)| every == 1) == (m1 == "m1"),
            "{}: M1 read from every patch {kept:?}\n{text}",
            body.display()
        );
        assert!(
            moved(&whole) > 0,
            "{}: M1's collision moved nothing\n{text}",
            body.display()
        );
    }
}

#[test]
fn an_undo_restores_the_m1_its_step_made_bit_for_bit_though_the_history_keeps_no_m1() {
    // Steps: 1 garment, 2 cut, 3 ease, 4 drag, 5 drag, 6 set, 7-10 undo (back to the states
    // after steps 5, 4, 3 and 2; the cut step logs no M1 of its own, so the last undo is
    // compared with its cut lines rebuilt on step 1's M1).
    let text = "drape 1\nbody builtin\nunits m\nm1\ngarment jumpsuit fit=tight resolution=5\n\
                cut yoke at=0,1.0,0 normal=0,1,0.25\nset ease 0.004\n\
                drag waist.front_left by=0,0,0.02\ndrag left_knee by=0,0.03,0\nset waist_girth +0.02\n\
                undo\nundo\nundo\nundo\n";
    let session = parse_session(text, "undo_m1.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = M1s::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    let at = |step: usize| sink.last_at(step);
    for (undo, made) in [(7, 5), (8, 4), (9, 3)] {
        assert_same_m1(&at(undo), &at(made), &format!("undo at step {undo}"));
    }
    // The states compared differ (each step changed M1), so a restore of the wrong one fails.
    assert_ne!(bits(&at(5).collision.positions), bits(&at(4).collision.positions));
    assert_ne!(bits(&at(4).collision.positions), bits(&at(3).collision.positions));
    // Back to the cut step's state: step 1's M1, with the cut line.
    let (restored, built) = (at(10), at(1));
    assert_eq!(restored.m1, built.m1);
    assert_eq!(bits(&restored.collision.positions), bits(&built.collision.positions));
    assert_eq!(restored.stored.len(), 1, "the cut line is kept");
    // Every undo made M1 again (its build's work is in the undo's metrics).
    for step in 7..=10 {
        let metrics = report.steps.iter().find(|m| m.step == step).expect("metrics");
        let work = &metrics.work;
        assert!(work.contains_key("m1.patches_kept"), "step {step}: {work:?}");
    }
}

#[test]
fn an_edit_the_garment_over_it_cannot_follow_is_refused_and_restores_the_m1_before_it_bit_for_bit() {
    // Steps: 1 the inner jumpsuit with M1, 2 its cut line, 3 a tight jumpsuit over it, 4 a
    // sculpt of the inner one: a spike 8 cm high on a 1 cm base that the coarse garment
    // over it cannot be kept in front of. The edit is refused; the inner garment goes back
    // to its state after step 2, whose M1 its history does not keep (no sculpt was made
    // on it): the refusal makes it again, and it must be the M1 step 2 made.
    let text = "drape 1\nbody builtin\nunits m\nm1\ngarment jumpsuit name=inner resolution=5\n\
                cut inner:yoke at=0,1.0,0 normal=0,1,0.25\n\
                garment jumpsuit fit=tight name=outer over=inner resolution=5\n\
                sculpt at=inner:waist.front radius=0.01 peak=0.08\n";
    let session = parse_session(text, "refused_m1.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = M1s::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    let refused = report.steps[4].figures.get("refused").and_then(|r| r.as_str());
    assert!(
        refused.is_some_and(|r| r.starts_with("'outer' cannot be kept over 'inner'")),
        "the sculpt was not refused for the garment over it: {:?}",
        report.steps[4].figures
    );
    let (restored, before) = (sink.last_at(4), sink.last_at(2));
    assert_same_m1(&restored, &before, "the refused sculpt");
    assert_eq!(restored.stored.len(), 1, "the cut line is kept");
    // The refusal made M1 again (its build's work is in the step's metrics).
    let work = &report.steps[4].work;
    assert!(work.contains_key("m1.patches_kept"), "{work:?}");
}
