//! `drape stress`: random edit sessions on every body, judged; `drape stress merge`: the
//! reports of shards joined.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context as _;
use drape::stress::{GenerateOptions, Report, SessionOutcome, StressOptions, body_name, shrink};

use crate::args::{StressArgs, StressCommand};
use crate::failure::{Classify, Result};
use crate::files::write_atomic;

pub(crate) fn stress(args: &StressArgs) -> Result<ExitCode> {
    if let Some(StressCommand::Merge { reports, json }) = &args.command {
        return merge(reports, *json);
    }
    let generate = GenerateOptions {
        steps: args.steps,
        ..GenerateOptions::default()
    };
    if let Some(k) = args.show {
        print!(
            "{}",
            drape::stress::session_text(&mut drape::stress::Rng::for_session(args.seed, k), &generate)
        );
        return Ok(ExitCode::SUCCESS);
    }
    let bodies = bodies(args.bodies.as_deref())?;
    let (i, n) = args.shard;
    let options = StressOptions {
        sessions: args.sessions,
        seed: args.seed,
        generate,
        shard: (i, n),
        verify: args.verify,
    };
    // Panics are caught and reported per session; the default hook's message would only
    // interleave with the progress lines.
    std::panic::set_hook(Box::new(|_| {}));
    let total = bodies.len() as u64 * (options.sessions / n + u64::from(options.sessions % n > i));
    let mut done = 0u64;
    eprintln!(
        "stress: {} session(s) of {} step(s) on {} body(ies), seed {}, shard {i}/{n}{}",
        total,
        options.generate.steps,
        bodies.len(),
        options.seed,
        if options.verify {
            ", every collision verified"
        } else {
            ""
        }
    );
    let out_dir = args.out.clone();
    let report = drape::stress::run(
        &bodies,
        &options,
        |body, k, o: &SessionOutcome| {
            done += 1;
            eprintln!(
                "  [{done}/{total}] {body} session {k}: {} steps, {} refused{}{}",
                o.steps,
                o.refused.len(),
                o.failed.as_deref().map_or(String::new(), |f| format!(", failed: {f}")),
                if o.is_bug() {
                    format!(", BUG: {}", drape::stress::report::bug_summary(o))
                } else {
                    String::new()
                }
            );
        },
        |body, k, text, _| save_case(&out_dir, body, options.seed, k, text, args.no_shrink, args.verify).ok(),
    );
    let _ = std::panic::take_hook();
    print_report(&report, args.json, args.report.as_deref())
}

fn print_report(report: &Report, json: bool, file: Option<&Path>) -> Result<ExitCode> {
    let text = serde_json::to_string_pretty(&report.json()).internal()?;
    if let Some(path) = file {
        write_atomic(path, text.as_bytes()).internal()?;
        eprintln!("report: {}", path.display());
    }
    if json {
        println!("{text}");
    } else {
        print!("{}", report.text());
    }
    Ok(if report.overall().has_bugs() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

fn merge(paths: &[PathBuf], json: bool) -> Result<ExitCode> {
    let mut reports = Vec::new();
    for p in paths {
        let text = std::fs::read_to_string(p)
            .with_context(|| format!("cannot read {}", p.display()))
            .bad_input()?;
        let r: Report = serde_json::from_str(&text)
            .with_context(|| format!("{}: not a stress report", p.display()))
            .bad_input()?;
        reports.push(r);
    }
    let merged = Report::merge(reports).map_err(|e| anyhow::anyhow!(e)).bad_input()?;
    print_report(&merged, json, None)
}

/// The bodies: every `.obj` in `dir`, sorted, or the built-in body.
fn bodies(dir: Option<&Path>) -> Result<Vec<Option<PathBuf>>> {
    let Some(dir) = dir else {
        return Ok(vec![None]);
    };
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("--bodies {}: cannot list", dir.display()))
        .bad_input()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("obj")))
        .collect();
    out.sort();
    if out.is_empty() {
        return Err(anyhow::anyhow!("--bodies {}: no .obj file", dir.display())).bad_input();
    }
    Ok(out.into_iter().map(Some).collect())
}

/// Writes a session that found a bug (shrunk unless asked not to) into `dir`, its body
/// named relative to the file so that `drape run FILE` replays it from anywhere.
fn save_case(
    dir: &Path,
    body: Option<&Path>,
    seed: u64,
    k: u64,
    text: &str,
    no_shrink: bool,
    verify: bool,
) -> anyhow::Result<String> {
    let text = if no_shrink {
        text.to_string()
    } else {
        shrink(text, body, verify)
    };
    let stem = body_name(body);
    let stem = stem.trim_end_matches(".obj");
    let path = dir.join(format!("{stem}-seed{seed}-session{k}.drape"));
    let body_line = match body {
        None => "body builtin".to_string(),
        Some(b) => format!("body {}", relative_to(dir, b).display()),
    };
    let text = text.replacen("body builtin", &body_line, 1);
    write_atomic(&path, text.as_bytes())?;
    Ok(path.display().to_string())
}

/// `target` as seen from `dir` when both are relative to the working directory (absolute
/// when either is absolute).
fn relative_to(dir: &Path, target: &Path) -> PathBuf {
    if dir.is_absolute() || target.is_absolute() {
        return std::fs::canonicalize(target).unwrap_or_else(|_| target.to_path_buf());
    }
    let ups = dir
        .components()
        .filter(|c| matches!(c, std::path::Component::Normal(_)))
        .count();
    let mut out = PathBuf::new();
    for _ in 0..ups {
        out.push("..");
    }
    out.join(target)
}
