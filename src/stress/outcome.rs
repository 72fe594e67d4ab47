//! One stress session run and judged: its steps accepted, refused (by reason) or failed, a
//! panic caught, non-finite outputs, guarantee failures, solves and step times.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::collision::Misses;
use crate::convergence::{self, Tallies};
use crate::session::{RunOptions, Shortfall, parse_session, run_session};

use super::watch::Watch;

/// What became of one session.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
pub struct SessionOutcome {
    /// Steps after the scene that ran (refused ones included).
    pub steps: usize,
    /// Steps refused, by reason (the message with names and numbers blanked).
    pub refused: Vec<String>,
    /// The error that stopped the session, if one did.
    pub failed: Option<String>,
    /// The panic message, if the session panicked.
    pub panic: Option<String>,
    /// Places where a step's output held NaN or an infinity (`step N: place`).
    pub non_finite: Vec<String>,
    /// Steps after which the garment was left inside the body or crossing it.
    pub guarantee_failures: Vec<usize>,
    /// Solves: (converged, passes, largest residual).
    pub solves: Vec<(bool, usize, f64)>,
    /// Compute ms of every finished step after the scene.
    pub step_ms: Vec<f64>,
    /// The session did not parse (a generator bug: reported, never expected).
    pub parse_error: Option<String>,
    /// Why the iterative loops stopped, by loop (see [`crate::convergence`]).
    #[serde(default)]
    pub loops: Tallies,
    /// With `--verify`: each collision against the brute-force truth and a full check.
    #[serde(default)]
    pub verified: Verified,
}

/// The collisions of a session checked (`drape stress --verify`): detection and the quality
/// check against the brute-force ground truth, and the step's quality check (partial: only
/// what moved) against a full one of every vertex and edge, with the time of each.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
pub struct Verified {
    /// Collisions checked.
    pub collisions: usize,
    /// Garment vertices and edges checked, summed over them.
    pub vertices: usize,
    /// Garment edges checked, summed.
    pub edges: usize,
    /// Vertices inside before the response (the truth), summed.
    #[serde(default)]
    pub inside: usize,
    /// Vertices inside before the response that detection did not report.
    pub missed: usize,
    /// The missed by cause.
    #[serde(default)]
    pub missed_by: Misses,
    /// Verdicts the inert and patch skips changed (against a detection testing every vertex).
    #[serde(default)]
    pub skips_changed: usize,
    /// Vertices detection reported that were not inside.
    pub false_hits: usize,
    /// Steps whose quality check did not find exactly the truth's inside vertices and
    /// crossing edges.
    pub wrong_quality: Vec<usize>,
    /// Steps whose quality check differed in anything from a full one.
    pub partial_differs: Vec<usize>,
    /// The step's quality check, ms, per collision.
    pub quality_ms: Vec<f64>,
    /// The full check of the same positions, ms, per collision.
    pub full_quality_ms: Vec<f64>,
}

impl Verified {
    /// Adds the collisions of `other`.
    pub fn absorb(&mut self, other: Verified) {
        self.collisions += other.collisions;
        self.vertices += other.vertices;
        self.edges += other.edges;
        self.inside += other.inside;
        self.missed += other.missed;
        self.missed_by.add(&other.missed_by);
        self.skips_changed += other.skips_changed;
        self.false_hits += other.false_hits;
        self.wrong_quality.extend(other.wrong_quality);
        self.partial_differs.extend(other.partial_differs);
        self.quality_ms.extend(other.quality_ms);
        self.full_quality_ms.extend(other.full_quality_ms);
    }
}

impl SessionOutcome {
    /// A failure a stress run must report as a bug: a panic, a non-finite output, a
    /// guarantee failure or a session that did not parse.
    pub fn is_bug(&self) -> bool {
        self.panic.is_some()
            || !self.non_finite.is_empty()
            || !self.guarantee_failures.is_empty()
            || self.parse_error.is_some()
            || !self.verified.wrong_quality.is_empty()
            || !self.verified.partial_differs.is_empty()
    }
}

/// The reason class of a refusal or failure message: quoted names, numbers and anything in
/// parentheses blanked, so that refusals of the same kind count together.
pub fn reason_of(message: &str) -> String {
    let mut out = String::new();
    let mut depth = 0usize;
    let mut quoted = false;
    let mut last_number = false;
    let mut prev = ' ';
    for ch in message.chars() {
        let before = std::mem::replace(&mut prev, ch);
        match ch {
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            _ if depth > 0 => {}
            // A quote opens after a space (an apostrophe follows a letter) and closes the name.
            '\'' if quoted || before.is_whitespace() => {
                if !quoted {
                    out.push('*');
                }
                quoted = !quoted;
            }
            _ if quoted => {}
            c if c.is_ascii_digit() || ((c == '.' || c == '-' || c == '+') && last_number) => {
                if !last_number {
                    out.push('#');
                }
                last_number = true;
                continue;
            }
            c => out.push(c),
        }
        last_number = false;
    }
    let collapsed: Vec<&str> = out.split_whitespace().collect();
    collapsed.join(" ").trim_end_matches([':', ',', ' ']).to_string()
}

/// Runs session `text` on `body` (its own body, the built-in one, when `None`) and judges
/// it. A panic anywhere in the run is caught and reported (the caller may silence the
/// default panic message with a hook).
pub fn run_one(text: &str, body: Option<&Path>, verify: bool) -> SessionOutcome {
    let session = match parse_session(text, "stress.drape", Path::new(".")) {
        Ok(s) => s,
        Err(e) => {
            return SessionOutcome {
                parse_error: Some(e.to_string()),
                ..SessionOutcome::default()
            };
        }
    };
    let options = RunOptions {
        body_override: body.map(Path::to_path_buf),
        verify,
        ..RunOptions::default()
    };
    let mut watch = Watch::default();
    let (result, loops) = convergence::collect(|| {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            run_session(&session, &options, &mut [&mut watch])
        }))
    });
    let mut out = SessionOutcome {
        loops,
        ..SessionOutcome::default()
    };
    match result {
        Err(payload) => {
            out.panic = Some(
                payload
                    .downcast_ref::<&str>()
                    .map(|s| (*s).to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "panic with a non-text payload".into()),
            );
        }
        Ok(report) => {
            out.steps = report.steps.iter().filter(|s| s.step > 0).count();
            for (step, shortfall) in &report.shortfalls {
                match shortfall {
                    Shortfall::Guarantee { .. } => out.guarantee_failures.push(*step),
                    Shortfall::Refused(message) => out.refused.push(reason_of(message)),
                }
            }
            out.failed = report.error.map(|e| reason_of(&e.to_string()));
        }
    }
    out.non_finite = watch
        .non_finite
        .iter()
        .map(|n| format!("step {}: {}", n.step, n.place))
        .collect();
    out.solves = watch
        .solves
        .iter()
        .map(|s| (s.converged, s.passes, s.max_residual))
        .collect();
    out.step_ms = watch.step_ms;
    out.verified = watch.verified;
    out
}

#[cfg(test)]
mod tests {
    use super::reason_of;

    #[test]
    fn reasons_blank_names_numbers_and_parentheses() {
        assert_eq!(
            reason_of(
                "curve 'waist' would cross itself (segments 8 and 30 meet at (0.09, 1.02, 0.15) m, cutting off a loop of 0.36 m): edit refused"
            ),
            "curve * would cross itself : edit refused"
        );
        assert_eq!(
            reason_of("dimension ease = 0.2: ease must be between 0 and a tenth of the body's height"),
            "dimension ease = #: ease must be between # and a tenth of the body's height"
        );
    }
}
