//! Stress: random edit sessions on every body, each judged for panics, NaN and infinite
//! outputs, and garments left in the body; refusals and failures counted by reason; solves
//! and step times gathered. Sessions are numbered under a seed and each draws from its own
//! stream, so any share of them (a shard) runs alone and shards merge into the whole.
//!
//! A session that finds a bug is written out; [`shrink`] cuts it down to the fewest steps
//! that still show the same kind of bug, for a regression test.

pub mod generate;
pub mod outcome;
pub mod report;
pub mod rng;
pub mod verified;
pub mod watch;

use std::path::{Path, PathBuf};

pub use generate::{GenerateOptions, session_text};
pub use outcome::{SessionOutcome, reason_of, run_one};
pub use report::{Record, Report, Totals, VerifiedTotals};
pub use rng::Rng;
pub use verified::Verified;

/// A stress sweep.
#[derive(Clone, Debug)]
pub struct StressOptions {
    /// Sessions per body. Default 20.
    pub sessions: u64,
    /// The seed. Default 1.
    pub seed: u64,
    /// What each session contains.
    pub generate: GenerateOptions,
    /// This run's share: shard `i` of `n` runs the sessions whose index is `i` modulo `n`.
    /// Default `(0, 1)`: every session.
    pub shard: (u64, u64),
    /// Check every collision against the brute-force truth and a full quality check (slow:
    /// seconds a step). Default false.
    pub verify: bool,
}

impl Default for StressOptions {
    fn default() -> Self {
        Self {
            sessions: 20,
            seed: 1,
            generate: GenerateOptions::default(),
            shard: (0, 1),
            verify: false,
        }
    }
}

/// The sessions of `body` this shard runs: `(index, text)`.
pub fn sessions_of(options: &StressOptions) -> Vec<(u64, String)> {
    let (i, n) = options.shard;
    (0..options.sessions)
        .filter(|k| k % n.max(1) == i)
        .map(|k| {
            (
                k,
                session_text(&mut Rng::for_session(options.seed, k), &options.generate),
            )
        })
        .collect()
}

/// Runs the shard's sessions on every body (`None`: the built-in body), calling `progress`
/// after each; a session that finds a bug is written by `save` (which returns where). The
/// report is sorted.
pub fn run(
    bodies: &[Option<PathBuf>],
    options: &StressOptions,
    mut progress: impl FnMut(&str, u64, &SessionOutcome),
    mut save: impl FnMut(Option<&Path>, u64, &str, &SessionOutcome) -> Option<String>,
) -> Report {
    let sessions = sessions_of(options);
    let mut records = Vec::new();
    for body in bodies {
        let name = body_name(body.as_deref());
        for (k, text) in &sessions {
            let outcome = run_one(text, body.as_deref(), options.verify);
            progress(&name, *k, &outcome);
            let saved = if outcome.is_bug() {
                save(body.as_deref(), *k, text, &outcome)
            } else {
                None
            };
            records.push(Record {
                body: name.clone(),
                session: *k,
                outcome,
                saved,
            });
        }
    }
    records.sort_by(|a, b| (&a.body, a.session).cmp(&(&b.body, b.session)));
    Report {
        seed: options.seed,
        sessions_per_body: options.sessions,
        steps_per_session: options.generate.steps,
        shards: vec![[options.shard.0, options.shard.1]],
        records,
    }
}

/// A body's name in reports: its file name, or `builtin`.
pub fn body_name(body: Option<&Path>) -> String {
    body.and_then(Path::file_name)
        .map_or_else(|| "builtin".to_string(), |n| n.to_string_lossy().into_owned())
}

/// The kind of bug, for shrinking: a shrunk session must show the same kind.
fn bug_kind(o: &SessionOutcome) -> Option<&'static str> {
    if o.panic.is_some() {
        Some("panic")
    } else if !o.non_finite.is_empty() {
        Some("non-finite")
    } else if !o.guarantee_failures.is_empty() {
        Some("guarantee")
    } else if !o.verified.wrong_quality.is_empty() || !o.verified.partial_differs.is_empty() {
        Some("quality check")
    } else {
        None
    }
}

/// Cuts session `text` down to the fewest steps that still show the bug it shows on `body`
/// (greedy: drop one step at a time, last first, keep the drop when the bug stays; repeat
/// until no step can go; with `verify`, each run checked as `drape stress --verify` checks
/// it). Returns the text unchanged when it shows no bug.
pub fn shrink(text: &str, body: Option<&Path>, verify: bool) -> String {
    let Some(kind) = bug_kind(&run_one(text, body, verify)) else {
        return text.to_string();
    };
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let first_step = lines
        .iter()
        .position(|l| l.starts_with("garment "))
        .map_or(lines.len(), |g| g + 1);
    loop {
        let mut changed = false;
        let mut k = lines.len();
        while k > first_step {
            k -= 1;
            let mut candidate = lines.clone();
            candidate.remove(k);
            let joined = candidate.join("\n") + "\n";
            if bug_kind(&run_one(&joined, body, verify)) == Some(kind) {
                lines = candidate;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    lines.join("\n") + "\n"
}
