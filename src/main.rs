//! The `drape` command line: run a session (the demo by default), check one, or measure
//! the mannequin refinements.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context as _;
use clap::{Args, Parser, Subcommand};

use drape::mannequin::{DressForm, MannequinOptions, Region, run_mannequin};
use drape::session::export::ObjExporter;
use drape::session::metrics::metrics_json;
use drape::session::{
    CollisionPart, CollisionStage, ConstraintStage, DEMO_SESSION, DEMO_SESSION_NAME, FailureKind, RunOptions,
    Session, SinkError, Stage, StageInfo, StageSink, StepEnd, parse_session, run_session,
};
use drape::viz::{LogOptions, RecordingTarget, RerunLogger, open_recording};

/// Exit codes, for `--help` and the README.
const EXIT_CODES: &str = "Exit codes: 0 success; 1 a step failed at run time (the recording keeps \
every stage before it, plus the error); 2 bad input (a malformed session, flag or body file); \
3 an internal or I/O failure (a file that cannot be written, a viewer that cannot be reached).";

/// Garment edit sessions against a body, every stage logged to Rerun.
///
/// With no command, runs the built-in demo session and writes recordings/demo.rrd
/// (view it with `rerun recordings/demo.rrd`).
#[derive(Parser, Debug)]
#[command(name = "drape", version, about, long_about, after_help = EXIT_CODES)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a session (default: the built-in demo) and log every stage to Rerun.
    Run(RunArgs),
    /// Parse and validate a session without running it.
    Check {
        /// The session file.
        session: PathBuf,
    },
    /// Print the constraint network of every garment the session builds: its curves, the
    /// matrix g_ij, and every constraint with its priority, direction and residual; then
    /// each drag's outcome.
    Constraints {
        /// The session file; without it, the built-in demo.
        session: Option<PathBuf>,
    },
    /// Refine the analytic dress form both ways (polar and chord-length cubic splines)
    /// and print each method's deviation from the true surface per region.
    Mannequin(MannequinArgs),
}

#[derive(Args, Debug, Default)]
struct RunArgs {
    /// Session file; without it, the built-in demo (assets/sessions/demo.drape).
    session: Option<PathBuf>,
    /// Use this body OBJ (metres, y up, facing +z) instead of the session's.
    #[arg(long, value_name = "OBJ")]
    body: Option<PathBuf>,
    /// Write the recording here [default: recordings/<session name>.rrd].
    #[arg(long, value_name = "PATH", conflicts_with_all = ["connect", "serve"])]
    save: Option<PathBuf>,
    /// Stream to a running viewer, e.g. rerun+http://host:9876/proxy.
    #[arg(long, value_name = "URL", conflicts_with = "serve")]
    connect: Option<String>,
    /// Serve the recording over gRPC for viewers to join (now or later) until Ctrl-C.
    #[arg(long)]
    serve: bool,
    /// Port for --serve.
    #[arg(long, default_value_t = 9876, requires = "serve")]
    port: u16,
    /// Write per-step metrics (timings, counts, figures) as a JSON array.
    #[arg(long, value_name = "PATH")]
    metrics: Option<PathBuf>,
    /// Write the body and every mesh a step produces as OBJ files into this folder.
    #[arg(long, value_name = "DIR")]
    export: Option<PathBuf>,
    /// Also log compute timings to the recording (makes recordings differ run to run).
    #[arg(long)]
    log_timings: bool,
    /// Check every collision against the brute-force ground truth (every garment vertex
    /// and edge against every body triangle; a few seconds per step). The figures go to
    /// the log, the metrics and the progress lines.
    #[arg(long)]
    verify: bool,
    /// Test every vertex point-face against every body triangle (no partitions, no BVH, no
    /// line-line), to compare.
    #[arg(long)]
    brute_force: bool,
    /// Re-test every vertex each step (no inert points, no patch skipping), to compare.
    #[arg(long)]
    no_skipping: bool,
}

#[derive(Args, Debug)]
struct MannequinArgs {
    /// Measured layers (rings) of the dress form.
    #[arg(long, default_value_t = 18, value_parser = clap::value_parser!(u16).range(4..=200))]
    layers: u16,
    /// Measured points per layer.
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u16).range(6..=360))]
    points: u16,
    /// Split every grid interval this many ways (the paper: 6).
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u16).range(1..=20))]
    subdivisions: u16,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    /// Log both surfaces, coloured by their distance to the true surface, to this recording.
    #[arg(long, value_name = "PATH", default_value = "recordings/mannequin.rrd")]
    save: PathBuf,
}

/// A command's failure: what kind (the exit code follows it) and the error with its context.
struct Failure {
    kind: FailureKind,
    error: anyhow::Error,
}

type Result<T> = std::result::Result<T, Failure>;

/// Sorts an error into bad input or drape's own failure.
trait Classify<T> {
    /// The input cannot be used (exit 2).
    fn bad_input(self) -> Result<T>;
    /// drape's own output failed (exit 3).
    fn internal(self) -> Result<T>;
}

impl<T, E: Into<anyhow::Error>> Classify<T> for std::result::Result<T, E> {
    fn bad_input(self) -> Result<T> {
        self.map_err(|e| Failure {
            kind: FailureKind::BadInput,
            error: e.into(),
        })
    }

    fn internal(self) -> Result<T> {
        self.map_err(|e| Failure {
            kind: FailureKind::Internal,
            error: e.into(),
        })
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => run(RunArgs::default()),
        Some(Command::Run(args)) => run(args),
        Some(Command::Check { session }) => check(&session),
        Some(Command::Constraints { session }) => constraints(session.as_deref()),
        Some(Command::Mannequin(args)) => mannequin(&args),
    };
    match result {
        Ok(code) => code,
        Err(Failure { kind, error }) => {
            eprintln!("error: {error:#}");
            ExitCode::from(kind.exit_code())
        }
    }
}

/// Reads and parses a session file, or the demo; a parse error is bad input.
fn load_session(path: Option<&Path>) -> Result<Session> {
    match path {
        Some(p) => {
            let text = std::fs::read_to_string(p)
                .with_context(|| format!("cannot read session {}", p.display()))
                .bad_input()?;
            let base = p.parent().unwrap_or(Path::new("."));
            parse_session(&text, &p.display().to_string(), base)
        }
        None => parse_session(DEMO_SESSION, DEMO_SESSION_NAME, Path::new(".")),
    }
    .bad_input()
}

fn check(path: &Path) -> Result<ExitCode> {
    match load_session(Some(path)) {
        Ok(s) => {
            println!(
                "{}: ok, body {} ({}), {} landmark override(s), {} step(s): {}",
                s.name,
                s.scene.body.name(),
                s.scene.units.name(),
                s.scene.landmarks.len(),
                s.steps.len(),
                s.steps.iter().map(|st| st.op.keyword()).collect::<Vec<_>>().join(", ")
            );
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => Err(e),
    }
}

/// Prints the constraint network of each garment built and each drag's outcome.
struct NetworkPrinter;

impl StageSink for NetworkPrinter {
    fn constraints(&mut self, info: &StageInfo, stage: ConstraintStage<'_>) -> std::result::Result<(), SinkError> {
        match stage {
            ConstraintStage::Network(fw, net) => {
                println!("step {} ({}):", info.step, info.op);
                println!(
                    "{}",
                    net.describe(fw, drape::constraint::SolverOptions::default().tolerance)
                );
            }
            ConstraintStage::Solve {
                edit, net, solution, ..
            } => println!("step {}: {}", info.step, solve_line(edit, net, solution)),
            ConstraintStage::Refused { message, .. } => println!("step {}: refused: {message}", info.step),
            _ => {}
        }
        Ok(())
    }

    fn step_end(&mut self, info: &StageInfo, end: StepEnd<'_>) -> std::result::Result<(), SinkError> {
        if let StepEnd::Failed(e) = end {
            println!("step {} FAILED: {}", info.step, e.message());
        }
        Ok(())
    }
}

fn solve_line(
    edit: &drape::constraint::Edit,
    net: &drape::constraint::ConstraintNet,
    s: &drape::constraint::Solution,
) -> String {
    let worst = s.max_residual();
    let violations = s.violation_lines(net);
    format!(
        "{edit}: {} iteration(s), {} pass(es), {}; largest residual {worst:.2e}{}",
        s.iterations.len(),
        s.passes,
        if s.converged { "converged" } else { "NOT converged" },
        if violations.is_empty() {
            String::new()
        } else {
            format!("; violated: {}", violations.join(", "))
        }
    )
}

fn constraints(path: Option<&Path>) -> Result<ExitCode> {
    let session = load_session(path)?;
    let mut printer = NetworkPrinter;
    let report = run_session(&session, &RunOptions::default(), &mut [&mut printer]);
    Ok(report
        .error
        .map_or(ExitCode::SUCCESS, |e| ExitCode::from(e.kind().exit_code())))
}

/// Prints each stage as it completes, so long runs show progress.
struct Progress;

impl StageSink for Progress {
    fn step_end(&mut self, info: &StageInfo, end: StepEnd<'_>) -> std::result::Result<(), SinkError> {
        match end {
            StepEnd::Done(m) => {
                let compute: f64 = m
                    .timings_ms
                    .iter()
                    .filter(|(k, _)| !k.starts_with("log."))
                    .map(|(_, v)| v)
                    .sum();
                let log: f64 = m
                    .timings_ms
                    .iter()
                    .filter(|(k, _)| k.starts_with("log."))
                    .map(|(_, v)| v)
                    .sum();
                // An empty sum is -0.0.
                let (compute, log) = (compute + 0.0, log + 0.0);
                eprintln!(
                    "  step {} {:<10} done: compute {compute:8.1} ms, logging {log:6.1} ms",
                    info.step, info.op
                );
            }
            StepEnd::Failed(e) => eprintln!("  step {} {} FAILED: {}", info.step, info.op, e.message()),
        }
        Ok(())
    }

    fn constraints(&mut self, info: &StageInfo, stage: ConstraintStage<'_>) -> std::result::Result<(), SinkError> {
        match stage {
            ConstraintStage::Solve {
                edit, net, solution, ..
            } => eprintln!("  step {} solve: {}", info.step, solve_line(edit, net, solution)),
            ConstraintStage::Refused { message, .. } => eprintln!("  step {} drag REFUSED: {message}", info.step),
            _ => {}
        }
        Ok(())
    }

    fn collision(&mut self, info: &StageInfo, stage: CollisionStage<'_>) -> std::result::Result<(), SinkError> {
        if stage.part != CollisionPart::Respond {
            return Ok(());
        }
        let outcome = stage.outcome;
        let c = &outcome.collision;
        let d = &c.detection;
        eprintln!(
            "  step {} collision: {} tested, {} inert, {} patch-skipped; {} hits -> {} moved; after: {} inside, {} crossing edges",
            info.step,
            d.tested,
            d.skipped_inert,
            d.skipped_patch,
            d.hits.len(),
            c.responses.len(),
            c.quality.penetrating_vertices,
            c.quality.crossing_edges
        );
        if let Some(v) = &outcome.verify {
            eprintln!(
                "  step {} verify: truth {} inside before, detection missed {} (line-line {}), false hits {} (line-line {}); after: {} inside, {} crossing; quality agrees: {}",
                info.step,
                v.inside_before,
                v.missed,
                v.missed_line_line,
                v.false_hits,
                v.false_line_line,
                v.inside_after,
                v.crossing_after,
                v.quality_agrees
            );
        }
        Ok(())
    }
}

/// Writes `bytes` to `path` through a temporary file and a rename.
fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let tmp = partial_path(path);
    std::fs::write(&tmp, bytes).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("cannot rename {} to {}", tmp.display(), path.display()))
}

fn partial_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(".partial");
    path.with_file_name(name)
}

fn create_parent(path: &Path) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    Ok(())
}

fn session_stem(session: &Session) -> String {
    Path::new(&session.name)
        .file_stem()
        .map_or_else(|| "session".into(), |s| s.to_string_lossy().into_owned())
}

fn host_name() -> String {
    std::env::var("HOSTNAME")
        .ok()
        .or_else(|| std::fs::read_to_string("/etc/hostname").ok())
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "localhost".into())
}

fn run(args: RunArgs) -> Result<ExitCode> {
    let session = load_session(args.session.as_deref())?;
    if let Some(body) = &args.body
        && !body.is_file()
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
    let target = if let Some(url) = &args.connect {
        RecordingTarget::Connect(url.clone())
    } else if args.serve {
        RecordingTarget::Serve(args.port)
    } else {
        create_parent(&final_path).internal()?;
        RecordingTarget::File(partial_path(&final_path))
    };
    let rec = open_recording(&target, &stem)
        .context("cannot open the recording")
        .internal()?;
    if args.serve {
        println!("serving on port {}; open it from any machine with:", args.port);
        println!("  rerun rerun+http://{}:{}/proxy", host_name(), args.port);
    }
    eprintln!("running {} ({} step(s))", session.name, session.steps.len());
    let mut logger = RerunLogger::new(rec, LogOptions::default().with_timings(args.log_timings)).internal()?;
    let mut exporter = args.export.clone().map(ObjExporter::new).transpose().internal()?;
    let mut progress = Progress;
    let mut options = RunOptions {
        body_override: args.body.clone(),
        verify: args.verify,
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
    if args.serve {
        logger.recording().flush_blocking().ok();
        println!("all data sent; still serving for late viewers. Press Ctrl-C to stop.");
        std::io::stdout().flush().ok();
        loop {
            std::thread::sleep(std::time::Duration::from_secs(3600));
        }
    }
    if let Some(url) = &args.connect {
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
    match report.error {
        Some(e) => {
            eprintln!("error: {e}");
            Ok(ExitCode::from(e.kind().exit_code()))
        }
        None => Ok(ExitCode::SUCCESS),
    }
}

fn mannequin(args: &MannequinArgs) -> Result<ExitCode> {
    let options = MannequinOptions::grid(usize::from(args.layers), usize::from(args.points))
        .with_subdivisions(usize::from(args.subdivisions));
    let result = run_mannequin(&DressForm::default(), &options).bad_input()?;
    let ordered: Vec<_> = Region::REPORT_ORDER
        .iter()
        .filter_map(|r| result.regions.iter().find(|e| e.region == r.name()))
        .collect();
    if args.json {
        let regions: Vec<_> = ordered
            .iter()
            .map(|e| {
                serde_json::json!({"region": e.region, "polar": {"max_m": e.polar.max_m, "rms_m": e.polar.rms_m},
                                        "chord": {"max_m": e.chord.max_m, "rms_m": e.chord.rms_m}})
            })
            .collect();
        let out = serde_json::json!({"layers": options.layers, "points": options.points, "regions": regions});
        println!("{}", serde_json::to_string_pretty(&out).internal()?);
    } else {
        println!(
            "dress form {} layers x {} points, refined to {} x {} (k = {}); deviation from the true surface, mm",
            options.layers, options.points, result.polar.points, result.polar.layers, options.subdivisions
        );
        println!(
            "{:<9} {:>10} {:>10} {:>10} {:>10}   better",
            "region", "polar max", "polar rms", "chord max", "chord rms"
        );
        for e in &ordered {
            let better = if e.chord.max_m < e.polar.max_m {
                "chord"
            } else {
                "polar"
            };
            let [pm, pr, cm, cr] = e.millimetres();
            println!("{:<9} {pm:>10.3} {pr:>10.3} {cm:>10.3} {cr:>10.3}   {better}", e.region);
        }
    }
    let path = &args.save;
    let partial = partial_path(path);
    create_parent(path).internal()?;
    {
        let rec = open_recording(&RecordingTarget::File(partial.clone()), "mannequin").internal()?;
        let mut logger = RerunLogger::new(rec, LogOptions::default().with_mannequin_offset_x(-0.3)).internal()?;
        let info = StageInfo {
            step: 1,
            op: "mannequin",
            stage: 0,
            name: "mannequin.refine",
        };
        logger.stage(&info, Stage::Mannequin(&result)).internal()?;
    }
    std::fs::rename(&partial, path)
        .with_context(|| format!("cannot rename {} to {}", partial.display(), path.display()))
        .internal()?;
    eprintln!("recording: {}", path.display());
    Ok(ExitCode::SUCCESS)
}
