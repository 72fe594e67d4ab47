//! What the demo really logs: the demo session run into a memory sink, the chunks decoded,
//! and a summary per entity (components, rows, rounded values, and a digest of every
//! position, vector, index, colour and radius buffer) compared with a snapshot, so that one
//! moved vertex fails it with a diff naming the entity.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use drape::session::{
    DEMO_SESSION, GarmentPart, GarmentStage, RunOptions, SinkError, Stage, StageInfo, StageSink, parse_session,
    run_session,
};
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

/// FNV-1a (64-bit) over the values, each rounded to 1e-9 (metres for positions; colours,
/// indices and counts are whole numbers already): stable across runs and platforms.
fn digest(values: impl IntoIterator<Item = f64>) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut n = 0usize;
    for v in values {
        n += 1;
        for b in ((v * 1e9).round() as i64).to_le_bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    format!("{n} values, digest {h:016x}")
}

/// The digest lines of one component of `chunk`: one per row, `(stage, text)`.
fn digests<C: rerun::Component>(
    chunk: &Chunk,
    id: rerun::ComponentIdentifier,
    values: impl Fn(&C) -> Vec<f64>,
) -> Vec<(i64, String)> {
    stages(chunk, id)
        .zip(chunk.iter_component::<C>(id))
        .map(|(stage, batch)| (stage, digest(batch.iter().flat_map(&values))))
        .collect()
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
            let f3 = |v: [f32; 3]| v.map(f64::from).to_vec();
            let hashed: Vec<(i64, String)> = match id.as_str() {
                "Points3D:positions" | "Mesh3D:vertex_positions" | "Arrows3D:origins" => {
                    digests::<rerun::Position3D>(&chunk, id, |p| f3(p.0.0))
                }
                "Arrows3D:vectors" | "Mesh3D:vertex_normals" => {
                    digests::<rerun::components::Vector3D>(&chunk, id, |v| f3(v.0.0))
                }
                "LineStrips3D:strips" => digests::<rerun::components::LineStrip3D>(&chunk, id, |s| {
                    // The strip's length first, so that moving a point between strips shows.
                    let mut out = vec![s.0.len() as f64];
                    out.extend(s.0.iter().flat_map(|p| f3(p.0)));
                    out
                }),
                "Mesh3D:triangle_indices" => {
                    digests::<rerun::components::TriangleIndices>(&chunk, id, |t| t.0.0.map(f64::from).to_vec())
                }
                c if c.ends_with(":colors") || c == "Mesh3D:vertex_colors" => {
                    digests::<rerun::components::Color>(&chunk, id, |c| vec![f64::from(c.0.0)])
                }
                c if c.ends_with(":radii") => {
                    digests::<rerun::components::Radius>(&chunk, id, |r| vec![f64::from(r.0.0)])
                }
                _ => Vec::new(),
            };
            for (stage, text) in hashed {
                entry.values.push((id.to_string(), stage, text));
            }
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
    logged_summary(LogOptions::default(), |logger| Box::new(logger))
}

/// Runs the demo into a memory recording through the sink `wrap` makes of the logger, and
/// summarizes what was logged.
fn logged_summary(options: LogOptions, wrap: impl FnOnce(&mut RerunLogger) -> Box<dyn StageSink + '_>) -> String {
    let (rec, storage) = drape::viz::target::memory_recording("demo").unwrap();
    let session = parse_session(DEMO_SESSION, "demo.drape", std::path::Path::new(".")).unwrap();
    {
        let mut logger = RerunLogger::new(rec, options).unwrap();
        let mut sink = wrap(&mut logger);
        let report = run_session(&session, &RunOptions::default(), &mut [sink.as_mut()]);
        assert!(report.error.is_none(), "{:?}", report.error);
    }
    summarize(storage.take())
}

/// Forwards every stage to the logger, but the M0 of step `step` with vertex 0 moved 1 mm.
struct Nudge<'a> {
    logger: &'a mut RerunLogger,
    step: usize,
}

impl StageSink for Nudge<'_> {
    fn stage(&mut self, info: &StageInfo, stage: Stage<'_>) -> Result<(), SinkError> {
        if let Stage::Garment(GarmentStage::Part(fw, GarmentPart::Mesh)) = stage
            && info.step == self.step
        {
            let mut moved = fw.clone();
            moved.m0.mesh.positions[0].x += 0.001;
            return self
                .logger
                .stage(info, Stage::Garment(GarmentStage::Part(&moved, GarmentPart::Mesh)));
        }
        self.logger.stage(info, stage)
    }
}

/// The snapshot catches one vertex moved by 1 mm, and the diff names the entity: every
/// line that differs sits under `/garment/m0` (the mesh part and the edge lines that hold
/// the vertex). Every part is logged at every step here, so that both runs log the same rows.
#[test]
fn one_vertex_moved_by_a_millimetre_changes_the_summary_of_its_entity_only() {
    let every_part = || LogOptions::default().with_only_changed(false);
    let clean = logged_summary(every_part(), |logger| Box::new(logger));
    let nudged = logged_summary(every_part(), |logger| Box::new(Nudge { logger, step: 3 }));
    let entity_of = |text: &str, line: usize| -> String {
        text.lines()
            .take(line + 1)
            .filter(|l| l.starts_with('/'))
            .last()
            .unwrap_or("")
            .to_string()
    };
    let (a, b): (Vec<&str>, Vec<&str>) = (clean.lines().collect(), nudged.lines().collect());
    assert_eq!(a.len(), b.len(), "the same entities and rows");
    let changed: Vec<(String, &str)> = (0..a.len())
        .filter(|&k| a[k] != b[k])
        .map(|k| (entity_of(&clean, k), a[k]))
        .collect();
    assert!(!changed.is_empty(), "a 1 mm move went unnoticed");
    for (entity, line) in &changed {
        assert!(entity.starts_with("/garment/m0"), "{entity}: {line}");
    }
    assert!(
        changed
            .iter()
            .any(|(e, l)| e.starts_with("/garment/m0/mesh/") && l.contains("Mesh3D:vertex_positions"))
    );
}

#[test]
fn the_demo_logs_what_the_snapshot_shows() {
    insta::assert_snapshot!("demo_recording", demo_summary());
}

#[test]
fn the_demo_logs_the_same_data_twice() {
    assert_eq!(demo_summary(), demo_summary());
}

/// The demo's recording as decoded chunks, in the order they were written.
fn demo_chunks() -> Vec<Chunk> {
    recorded_chunks(DEMO_SESSION, LogOptions::default())
}

/// The recording of the session `text` logged with `options`, as decoded chunks in the
/// order they were written (the recording's own, not the blueprint's).
pub fn recorded_chunks(text: &str, options: LogOptions) -> Vec<Chunk> {
    recorded(text, options).1
}

/// [`recorded_chunks`], with the run's report (each step's figures).
pub fn recorded(text: &str, options: LogOptions) -> (drape::session::RunReport, Vec<Chunk>) {
    let (rec, storage) = drape::viz::target::memory_recording("demo").unwrap();
    let session = parse_session(text, "session.drape", std::path::Path::new(".")).expect("parses");
    let report = {
        let mut logger = RerunLogger::new(rec, options).unwrap();
        run_session(&session, &RunOptions::default(), &mut [&mut logger])
    };
    assert!(report.error.is_none(), "{:?}", report.error);
    let chunks = storage
        .take()
        .into_iter()
        .filter_map(|msg| match msg {
            LogMsg::ArrowMsg(store, arrow) if store.kind() == rerun::StoreKind::Recording => {
                Some(Chunk::from_arrow_msg(&arrow).expect("chunk decodes"))
            }
            _ => None,
        })
        .collect();
    (report, chunks)
}

/// Two runs write the same chunks in the same order (what plain `rerun rrd compare`
/// checks): chunk by chunk, the same entity, timelines, components and values (Rerun's own
/// `Chunk::ensure_similar`, which ignores only chunk and row ids). Then two runs of the
/// binary, one on one thread pinned to one core (`taskset -c 0 drape --threads 1`) and one
/// on two worker threads (`--threads 2`, whatever the machine's cores), write files with
/// the same data in the same order; with the `rerun` command installed, they also pass
/// plain `rerun rrd compare`.
#[test]
fn two_runs_write_the_same_chunks_in_the_same_order_on_one_thread_or_two() {
    let (a, b) = (demo_chunks(), demo_chunks());
    assert_eq!(a.len(), b.len(), "chunk counts");
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        if let Err(e) = Chunk::ensure_similar(x, y) {
            panic!("chunk {k} ({} vs {}): {e:#}", x.entity_path(), y.entity_path());
        }
    }
    let dir = std::env::temp_dir().join(format!("drape-compare-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let files: Vec<std::path::PathBuf> = (0..2).map(|i| dir.join(format!("run{i}.rrd"))).collect();
    let one_core = std::process::Command::new("taskset")
        .env("XDG_CACHE_HOME", super::common::cache_home())
        .args([
            "-c",
            "0",
            env!("CARGO_BIN_EXE_drape"),
            "--threads",
            "1",
            "run",
            "--save",
        ])
        .arg(&files[0])
        .output()
        .expect("taskset runs (util-linux)");
    assert!(
        one_core.status.success(),
        "{}",
        String::from_utf8_lossy(&one_core.stderr)
    );
    let (code, stderr) = super::session_errors::drape(&["--threads", "2", "run", "--save", files[1].to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    let data = |f: &std::path::Path| drape::viz::replay::read_rrd(f).expect("decodes");
    let (x, y) = (data(&files[0]), data(&files[1]));
    assert!(x.len() > 1000, "{} chunks", x.len());
    assert_eq!(drape::viz::replay::first_difference(&x, &y, 0.0), None);
    // Rerun's own comparison agrees.
    let out = super::common::rerun_cli()
        .args(["rrd", "compare"])
        .args(&files)
        .output()
        .expect("rerun runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).ok();
}

/// The summary of the demo logged at `detail`.
fn demo_at(detail: drape::session::LogDetail) -> String {
    let (rec, storage) = drape::viz::target::memory_recording("demo").unwrap();
    let session = parse_session(DEMO_SESSION, "demo.drape", std::path::Path::new(".")).unwrap();
    {
        let mut logger = RerunLogger::new(rec, LogOptions::default().with_detail(detail)).unwrap();
        let report = run_session(&session, &RunOptions::default(), &mut [&mut logger]);
        assert!(report.error.is_none(), "{:?}", report.error);
    }
    summarize(storage.take())
}

/// `log detail=metrics` keeps only the metrics, the log and the legends; `final` keeps the
/// final meshes (the body, M0 after its collision, M1, the fit map) and drops the
/// framework's intermediate stages; both keep every metric of the full recording.
#[test]
fn lighter_log_details_keep_the_metrics_and_drop_the_rest() {
    use drape::session::LogDetail;
    let entities = |summary: &str| -> Vec<String> {
        summary
            .lines()
            .filter(|l| l.starts_with('/'))
            .map(str::to_string)
            .collect()
    };
    let all = entities(&demo_summary());
    let metrics = entities(&demo_at(LogDetail::Metrics));
    let last = entities(&demo_at(LogDetail::Final));
    for e in &metrics {
        assert!(
            e == "/" || e.starts_with("/metrics") || e.starts_with("/log") || e.starts_with("/legend"),
            "{e} at detail metrics"
        );
    }
    for e in [
        "/body/mesh",
        "/garment/m0/mesh/p000",
        "/garment/m0/edges/p000",
        "/garment/m1/mesh/p000",
        "/garment/clearance/p000",
        "/garment/cut_lines/yoke",
    ] {
        assert!(last.iter().any(|x| x == e), "{e} missing at detail final");
    }
    for e in [
        "/garment/curves/rings/waist",
        "/garment/control_points",
        "/body/landmarks",
        "/collision/mesh/hits/E",
    ] {
        assert!(!last.iter().any(|x| x.starts_with(e)), "{e} at detail final");
        assert!(
            all.iter().any(|x| x.starts_with(e)),
            "{e} not in the full recording either"
        );
    }
    let metric_entities =
        |v: &[String]| -> Vec<String> { v.iter().filter(|e| e.starts_with("/metrics")).cloned().collect() };
    assert_eq!(metric_entities(&metrics), metric_entities(&all));
}

/// Every number a step records (its `--metrics` figures) reaches the recording, once, at
/// the step's end, as a series of `metrics/<unit>/step/<op>` (or of
/// `metrics/count/guarantee/<op>`) named by its path, with the same value; and nothing else is
/// logged there. The truth is the run's own metrics report, walked here independently of
/// the logger's walk: each figure's leaves, an object's by field name, a list's by its
/// elements' name (`name`, `ring`, `region` or `id`, else the text fields joined) or index.
#[test]
fn every_figure_a_step_records_is_logged_at_its_end() {
    fn leaves(path: &str, value: &serde_json::Value, out: &mut BTreeMap<String, f64>) {
        match value {
            serde_json::Value::Number(n) => {
                out.insert(path.to_string(), n.as_f64().expect("a finite figure"));
            }
            serde_json::Value::Object(fields) => {
                for (k, v) in fields {
                    leaves(&format!("{path}/{k}"), v, out);
                }
            }
            serde_json::Value::Array(items) => {
                let mut used = std::collections::BTreeSet::new();
                for (i, item) in items.iter().enumerate() {
                    let fields = item.as_object();
                    let named = ["name", "ring", "region", "id"].iter().find_map(|k| {
                        fields
                            .and_then(|f| f.get(*k))
                            .and_then(|v| v.as_str())
                            .map(str::to_string)
                    });
                    let joined = fields
                        .map(|f| f.values().filter_map(|v| v.as_str()).collect::<Vec<_>>().join("_"))
                        .filter(|s| !s.is_empty());
                    let mut key = named.or(joined).unwrap_or_else(|| i.to_string());
                    if !used.insert(key.clone()) {
                        key = format!("{key}_{i}");
                    }
                    leaves(&format!("{path}/{key}"), item, out);
                }
            }
            _ => {}
        }
    }
    let (report, chunks) = recorded(DEMO_SESSION, LogOptions::default());
    // The truth: (step, figure path) -> value.
    let mut truth: BTreeMap<(i64, String), f64> = BTreeMap::new();
    for m in &report.steps {
        let mut out = BTreeMap::new();
        for (k, v) in &m.figures {
            leaves(&format!("/{k}"), v, &mut out);
        }
        truth.extend(out.into_iter().map(|(p, v)| ((m.step as i64, p), v)));
    }
    // What was logged under metrics/<unit>/step/<op> and metrics/count/guarantee/<op>: each
    // entity's series names (static), and its rows of scalars by the `step` timeline, a
    // series' place in the row its place among the names.
    let scalars: rerun::ComponentIdentifier = "Scalars:scalars".into();
    let names_id: rerun::ComponentIdentifier = "SeriesPoints:names".into();
    let mut names: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut rows: Vec<(String, i64, Vec<f64>)> = Vec::new();
    for chunk in &chunks {
        let path = chunk.entity_path().to_string();
        let parts: Vec<&str> = path.split('/').collect();
        let ["", "metrics", _unit, "step" | "guarantee", _op] = parts.as_slice() else {
            continue;
        };
        if chunk.is_static() {
            for batch in chunk.iter_component::<rerun::components::Name>(names_id) {
                names.insert(path.clone(), batch.iter().map(|n| n.to_string()).collect());
            }
            continue;
        }
        for ((step, _), batch) in chunk
            .iter_component_indices("step".into(), scalars)
            .zip(chunk.iter_component::<rerun::components::Scalar>(scalars))
        {
            rows.push((path.clone(), step.as_i64(), batch.iter().map(|s| s.0.0).collect()));
        }
    }
    let mut logged: BTreeMap<(i64, String), Vec<f64>> = BTreeMap::new();
    for (path, step, row) in rows {
        let names = &names[&path];
        assert_eq!(names.len(), row.len(), "{path} at step {step}: a row of another length");
        for (name, value) in names.iter().zip(row) {
            logged.entry((step, format!("/{name}"))).or_default().push(value);
        }
    }
    assert!(truth.len() > 500, "{} figures: too few to trust", truth.len());
    let missing: Vec<_> = truth.keys().filter(|k| !logged.contains_key(*k)).take(5).collect();
    assert!(missing.is_empty(), "figures not logged: {missing:?}");
    let extra: Vec<_> = logged.keys().filter(|k| !truth.contains_key(*k)).take(5).collect();
    assert!(extra.is_empty(), "logged, not figures: {extra:?}");
    for (key, values) in &logged {
        assert_eq!(
            values,
            &vec![truth[key]],
            "{key:?}: logged {values:?}, recorded {}",
            truth[key]
        );
    }
}
