//! `drape edit [SESSION]`: an edit session typed (or piped) line by line. Each line is a
//! step in the session syntax, checked against everything before it and applied at once
//! (logged live to the recording, a viewer or a server); a line that does not parse or a
//! step that fails is reported and the session goes on as it was. Commands: `help`,
//! `show`, `save NAME` (writes `recordings/NAME/` with the session file, its recording and
//! manifest; a NAME with a `/` is a folder path), `quit`. `undo` is a step like any other.

use std::io::BufRead as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context as _;
use drape::session::{LiveSession, RunOptions, StageSink, parse_session};
use drape::viz::{LogOptions, RerunLogger};

use crate::args::EditArgs;
use crate::failure::{Classify, Result};
use crate::files::write_atomic;
use crate::live::open_live;
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
    let live_rec = open_live(&args.viewer, Some(&args.save), name)?;
    let mut logger = RerunLogger::new(live_rec.rec.clone(), LogOptions::default()).internal()?;
    let mut progress = Progress;
    let mut sinks: Vec<&mut dyn StageSink> = vec![&mut progress, &mut logger];
    let options = RunOptions {
        max_input_bytes: crate::max_input_bytes(),
        index_cache: crate::index_cache(),
        undo_limit: crate::undo_limit(),
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
    let mut input = LineSource::new();
    while let Some(line) = input.next_line().internal()? {
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
    }
    eprintln!();
    input.save_history();
    let report = live.finish();
    drop(sinks);
    drop(logger);
    // A server keeps serving late viewers until Ctrl-C (the handler is installed only now,
    // so that Ctrl-C while typing still ends the program at once).
    let stop = if args.viewer.serve || args.viewer.serve_web {
        crate::interrupt::stop_flag()
    } else {
        std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true))
    };
    if let Some(path) = live_rec.finish(&stop)? {
        eprintln!("recording: {}", path.display());
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
        serve_web: false,
        port: 9876,
        web_port: 9090,
        bind: crate::args::LOCAL,
    };
    crate::replay::replay(&args).map_err(|f| f.error)?;
    Ok(dir)
}

/// Where typed lines come from: a terminal, with line editing and a history kept across
/// sessions (`~/.drape_history`), or a pipe, read plainly.
enum LineSource {
    Terminal(Box<rustyline::DefaultEditor>),
    Pipe(std::io::Lines<std::io::StdinLock<'static>>),
}

/// The history file of `drape edit` at a terminal.
fn history_path() -> Option<PathBuf> {
    std::env::var_os("HOME").map(|h| Path::new(&h).join(".drape_history"))
}

impl LineSource {
    fn new() -> Self {
        use std::io::IsTerminal as _;
        if std::io::stdin().is_terminal()
            && let Ok(mut editor) = rustyline::DefaultEditor::new()
        {
            if let Some(path) = history_path() {
                editor.load_history(&path).ok(); // none yet is fine
            }
            return Self::Terminal(Box::new(editor));
        }
        Self::Pipe(std::io::stdin().lock().lines())
    }

    /// The next line, or `None` at the end of the input (Ctrl-D, or Ctrl-C at the prompt).
    fn next_line(&mut self) -> anyhow::Result<Option<String>> {
        match self {
            Self::Terminal(editor) => match editor.readline("drape> ") {
                Ok(line) => {
                    if !line.trim().is_empty() {
                        editor.add_history_entry(line.as_str()).ok();
                    }
                    Ok(Some(line))
                }
                Err(rustyline::error::ReadlineError::Eof | rustyline::error::ReadlineError::Interrupted) => Ok(None),
                Err(e) => Err(anyhow::anyhow!(e).context("cannot read the terminal")),
            },
            Self::Pipe(lines) => lines.next().transpose().context("cannot read the input"),
        }
    }

    fn save_history(&mut self) {
        if let (Self::Terminal(editor), Some(path)) = (self, history_path())
            && let Err(e) = editor.save_history(&path)
        {
            eprintln!("note: history not saved to {}: {e}", path.display());
        }
    }
}
