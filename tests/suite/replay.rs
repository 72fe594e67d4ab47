//! The recorded sessions in `recordings/`: each replayed through the memory sink gives the
//! digest its manifest holds (what `drape replay` checks when the `.rrd` is not kept) and
//! the committed snapshot of its decoded data; a value changed on purpose is found and
//! named by entity, component, row and index.

use std::path::{Path, PathBuf};

use drape::session::{RunOptions, parse_session, run_session};
use drape::viz::replay::{FlatChunk, Value, digest, first_difference, flatten_messages};
use drape::viz::{LogOptions, RerunLogger};
use rerun::log::LogMsg;

fn recordings() -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir("recordings")
        .expect("recordings/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.join("session.drape").exists())
        .collect();
    out.sort();
    assert!(out.len() >= 5, "{out:?}");
    out
}

/// Runs `recordings/NAME/session.drape` into memory as `drape replay` does.
fn replay(dir: &Path) -> Vec<LogMsg> {
    let name = dir.file_name().expect("a folder").to_string_lossy().into_owned();
    let text = std::fs::read_to_string(dir.join("session.drape")).expect("session");
    let session = parse_session(&text, &dir.join("session.drape").display().to_string(), dir).expect("parses");
    let (rec, storage) = drape::viz::target::memory_recording(&name).expect("memory");
    {
        let mut logger = RerunLogger::new(rec, LogOptions::default()).expect("logger");
        let report = run_session(&session, &RunOptions::default(), &mut [&mut logger]);
        assert!(report.error.is_none(), "{name}: {:?}", report.error);
    }
    storage.take()
}

#[test]
fn every_recording_replays_to_its_manifest_and_its_snapshot() {
    let demo = std::fs::read_to_string("recordings/demo/session.drape").expect("demo");
    assert_eq!(
        demo,
        drape::session::DEMO_SESSION,
        "recordings/demo is the demo session"
    );
    for dir in recordings() {
        let name = dir.file_name().expect("folder").to_string_lossy().into_owned();
        let manifest: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).expect("manifest")).expect("JSON");
        let msgs = replay(&dir);
        let chunks = flatten_messages(msgs.clone());
        assert_eq!(
            manifest["digest"].as_str(),
            Some(digest(&chunks).as_str()),
            "{name}: replay differs from its manifest (drape replay {} --write records it again)",
            dir.display()
        );
        assert_eq!(manifest["chunks"].as_u64(), Some(chunks.len() as u64), "{name}");
        // The demo's snapshot is `demo_recording` (tests/suite/snapshot.rs).
        if name != "demo" {
            insta::assert_snapshot!(format!("recording_{name}"), super::snapshot::summarize(msgs));
        }
    }
}

/// Finds the first value of component `component` at `entity` and moves it by `by`.
fn nudge(chunks: &mut [FlatChunk], entity: &str, component: &str, index: usize, by: f64) -> (usize, usize) {
    for (k, c) in chunks.iter_mut().enumerate() {
        if c.entity != entity {
            continue;
        }
        if let Some(rows) = c.components.get_mut(component)
            && let Some(Some(values)) = rows.first_mut()
            && let Some(Value::Num(v)) = values.get_mut(index)
        {
            *v += by;
            return (k, 0);
        }
    }
    panic!("no {component} at {entity}");
}

#[test]
fn a_changed_value_fails_replay_with_a_report_naming_entity_component_and_index() {
    let stored = flatten_messages(replay(Path::new("recordings/drag-into-body")));
    assert_eq!(first_difference(&stored, &stored.clone(), 0.0), None);
    let mut changed = stored.clone();
    let (chunk, row) = nudge(
        &mut changed,
        "/garment/m0/mesh/p000",
        "Mesh3D:vertex_positions",
        7,
        1e-4,
    );
    let d = first_difference(&stored, &changed, 0.0).expect("the change is found");
    assert_eq!(
        (d.chunk, d.entity.as_str(), d.component.as_deref(), d.row, d.index),
        (
            chunk,
            "/garment/m0/mesh/p000",
            Some("Mesh3D:vertex_positions"),
            Some(row),
            Some(7)
        )
    );
    let report = d.to_string();
    assert!(
        report.contains("entity /garment/m0/mesh/p000") && report.contains("index 7"),
        "{report}"
    );
    assert!(d.step.is_some() && d.stage.is_some(), "{report}");
    // Within a tolerance larger than the change, the same data.
    assert_eq!(first_difference(&stored, &changed, 1e-3), None);
    assert_ne!(digest(&stored), digest(&changed));
}

/// The binary: `--write` records a folder, `replay` passes against the file and against
/// the digest alone, and a manifest with another digest fails with exit code 1.
#[test]
fn drape_replay_passes_on_its_own_recording_and_fails_on_another_digest() {
    let dir = std::env::temp_dir()
        .join(format!("drape-replay-{}", std::process::id()))
        .join("tiny");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("session.drape"),
        "drape 1\ngarment jumpsuit resolution=2\nset ease 0.01\n",
    )
    .unwrap();
    let run = |args: &[&str]| {
        let out = super::common::drape_cli().args(args).output().expect("drape runs");
        (out.status.code(), String::from_utf8_lossy(&out.stdout).into_owned())
    };
    let d = dir.to_str().unwrap();
    assert_eq!(run(&["replay", d, "--write"]).0, Some(0));
    let (code, out) = run(&["replay", d]);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("the same data as"), "{out}");
    std::fs::remove_file(dir.join("recording.rrd")).unwrap();
    let (code, out) = run(&["replay", d]);
    assert_eq!(code, Some(0), "{out}");
    let manifest = std::fs::read_to_string(dir.join("manifest.json")).unwrap();
    let digest = serde_json::from_str::<serde_json::Value>(&manifest).unwrap()["digest"]
        .as_str()
        .unwrap()
        .to_string();
    std::fs::write(dir.join("manifest.json"), manifest.replace(&digest, "0123456789abcdef")).unwrap();
    let (code, out) = run(&["replay", d]);
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("the manifest says 0123456789abcdef"), "{out}");
    std::fs::remove_dir_all(dir.parent().unwrap()).ok();
}

/// `drape edit` fed through a pipe: malformed lines are reported and change nothing, `save`
/// writes the steps that ran, and the saved session, run again, logs the same data as the
/// live run (the recording's own name aside).
#[test]
fn a_piped_edit_session_saved_and_replayed_logs_what_the_live_run_logged() {
    use std::io::Write as _;
    let dir = std::env::temp_dir().join(format!("drape-edit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let live = dir.join("live.rrd");
    let saved = dir.join("saved");
    let mut child = super::common::drape_cli()
        .args(["edit", "--save", live.to_str().unwrap()])
        .stdin(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("drape edit starts");
    let input = format!(
        "garment jumpsuit fit=tight resolution=3\nset ease 0.008\nfrobnicate y=1\ndrag waist.frnt by=0,0,0.01\n\
         undo\nundo\ndrag waist.front by=0,0,-0.01\nsave {}\nquit\n",
        saved.display()
    );
    child.stdin.take().unwrap().write_all(input.as_bytes()).unwrap();
    let out = child.wait_with_output().expect("drape edit ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("unknown statement 'frobnicate'"), "{stderr}");
    assert!(stderr.contains("did you mean 'waist.front'"), "{stderr}");
    // The second undo has nothing left to take back: refused by the parser, nothing ran.
    assert!(stderr.contains("nothing to undo"), "{stderr}");
    let text = std::fs::read_to_string(saved.join("session.drape")).unwrap();
    assert_eq!(
        text,
        "drape 1\ngarment jumpsuit fit=tight resolution=3\nset ease 0.008\nundo\ndrag waist.front by=0,0,-0.01\n"
    );
    let data = |path: &Path| -> Vec<FlatChunk> {
        drape::viz::replay::read_rrd(path)
            .expect("reads")
            .into_iter()
            .filter(|c| !c.entity.starts_with("/__"))
            .collect()
    };
    let (a, b) = (data(&live), data(&saved.join("recording.rrd")));
    assert!(a.len() > 100);
    assert_eq!(first_difference(&a, &b, 0.0), None);
    std::fs::remove_dir_all(&dir).ok();
}
