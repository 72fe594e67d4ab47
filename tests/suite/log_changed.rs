//! Logging only what changed: a session logged with `only_changed` (a garment mesh's parts,
//! and of a part the fields, that the recording shows already are not sent again) and
//! logged whole (every part, every field, at every step) into memory; both recordings
//! decoded, and the latest-at scene rebuilt here from the chunks after every stage: per
//! entity and component, the last value logged at or before it, a `Clear` removing what
//! its entity (and, recursive, everything under it) showed. The two scenes are equal after
//! every stage, and the changed-only recording is smaller, by a margin.

use std::collections::BTreeMap;

use drape::session::DEMO_SESSION;
use drape::viz::LogOptions;
use rerun::external::arrow::array::{Array, ArrayRef, BooleanArray};
use rerun::log::Chunk;

use super::common::{Lcg, shipped_bodies};

/// Per (entity, component): the value the viewer shows.
type Scene = BTreeMap<(String, String), ArrayRef>;

/// A recording's chunks, decoded in the order they were written, Rerun's own entities
/// left out.
fn record(text: &str, options: LogOptions) -> Vec<Chunk> {
    super::snapshot::recorded_chunks(text, options)
        .into_iter()
        .filter(|c| !c.entity_path().to_string().starts_with("/__"))
        .collect()
}

/// The scene after every stage (by `stage` time; static data belongs to every stage), and
/// the bytes of component data sent.
fn scenes(chunks: &[Chunk]) -> (Vec<(i64, Scene)>, usize) {
    let mut scene = Scene::new();
    let mut out: Vec<(i64, Scene)> = Vec::new();
    let mut current: Option<i64> = None;
    let mut bytes = 0;
    for (chunk, row) in chunks.iter().flat_map(|c| (0..c.num_rows()).map(move |r| (c, r))) {
        let stage = chunk
            .timelines()
            .get(&"stage".into())
            .map_or(-1, |t| t.times_raw()[row]);
        if stage >= 0 && current != Some(stage) {
            if let Some(done) = current {
                assert!(stage > done, "stages in order");
                out.push((done, scene.clone()));
            }
            current = Some(stage);
        }
        let entity = chunk.entity_path().to_string();
        for descriptor in chunk.component_descriptors() {
            let component = descriptor.component.to_string();
            let Some(array) = chunk.component_batch_raw(descriptor.component, row) else {
                continue;
            };
            let array = array.expect("a row of the chunk");
            if component == "Clear:is_recursive" {
                let recursive = array
                    .as_any()
                    .downcast_ref::<BooleanArray>()
                    .is_some_and(|b| b.len() == 1 && b.value(0));
                let under = format!("{entity}/");
                scene.retain(|(e, _), _| !(*e == entity || (recursive && e.starts_with(&under))));
            } else {
                bytes += array.get_array_memory_size();
                scene.insert((entity.clone(), component), array);
            }
        }
    }
    if let Some(done) = current {
        out.push((done, scene));
    }
    (out, bytes)
}

/// Logs `text` both ways (parts of `part_faces` faces or more) and compares the scenes after
/// every stage; returns the bytes of component data each way.
fn same_scene(text: &str, part_faces: usize) -> (usize, usize) {
    let options = LogOptions::default().with_part_faces(part_faces);
    let changed = record(text, options.clone());
    let whole = record(text, options.with_only_changed(false));
    let ((a, changed_bytes), (b, whole_bytes)) = (scenes(&changed), scenes(&whole));
    assert_eq!(
        a.iter().map(|(s, _)| *s).collect::<Vec<_>>(),
        b.iter().map(|(s, _)| *s).collect::<Vec<_>>(),
        "the same stages"
    );
    for ((stage, x), (_, y)) in a.iter().zip(&b) {
        let keys = |s: &Scene| s.keys().cloned().collect::<Vec<_>>();
        assert_eq!(
            keys(x),
            keys(y),
            "the entities and components shown after stage {stage}"
        );
        for (key, value) in x {
            assert!(
                value.as_ref() == y[key].as_ref(),
                "{key:?} after stage {stage} differs from logging everything"
            );
        }
    }
    // The garment meshes really came in parts, and some were left out.
    let parts = |chunks: &[Chunk]| {
        chunks
            .iter()
            .filter(|c| c.entity_path().to_string().starts_with("/garment/m0/mesh/"))
            .count()
    };
    assert!(
        parts(&changed) < parts(&whole),
        "{} of {} M0 part chunks",
        parts(&changed),
        parts(&whole)
    );
    assert!(
        whole
            .iter()
            .any(|c| c.entity_path().to_string().starts_with("/garment/m0/mesh/p0")
                && !c.entity_path().to_string().ends_with("p000")),
        "more than one M0 part"
    );
    (changed_bytes, whole_bytes)
}

/// The demo (cut line, dimension edits, drags, an undo, a refused drag), M0 and M1 in parts
/// of 256 faces or more.
#[test]
fn the_demo_logged_only_where_it_changed_shows_the_scene_logging_everything_shows_after_every_stage() {
    let (changed, whole) = same_scene(DEMO_SESSION, 256);
    println!("component data: {changed} bytes changed-only, {whole} bytes logging everything");
    assert!(changed * 10 < whole * 8, "{changed} against {whole} bytes");
}

/// A random drag and dimension session on every shipped body, parts of 128 faces or more.
#[test]
fn random_sessions_logged_only_where_they_changed_show_the_scene_logging_everything_shows_on_every_body() {
    let mut rng = Lcg(20_261_128);
    for body in shipped_bodies() {
        let text = super::m1_reuse::random_session(&body, &mut rng, 6);
        let (changed, whole) = same_scene(&text, 128);
        println!("{}: {changed} of {whole} bytes", body.display());
        assert!(changed < whole, "{}: {changed} against {whole} bytes", body.display());
    }
}

/// A solve's iterations go out as one chunk per entity with a row per iteration: at each
/// step of the demo whose solver ran, `constraints/solve/curve`, `constraints/solve/control`
/// and `metrics/m/solver/max_residual_touched` each have one chunk, with as many rows as the
/// solver's own count of its iterations (`solver_iterations` in the step's figures), at
/// consecutive `iter` times that go on from the step before, all at one stage. (That the rows
/// are those logged one by one shows in the demo's snapshot, which summarizes row by row and
/// did not change when the iterations were held.)
#[test]
fn a_solves_iterations_go_out_as_one_chunk_per_entity_with_a_row_per_iteration() {
    let (report, chunks) = super::snapshot::recorded(DEMO_SESSION, LogOptions::default());
    let truth: Vec<(i64, usize)> = (report.steps.iter())
        .filter_map(|m| {
            let n = m.figures.get("solver_iterations")?.as_u64()?;
            Some((m.step as i64, n as usize))
        })
        .collect();
    assert!(truth.len() >= 3 && truth.iter().any(|&(_, n)| n >= 5), "{truth:?}");
    fn times(c: &Chunk, timeline: &'static str) -> Vec<i64> {
        c.timelines()
            .get(&timeline.into())
            .map_or(Vec::new(), |t| t.times_raw().to_vec())
    }
    for entity in [
        "/constraints/solve/curve",
        "/constraints/solve/control",
        "/metrics/m/solver/max_residual_touched",
    ] {
        let mine: Vec<&Chunk> = chunks
            .iter()
            .filter(|c| c.entity_path().to_string() == entity)
            .collect();
        let mut by_step: Vec<(i64, usize)> = Vec::new();
        let mut next_iter = 1;
        for c in &mine {
            let (steps, stages, iters) = (times(c, "step"), times(c, "stage"), times(c, "iter"));
            assert_eq!(steps.len(), c.num_rows(), "{entity}: a step for every row");
            assert!(steps.iter().all(|&s| s == steps[0]), "{entity}: one step per chunk");
            assert!(stages.iter().all(|&s| s == stages[0]), "{entity}: one stage per chunk");
            let expected: Vec<i64> = (next_iter..next_iter + c.num_rows() as i64).collect();
            assert_eq!(iters, expected, "{entity} at step {}: consecutive iterations", steps[0]);
            next_iter += c.num_rows() as i64;
            by_step.push((steps[0], c.num_rows()));
        }
        assert_eq!(by_step, truth, "{entity}: (step, rows) against the solver's iterations");
    }
}
