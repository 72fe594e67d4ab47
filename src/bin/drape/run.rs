//! `drape run`: a session (the demo by default) run into its sinks: the recording (a file,
//! a viewer, or a server viewers join), the progress lines, the metrics and the export.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context as _;
use drape::session::export::ObjExporter;
use drape::session::metrics::metrics_json;
use drape::session::{FailureKind, LogDetail, RunOptions, Shortfall, StageSink, run_session};
use drape::viz::{LogOptions, RecordingTarget, RerunLogger, open_recording};

use crate::args::RunArgs;
use crate::failure::{Classify, Result};
use crate::files::{create_parent, host_name, partial_path, session_stem, write_atomic};
use crate::load_session;
use crate::progress::Progress;

pub(crate) fn run(args: RunArgs) -> Result<ExitCode> {
    let session = load_session(args.session.as_deref())?;
    if let Some(body) = &args.body
        && !body.exists()
    {
        return Err(anyhow::anyhow!("--body {}: no such file", body.display())).bad_input();
    }
    let stem = session_stem(&session);
    // A file recording is written beside its final name and renamed at the end, so a run
    // that dies midway never leaves a broken file where a good one was.
    let final_path = args
        .save
        .clone()
        .unwrap_or_else(|| PathBuf::from("recordings").join(format!("{stem}.rrd")));
    let target = if let Some(url) = &args.viewer.connect {
        RecordingTarget::Connect(url.clone())
    } else if args.viewer.serve {
        RecordingTarget::Serve(args.viewer.port)
    } else {
        create_parent(&final_path).internal()?;
        RecordingTarget::File(partial_path(&final_path))
    };
    let rec = open_recording(&target, &stem)
        .context("cannot open the recording")
        .internal()?;
    if args.viewer.serve {
        println!("serving on port {}; open it from any machine with:", args.viewer.port);
        println!("  rerun rerun+http://{}:{}/proxy", host_name(), args.viewer.port);
    }
    eprintln!("running {} ({} step(s))", session.name, session.steps.len());
    let detail = args
        .log_detail
        .as_deref()
        .and_then(LogDetail::from_name)
        .or(session.scene.log)
        .unwrap_or_default();
    let mut logger = RerunLogger::new(
        rec,
        LogOptions::default().with_timings(args.log_timings).with_detail(detail),
    )
    .internal()?;
    let mut exporter = args.export.clone().map(ObjExporter::new).transpose().internal()?;
    let mut progress = Progress;
    let mut options = RunOptions {
        body_override: args.body.clone(),
        verify: args.verify,
        max_input_bytes: crate::max_input_bytes(),
        stop: Some(crate::interrupt::stop_flag()),
        ..RunOptions::default()
    };
    if args.brute_force {
        options.collision.detect.acceleration = drape::collision::Acceleration::BruteForce;
        options.collision.detect.method_override = Some(drape::body::DetectionMethod::PointFace);
    }
    if args.no_skipping {
        options.collision.detect.inert = false;
        options.collision.detect.patch_skipping = false;
    }
    let report = {
        let mut sinks: Vec<&mut dyn StageSink> = vec![&mut progress, &mut logger];
        if let Some(e) = exporter.as_mut() {
            sinks.push(e);
        }
        run_session(&session, &options, &mut sinks)
    };
    if let Some(path) = &args.metrics {
        let text = serde_json::to_string_pretty(&metrics_json(&report.steps)).internal()?;
        write_atomic(path, text.as_bytes()).internal()?;
        eprintln!("metrics: {}", path.display());
    }
    if let Some(e) = &exporter {
        eprintln!(
            "exported {} OBJ file(s) to {}",
            e.written.len(),
            args.export.as_deref().unwrap_or(Path::new(".")).display()
        );
    }
    if args.viewer.serve {
        logger.recording().flush_blocking().ok();
        println!("all data sent; still serving for late viewers. Press Ctrl-C to stop.");
        std::io::stdout().flush().ok();
        loop {
            std::thread::sleep(std::time::Duration::from_secs(3600));
        }
    }
    if let Some(url) = &args.viewer.connect {
        // Without a listener the SDK would drop the data with only a log line: say so.
        if let Err(e) = logger
            .recording()
            .flush_with_timeout(std::time::Duration::from_secs(10))
        {
            eprintln!("error: the recording could not be delivered to {url}: {e}");
            // Dropping a gRPC stream that never connected waits on its sender thread for
            // good; metrics and exports are written already, so leave without it.
            std::process::exit(i32::from(FailureKind::Internal.exit_code()));
        }
        eprintln!("recording sent to {url}");
    }
    drop(logger); // closes the file sink (writes its footer)
    if let RecordingTarget::File(partial) = &target {
        std::fs::rename(partial, &final_path)
            .with_context(|| format!("cannot rename {} to {}", partial.display(), final_path.display()))
            .internal()?;
        eprintln!(
            "recording: {} (view: rerun {})",
            final_path.display(),
            final_path.display()
        );
    }
    if let Some(after) = report.interrupted {
        eprintln!("interrupted after step {after}: the recording holds every step before the signal");
        return Ok(ExitCode::from(crate::interrupt::EXIT_INTERRUPTED));
    }
    for (step, shortfall) in &report.shortfalls {
        match shortfall {
            Shortfall::Guarantee { inside, crossing } => eprintln!(
                "{}: step {step}: the garment is not clear of the body: {inside} vertices inside, {crossing} edges crossing",
                if args.strict { "error" } else { "warning" }
            ),
            Shortfall::Refused(message) => eprintln!(
                "{}: step {step}: edit refused: {message}",
                if args.strict { "error" } else { "note" }
            ),
        }
    }
    match report.error {
        Some(e) => {
            eprintln!("error: {e}");
            Ok(ExitCode::from(e.kind().exit_code()))
        }
        None if args.strict && !report.shortfalls.is_empty() => Ok(ExitCode::from(FailureKind::StepFailed.exit_code())),
        None => Ok(ExitCode::SUCCESS),
    }
}
