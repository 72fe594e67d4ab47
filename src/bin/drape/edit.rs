//! `drape edit [SESSION]`: an edit session typed (or piped) line by line. Each line is a
//! step in the session syntax, checked against everything before it and applied at once
//! (logged live to the recording, a viewer or a server); a line that does not parse or a
//! step that fails is reported and the session goes on as it was. Commands: `help`,
//! `show`, `save NAME` (writes `recordings/NAME/` with the session file, its recording and
//! manifest; a NAME with a `/` is a folder path), `quit`. `undo` is a step like any other.

use std::io::{BufRead, Write as _};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context as _;
use drape::session::{LiveSession, RunOptions, StageSink, parse_session};
use drape::viz::{LogOptions, RecordingTarget, RerunLogger, open_recording};

use crate::args::EditArgs;
use crate::failure::{Classify, Result};
use crate::files::{partial_path, write_atomic};
use crate::progress::Progress;

const HELP: &str = "Type a step in the session syntax, e.g.\n  garment jumpsuit fit=tight resolution=6\n  set waist_girth +0.02\n  drag waist.front by=0,0,-0.01\n  undo\nCommands: help, show (the session so far), save NAME (recordings/NAME/: session, \
recording, manifest), quit (or end of input).";

pub(crate) fn edit(args: &EditArgs) -> Result<ExitCode> {
    let (mut text, base) = match &args.session {
        Some(p) => (
            drape::input::read_text(p, crate::max_input_bytes())
                .context("cannot read the session")
                .bad_input()?,
            p.parent().unwrap_or(Path::new(".")).to_path_buf(),
        ),
        None => ("drape 1\n".to_string(), PathBuf::from(".")),
    };
    if !text.ends_with('\n') {
        text.push('\n');
    }
    let name = "edit";
    let session = parse_session(&text, name, &base).bad_input()?;
    let target = match (&args.viewer.connect, args.viewer.serve) {
        (Some(url), _) => RecordingTarget::Connect(url.clone()),
        (None, true) => RecordingTarget::Serve(args.viewer.port),
        (None, false) => RecordingTarget::File(partial_path(&args.save)),
    };
    let rec = open_recording(&target, name)
        .context("cannot open the recording")
        .internal()?;
    let mut logger = RerunLogger::new(rec, LogOptions::default()).internal()?;
    let mut progress = Progress;
    let mut sinks: Vec<&mut dyn StageSink> = vec![&mut progress, &mut logger];
    let options = RunOptions {
        max_input_bytes: crate::max_input_bytes(),
        ..RunOptions::default()
    };
    let mut live = match LiveSession::start(&session, options, &mut sinks) {
        Ok(live) => live,
        Err(report) => {
            let e = report.error.map_or_else(String::new, |e| e.to_string());
            return Err(anyhow::anyhow!(e)).bad_input();
        }
    };
    // The session file's own steps first; the text kept (what `save` writes) is its scene
    // and the steps that ran.
    let lines: Vec<&str> = text.lines().collect();
    let first = session.steps.first().map_or(lines.len(), |s| s.line - 1);
    let mut kept: String = lines[..first].iter().map(|l| format!("{l}\n")).collect();
    for step in &session.steps {
        match live.step(step) {
            Ok(()) => {
                kept.push_str(lines[step.line - 1]);
                kept.push('\n');
            }
            Err(e) => eprintln!("error: {e}"),
        }
    }
    let stdin = std::io::stdin();
    let prompt = || {
        eprint!("drape> ");
        std::io::stderr().flush().ok();
    };
    prompt();
    for line in stdin.lock().lines() {
        let line = line.context("cannot read the input").internal()?;
        let typed = line.trim();
        match typed.split_whitespace().next() {
            None => {}
            Some("quit" | "exit") => break,
            Some("help") => eprintln!("{HELP}"),
            Some("show") => {
                eprintln!("{kept}");
                eprintln!("({} step(s) ran)", live.session().steps.len());
            }
            Some("save") => match typed.split_whitespace().nth(1) {
                Some(to) => match save(to, &kept) {
                    Ok(dir) => eprintln!("saved {}", dir.display()),
                    Err(e) => eprintln!("error: cannot save: {e:#}"),
                },
                None => eprintln!("error: save NAME (recordings/NAME/) or save FOLDER/NAME"),
            },
            Some(_) => {
                let candidate = format!("{kept}{typed}\n");
                match parse_session(&candidate, name, &base) {
                    Err(e) => eprintln!("error: {}", e.message),
                    Ok(parsed) => match parsed.steps.last() {
                        Some(step) if parsed.steps.len() > live.session().steps.len() => match live.step(step) {
                            Ok(()) => kept = candidate,
                            Err(e) => eprintln!("error: {e}"),
                        },
                        _ => eprintln!("error: not a step (scene statements belong in the session file)"),
                    },
                }
            }
        }
        prompt();
    }
    eprintln!();
    let report = live.finish();
    drop(sinks);
    drop(logger);
    if let RecordingTarget::File(partial) = &target {
        std::fs::rename(partial, &args.save)
            .with_context(|| format!("cannot rename {}", partial.display()))
            .internal()?;
        eprintln!("recording: {}", args.save.display());
    }
    Ok(if report.error.is_some() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// Writes the session so far into `recordings/NAME/` (or the folder `to` when it has a
/// `/`) and records it there (recording and manifest).
fn save(to: &str, text: &str) -> anyhow::Result<PathBuf> {
    let dir = if to.contains('/') {
        PathBuf::from(to)
    } else {
        Path::new("recordings").join(to)
    };
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    write_atomic(&dir.join("session.drape"), text.as_bytes())?;
    let args = crate::args::ReplayArgs {
        dir: dir.clone(),
        tolerance: 0.0,
        write: true,
        serve: false,
        port: 9876,
    };
    crate::replay::replay(&args).map_err(|f| f.error)?;
    Ok(dir)
}
