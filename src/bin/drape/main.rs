//! The `drape` command line: run a session (the demo by default), check one, or measure
//! the mannequin refinements.

mod args;
mod failure;
mod files;
mod mannequin;
mod network;
mod progress;
mod run;

use std::path::Path;
use std::process::ExitCode;

use anyhow::Context as _;
use clap::Parser as _;
use drape::session::{DEMO_SESSION, DEMO_SESSION_NAME, Session, parse_session};

use args::{Cli, Command, RunArgs};
use failure::{Classify, Failure, Result};

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => run::run(RunArgs::default()),
        Some(Command::Run(args)) => run::run(args),
        Some(Command::Check { session }) => check(&session),
        Some(Command::Constraints { session }) => network::constraints(session.as_deref()),
        Some(Command::Mannequin(args)) => mannequin::mannequin(&args),
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
