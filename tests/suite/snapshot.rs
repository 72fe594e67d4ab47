//! What the demo really logs: the demo session run into a memory sink, the chunks decoded,
//! and a summary per entity (components, rows, rounded values) compared with a snapshot.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use drape::session::{DEMO_SESSION, RunOptions, StageSink, parse_session, run_session};
use drape::viz::{LogOptions, RerunLogger};
use rerun::external::re_log_encoding::DecoderApp;
use rerun::log::{Chunk, LogMsg};

#[derive(Default)]
struct EntitySummary {
    components: BTreeMap<String, usize>,
    /// (component, stage, text): sorted on output, so chunk boundaries do not matter.
    values: Vec<(String, i64, String)>,
}

fn round3(v: f32) -> f32 {
    (v * 1000.0).round() / 1000.0
}

/// The `stage` time of each row holding `component` (static rows count as -1).
fn stages<'a>(chunk: &'a Chunk, component: rerun::ComponentIdentifier) -> Box<dyn Iterator<Item = i64> + 'a> {
    if chunk.is_static() {
        Box::new(std::iter::repeat(-1))
    } else {
        Box::new(
            chunk
                .iter_component_indices("stage".into(), component)
                .map(|(t, _)| t.as_i64()),
        )
    }
}

/// Summarizes decoded recording messages: per entity path, each component's row count,
/// plus rounded sample values of positions, strips, scalars and text.
pub fn summarize(msgs: impl IntoIterator<Item = LogMsg>) -> String {
    let mut entities: BTreeMap<String, EntitySummary> = BTreeMap::new();
    for msg in msgs {
        let LogMsg::ArrowMsg(store, arrow) = msg else { continue };
        if store.kind() != rerun::StoreKind::Recording {
            continue;
        }
        let chunk = Chunk::from_arrow_msg(&arrow).expect("chunk decodes");
        let path = chunk.entity_path().to_string();
        if path.starts_with("/__") {
            continue;
        }
        let entry = entities.entry(path).or_default();
        for descriptor in chunk.component_descriptors() {
            let id = descriptor.component;
            let rows = chunk
                .iter_component_indices("stage".into(), id)
                .count()
                .max(usize::from(chunk.is_static()));
            *entry.components.entry(id.to_string()).or_insert(0) += rows;
            match id.as_str() {
                "Points3D:positions" | "Mesh3D:vertex_positions" => {
                    for (stage, batch) in stages(&chunk, id).zip(chunk.iter_component::<rerun::Position3D>(id)) {
                        let n = batch.len();
                        let first = batch.first().map(|p| p.0.0.map(round3));
                        entry
                            .values
                            .push((id.to_string(), stage, format!("{n} points, first {first:?}")));
                    }
                }
                "LineStrips3D:strips" => {
                    for (stage, batch) in
                        stages(&chunk, id).zip(chunk.iter_component::<rerun::components::LineStrip3D>(id))
                    {
                        let sizes: Vec<usize> = batch.iter().map(|s| s.0.len()).collect();
                        entry
                            .values
                            .push((id.to_string(), stage, format!("strip sizes {sizes:?}")));
                    }
                }
                "Scalars:scalars" => {
                    for (stage, batch) in stages(&chunk, id).zip(chunk.iter_component::<rerun::components::Scalar>(id))
                    {
                        let v: Vec<String> = batch.iter().map(|s| format!("{:.3}", s.0.0)).collect();
                        entry.values.push((id.to_string(), stage, v.join(", ")));
                    }
                }
                "TextLog:text" | "TextLog:level" => {
                    for (stage, batch) in stages(&chunk, id).zip(chunk.iter_component::<rerun::components::Text>(id)) {
                        for t in batch.iter() {
                            let first_line = t.as_str().lines().next().unwrap_or("").to_string();
                            entry.values.push((id.to_string(), stage, first_line.clone()));
                        }
                    }
                }
                _ => {}
            }
        }
    }
    let mut out = String::new();
    for (path, e) in &mut entities {
        e.values.sort();
        writeln!(out, "{path}").ok();
        for (c, rows) in &e.components {
            writeln!(out, "  {c} x{rows}").ok();
        }
        for (component, stage, v) in &e.values {
            writeln!(out, "    {component} @stage {stage}: {v}").ok();
        }
    }
    out
}

/// Summarizes an `.rrd` file's bytes (decoding must succeed to the end).
pub fn summarize_rrd(bytes: &[u8]) -> String {
    let msgs: Vec<LogMsg> = DecoderApp::decode_eager(bytes)
        .expect("rrd header")
        .map(|m| m.expect("every message decodes"))
        .collect();
    summarize(msgs)
}

fn demo_summary() -> String {
    let (rec, storage) = drape::viz::target::memory_recording("demo").unwrap();
    let session = parse_session(DEMO_SESSION, "demo.drape", std::path::Path::new(".")).unwrap();
    {
        let mut logger = RerunLogger::new(rec, LogOptions::default()).unwrap();
        let mut sinks: Vec<&mut dyn StageSink> = vec![&mut logger];
        let report = run_session(&session, &RunOptions::default(), &mut sinks);
        assert!(report.error.is_none(), "{:?}", report.error);
    }
    summarize(storage.take())
}

#[test]
fn the_demo_logs_what_the_snapshot_shows() {
    insta::assert_snapshot!("demo_recording", demo_summary());
}

#[test]
fn the_demo_logs_the_same_data_twice() {
    assert_eq!(demo_summary(), demo_summary());
}
