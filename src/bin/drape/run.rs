//! `drape run`: a session (the demo by default) run into its sinks: the recording (a file,
//! a viewer, or a server viewers join), the progress lines, the metrics and the export.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use drape::session::export::{ObjExporter, PatternExporter};
use drape::session::metrics::metrics_json;
use drape::session::{FailureKind, LogDetail, RunOptions, Shortfall, StageSink, run_session};
use drape::viz::{LogOptions, RerunLogger};

use crate::args::RunArgs;
use crate::failure::{Classify, Result};
use crate::files::{session_stem, write_atomic};
use crate::live::open_live;
use crate::load_session;
use crate::progress::Progress;

pub(crate) fn run(args: RunArgs) -> Result<ExitCode> {
    let mut session = load_session(args.session.as_deref())?;
    if args.patterns.is_some() && session.scene.patterns.is_none() {
        session.scene.patterns = Some(drape::pattern::PatternOptions::default());
    }
    if let Some(body) = &args.body
        && !body.exists()
    {
        return Err(anyhow::anyhow!("--body {}: no such file", body.display())).bad_input();
    }
    let stem = session_stem(&session);
    // The recording is written beside its final name and renamed at the end, so a run that
    // dies midway never leaves a broken file where a good one was; with a viewer or a
    // server the file is written too and keeps everything if the viewer goes away.
    let final_path = args
        .save
        .clone()
        .unwrap_or_else(|| PathBuf::from("recordings").join(format!("{stem}.rrd")));
    let stop = crate::interrupt::stop_flag();
    let live = open_live(&args.viewer, Some(&final_path), &stem)?;
    eprintln!("running {} ({} step(s))", session.name, session.steps.len());
    let detail = args
        .log_detail
        .as_deref()
        .and_then(LogDetail::from_name)
        .or(session.scene.log)
        .unwrap_or_default();
    let mut logger = RerunLogger::new(
        live.rec.clone(),
        LogOptions::default()
            .with_timings(args.log_timings)
            .with_only_changed(!args.log_unchanged)
            .with_detail(detail)
            .with_settle(args.viewer.connect.is_none() && !args.viewer.serve && !args.viewer.serve_web),
    )
    .internal()?;
    let mut exporter = args.export.clone().map(ObjExporter::new).transpose().internal()?;
    let mut pattern_exporter = args.patterns.clone().map(PatternExporter::new);
    let mut progress = Progress;
    let options = run_options(&args, &stop)?;
    let report = {
        let mut sinks: Vec<&mut dyn StageSink> = vec![&mut progress, &mut logger];
        if let Some(e) = exporter.as_mut() {
            sinks.push(e);
        }
        if let Some(e) = pattern_exporter.as_mut() {
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
    if let Some(e) = &pattern_exporter {
        eprintln!(
            "patterns: {} file(s) in {}",
            e.written.len(),
            args.patterns.as_deref().unwrap_or(Path::new(".")).display()
        );
    }
    drop(logger);
    if let Some(path) = live.finish(&stop)? {
        eprintln!("recording: {} (view: rerun {})", path.display(), path.display());
    }
    if let Some(after) = report.interrupted {
        eprintln!("interrupted after step {after}: the recording holds every step before the signal");
        return Ok(ExitCode::from(crate::interrupt::EXIT_INTERRUPTED));
    }
    for (step, shortfall) in &report.shortfalls {
        match shortfall {
            Shortfall::Guarantee {
                inside,
                crossing,
                pierced,
            } => eprintln!(
                "{}: step {step}: the garment is not clear of the body: {inside} vertices inside, {crossing} edges \
                 crossing, {pierced} faces pierced",
                if args.strict { "error" } else { "warning" }
            ),
            Shortfall::Refused(message) => eprintln!(
                "{}: step {step}: edit refused: {message}",
                if args.strict { "error" } else { "note" }
            ),
            Shortfall::Layers(message) => eprintln!(
                "{}: step {step}: the layers are out of order: {message}",
                if args.strict { "error" } else { "warning" }
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

/// The run's settings from the command line: the body and its axes, `--verify`, the input
/// limit, the stop flag, the index cache and the collision's switches.
fn run_options(args: &RunArgs, stop: &std::sync::Arc<std::sync::atomic::AtomicBool>) -> Result<RunOptions> {
    let frame = drape::body::Frame::new(
        args.up.unwrap_or(drape::body::Axis(glam::DVec3::Y)),
        args.front.unwrap_or(drape::body::Axis(glam::DVec3::Z)),
    )
    .map_err(anyhow::Error::msg)
    .bad_input()?;
    let mut options = RunOptions {
        body_override: args.body.clone(),
        body_frame: frame,
        verify: args.verify,
        max_input_bytes: crate::max_input_bytes(),
        stop: Some(stop.clone()),
        index_cache: crate::index_cache(),
        undo_limit: crate::undo_limit(),
        ..RunOptions::default()
    };
    if args.brute_force {
        options.collision.detect.acceleration = drape::collision::Acceleration::BruteForce;
        options.collision.detect.method_override = Some(drape::body::DetectionMethod::PointFace);
    }
    options.collision.full_quality = args.quality == "full";
    options.full_m1 = args.full_m1;
    if args.no_skipping {
        options.collision.detect.inert = false;
        options.collision.detect.patch_skipping = false;
    }
    Ok(options)
}
