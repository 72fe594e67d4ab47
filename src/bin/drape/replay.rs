//! `drape replay DIR`: a recorded session (`DIR/session.drape`) run again and its logged
//! data compared with the stored recording (`DIR/recording.rrd`, value by value, in
//! order), or with the digest in `DIR/manifest.json` when the recording is not kept.
//! `--write` records the session into the folder (the recording and the manifest).

use std::path::Path;
use std::process::ExitCode;

use anyhow::Context as _;
use drape::session::{RunOptions, Session, run_session};
use drape::viz::replay::{FlatChunk, digest, first_difference, flatten_messages, read_rrd};
use drape::viz::{LogOptions, RecordingStream, RecordingTarget, RerunLogger, open_recording};
use serde_json::json;

use crate::args::ReplayArgs;
use crate::failure::{Classify, Result};
use crate::files::{partial_path, write_atomic};
use crate::load_session;

/// The folder's name: the recording's name (its id derives from it).
fn name_of(dir: &Path) -> String {
    dir.file_name()
        .map_or_else(|| "recording".to_string(), |n| n.to_string_lossy().into_owned())
}

/// Runs `session` into `rec` (a step that fails fails the command with its exit code).
fn run_into(session: &Session, rec: RecordingStream) -> Result<()> {
    let report = {
        let mut logger = RerunLogger::new(rec, LogOptions::default()).internal()?;
        run_session(session, &RunOptions::default(), &mut [&mut logger])
    };
    match report.error {
        None => Ok(()),
        Some(e) => Err(crate::failure::Failure {
            kind: e.kind(),
            error: anyhow::anyhow!(e.to_string()),
        }),
    }
}

/// Runs the session of `dir` into memory and returns its data, flattened.
fn run_in_memory(dir: &Path) -> Result<Vec<FlatChunk>> {
    let session = load_session(Some(&dir.join("session.drape")))?;
    let (rec, storage) = drape::viz::target::memory_recording(&name_of(dir))
        .context("cannot open a memory recording")
        .internal()?;
    run_into(&session, rec)?;
    Ok(flatten_messages(storage.take()))
}

pub(crate) fn replay(args: &ReplayArgs) -> Result<ExitCode> {
    let dir = &args.dir;
    let rrd = dir.join("recording.rrd");
    let manifest_path = dir.join("manifest.json");
    if args.write {
        return write(dir);
    }
    if args.serve || args.serve_web {
        return serve(dir, args);
    }
    let live = run_in_memory(dir)?;
    let name = name_of(dir);
    if rrd.exists() {
        let stored = read_rrd(&rrd).bad_input()?;
        return Ok(match first_difference(&stored, &live, args.tolerance) {
            None => {
                println!(
                    "replay {name}: the same data as {} ({} chunks, digest {})",
                    rrd.display(),
                    live.len(),
                    digest(&live)
                );
                ExitCode::SUCCESS
            }
            Some(d) => {
                println!("replay {name}: differs from {}: {d}", rrd.display());
                ExitCode::from(1)
            }
        });
    }
    let manifest: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(&manifest_path)
            .with_context(|| {
                format!(
                    "{}: cannot read (and no recording.rrd beside it)",
                    manifest_path.display()
                )
            })
            .bad_input()?,
    )
    .with_context(|| format!("{}: not JSON", manifest_path.display()))
    .bad_input()?;
    let expected = manifest["digest"].as_str().unwrap_or_default();
    let got = digest(&live);
    if expected == got {
        println!(
            "replay {name}: the digest of the manifest ({} chunks, digest {got})",
            live.len()
        );
        Ok(ExitCode::SUCCESS)
    } else {
        println!(
            "replay {name}: digest {got}, the manifest says {expected} (the recording is not kept: \
             `drape replay {} --write` records it again to compare value by value)",
            dir.display()
        );
        Ok(ExitCode::from(1))
    }
}

/// Serves the folder's session to viewers (and the web viewer with `--serve-web`) until
/// Ctrl-C.
fn serve(dir: &Path, args: &ReplayArgs) -> Result<ExitCode> {
    let session = load_session(Some(&dir.join("session.drape")))?;
    let viewer = crate::args::ViewerArgs {
        serve: args.serve,
        serve_web: args.serve_web,
        port: args.port,
        web_port: args.web_port,
        bind: args.bind,
        connect: None,
    };
    let stop = crate::interrupt::stop_flag();
    let live = crate::live::open_live(&viewer, None, &name_of(dir))?;
    run_into(&session, live.rec.clone())?;
    live.finish(&stop)?;
    Ok(ExitCode::SUCCESS)
}

/// Records the session into the folder: `recording.rrd` and `manifest.json`.
fn write(dir: &Path) -> Result<ExitCode> {
    let session = load_session(Some(&dir.join("session.drape")))?;
    let rrd = dir.join("recording.rrd");
    let partial = partial_path(&rrd);
    let rec = open_recording(&RecordingTarget::File(partial.clone()), &name_of(dir))
        .context("cannot open the recording")
        .internal()?;
    run_into(&session, rec)?;
    crate::files::finish_recording(&partial, &rrd)?;
    let data = read_rrd(&rrd).internal()?;
    let bytes = std::fs::metadata(&rrd).map(|m| m.len()).unwrap_or(0);
    let manifest = json!({
        "drape_version": env!("CARGO_PKG_VERSION"),
        "session": "session.drape",
        "body": match &session.scene.body {
            drape::body::BodySource::File(p) => p
                .file_name()
                .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into_owned()),
            builtin => builtin.name(),
        },
        "steps": session.steps.len(),
        "chunks": data.len(),
        "rrd_bytes": bytes,
        "digest": digest(&data),
    });
    let text = serde_json::to_string_pretty(&manifest).internal()?;
    write_atomic(&dir.join("manifest.json"), format!("{text}\n").as_bytes()).internal()?;
    println!(
        "recorded {}: {} step(s), {} chunks, {bytes} bytes, digest {}",
        dir.display(),
        session.steps.len(),
        data.len(),
        digest(&data)
    );
    Ok(ExitCode::SUCCESS)
}
