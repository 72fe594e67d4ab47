//! One stress session run and judged: its steps accepted, refused (by reason) or failed, a
//! panic caught, non-finite outputs, guarantee failures, solves and step times.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::convergence::{self, Tallies};
use crate::session::{RunOptions, Shortfall, parse_session, run_session};

use super::verified::Verified;
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
                    Shortfall::Guarantee { .. } | Shortfall::Layers(_) => out.guarantee_failures.push(*step),
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
