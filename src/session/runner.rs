//! The session runner: the scene (step 0), then each step, each emitting its stages to the
//! sinks. Timings measure compute only; the sinks' time is kept apart under `log.*` keys.
//!
//! The steps themselves live in `steps/`, one file per kind; this is the driver.

use std::path::PathBuf;

use super::emit::{Emitter, Shortfall};
use super::error::{RunError, StepError};
use super::format::Session;
use super::metrics::StepMetrics;
use super::stage::{Stage, StageSink, StepEnd};
use super::state::SessionState;
use super::steps::{StepContext, run_step, scene};
use crate::body::{LandmarkOptions, PartitionOptions};
use crate::collision::CollisionOptions;

/// Run settings from the command line.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Replaces the session's body (`--body`).
    pub body_override: Option<PathBuf>,
    /// Landmark detection settings (overrides come from the session).
    pub landmarks: LandmarkOptions,
    /// Partition settings.
    pub partitions: PartitionOptions,
    /// Collision settings.
    pub collision: CollisionOptions,
    /// Check every collision against the brute-force ground truth (`--verify`; slow).
    pub verify: bool,
    /// The largest body file read, bytes (`--max-input-mb`; default
    /// [`crate::input::DEFAULT_MAX_INPUT_BYTES`]; 0 means the default).
    pub max_input_bytes: u64,
    /// Set (by a signal handler) to end the run after the current step: the steps after it
    /// do not run, an `interrupted` stage says where it stopped, and the report has
    /// [`RunReport::interrupted`].
    pub stop: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
}

/// What a run produced.
#[derive(Debug, Default)]
pub struct RunReport {
    /// Metrics of every step that ran (the failed one included, with its error).
    pub steps: Vec<StepMetrics>,
    /// The error that stopped the run, or the sinks' failures after it finished.
    pub error: Option<RunError>,
    /// Promises steps could not keep, by step index (the run went on).
    pub shortfalls: Vec<(usize, Shortfall)>,
    /// The run was stopped by [`RunOptions::stop`] after this step (its last finished one).
    pub interrupted: Option<usize>,
}

/// Runs a session: the scene (step 0), then each step. Stops at the first failure, which
/// is emitted as a failed step and returned in the report. A sink's failure does not stop
/// the run; the sinks' failures are reported after the last step.
pub fn run_session(session: &Session, options: &RunOptions, sinks: &mut [&mut dyn StageSink]) -> RunReport {
    let mut out = Emitter::new(sinks);
    let mut report = RunReport::default();
    let mut scope = out.step(0, "scene");
    let mut state = match scene::run(&mut scope, session, options) {
        Ok(body) => {
            report.steps.push(scope.done().0);
            SessionState::new(body)
        }
        Err(e) => {
            let (metrics, error) = scope.fail(&session.name, session.scene.body_line, e);
            report.steps.push(metrics);
            report.error = Some(error);
            return report;
        }
    };
    let cx = StepContext { session, options };
    for (i, step) in session.steps.iter().enumerate() {
        if options
            .stop
            .as_ref()
            .is_some_and(|s| s.load(std::sync::atomic::Ordering::SeqCst))
        {
            out.step(i, "interrupt")
                .emit("interrupted", Stage::Step(StepEnd::Interrupted { after: i }));
            report.interrupted = Some(i);
            return report;
        }
        let mut scope = out.step(i + 1, step.op.keyword());
        match run_step(&mut scope, &mut state, &cx, &step.op) {
            Ok(()) => {
                let (metrics, shortfalls) = scope.done();
                report.steps.push(metrics);
                report.shortfalls.extend(shortfalls.into_iter().map(|s| (i + 1, s)));
            }
            Err(e) => {
                let (metrics, error) = scope.fail(&session.name, step.line, e);
                report.steps.push(metrics);
                report.error = Some(error);
                return report;
            }
        }
    }
    if !out.errors.is_empty() {
        report.error = Some(RunError {
            session: session.name.clone(),
            line: 1,
            step: 0,
            op: "log",
            source: StepError::Sinks(std::mem::take(&mut out.errors)),
        });
    }
    report
}
