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
    for chunk in chunks {
        assert_eq!(chunk.num_rows(), 1, "one row per chunk");
        let stage = chunk.timelines().get(&"stage".into()).map_or(-1, |t| t.times_raw()[0]);
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
            let Some(array) = chunk.component_batch_raw(descriptor.component, 0) else {
                continue;
            };
            let array = array.expect("row 0");
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
