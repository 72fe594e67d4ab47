//! The `drape` command line: run a session (the demo by default), check one, or measure
//! the mannequin refinements.

mod args;
mod bench;
mod check_garment;
mod edit;
mod failure;
mod files;
mod flatten;
mod interrupt;
mod live;
mod mannequin;
mod network;
mod nurbs;
mod progress;
mod replay;
mod run;
mod sculpt;
mod stress;

use std::path::Path;
use std::process::ExitCode;

use anyhow::Context as _;
use clap::Parser as _;
use drape::body::index_cache::IndexCache;
use drape::session::{DEMO_SESSION, DEMO_SESSION_NAME, Session, parse_session};

use args::{Cli, Command, RunArgs};
use failure::{Classify, Failure, Result};

fn main() -> ExitCode {
    let cli = Cli::parse();
    MAX_INPUT_BYTES.store(
        cli.max_input_mb.saturating_mul(1024 * 1024),
        std::sync::atomic::Ordering::Relaxed,
    );
    UNDO_LIMIT.store(cli.undo_limit as usize, std::sync::atomic::Ordering::Relaxed);
    if let Some(n) = cli.threads {
        drape::par::set_threads(usize::from(n));
    }
    let cache = match (cli.no_index_cache, &cli.index_cache) {
        (true, _) => None,
        (false, Some(dir)) => Some(IndexCache::new(dir)),
        (false, None) => IndexCache::default_dir().map(IndexCache::new),
    };
    let _ = INDEX_CACHE.set(cache);
    let result = match cli.command {
        None => run::run(RunArgs::default()),
        Some(Command::Run(args)) => run::run(args),
        Some(Command::Check { session }) => check(&session),
        Some(Command::Constraints { session }) => network::constraints(session.as_deref()),
        Some(Command::Mannequin(args)) => mannequin::mannequin(&args),
        Some(Command::NurbsExperiment(args)) => nurbs::experiment(&args),
        Some(Command::SculptCompare(args)) => sculpt::compare_command(&args),
        Some(Command::Replay(args)) => replay::replay(&args),
        Some(Command::Stress(args)) => stress::stress(&args),
        Some(Command::Edit(args)) => edit::edit(&args),
        Some(Command::Flatten(args)) => flatten::flatten(&args),
        Some(Command::CheckGarment(args)) => check_garment::check_garment(&args),
        Some(Command::Bench(args)) => bench::bench(&args).map(|()| ExitCode::SUCCESS).internal(),
    };
    match result {
        Ok(code) => code,
        Err(Failure { kind, error }) => {
            eprintln!("error: {error:#}");
            ExitCode::from(kind.exit_code())
        }
    }
}

/// The input limit of this run, bytes (`--max-input-mb`).
static MAX_INPUT_BYTES: std::sync::atomic::AtomicU64 =
    std::sync::atomic::AtomicU64::new(drape::input::DEFAULT_MAX_INPUT_BYTES);

/// The largest input file read, bytes.
fn max_input_bytes() -> u64 {
    MAX_INPUT_BYTES.load(std::sync::atomic::Ordering::Relaxed)
}

/// How many edits `undo` can take back in this run (`--undo-limit`).
static UNDO_LIMIT: std::sync::atomic::AtomicUsize =
    std::sync::atomic::AtomicUsize::new(drape::session::DEFAULT_UNDO_LIMIT);

/// How many edits `undo` can take back.
fn undo_limit() -> usize {
    UNDO_LIMIT.load(std::sync::atomic::Ordering::Relaxed)
}

/// The body index cache of this run (`--index-cache`, `--no-index-cache`).
static INDEX_CACHE: std::sync::OnceLock<Option<IndexCache>> = std::sync::OnceLock::new();

/// Where this run keeps body indexes (`None`: built every run).
fn index_cache() -> Option<IndexCache> {
    INDEX_CACHE.get().cloned().flatten()
}

/// Reads and parses a session file (a regular file within the input limit), or the demo; a
/// parse error is bad input.
fn load_session(path: Option<&Path>) -> Result<Session> {
    match path {
        Some(p) => {
            let text = drape::input::read_text(p, max_input_bytes())
                .context("cannot read the session")
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
