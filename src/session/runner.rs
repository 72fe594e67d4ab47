//! The session runner: the scene (step 0), then each step, each emitting its stages to the
//! sinks. Timings measure compute only; the sinks' time is kept apart under `log.*` keys.
//!
//! The steps themselves live in `steps/`, one file per kind; this is the driver.

use super::emit::{Emitter, Shortfall};
use super::error::{RunError, StepError};
use super::format::{Session, Step};
use super::metrics::StepMetrics;
use super::options::RunOptions;
use super::stage::{Stage, StageSink, StepEnd};
use super::state::SessionState;
use super::steps::scene;
use super::wear::run_worn;

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

/// A session run step by step, as the steps come (`drape edit`; [`run_session`] runs a
/// whole file through it): the scene first, then each step applied to the state at once.
pub struct LiveSession<'k, 's> {
    out: Emitter<'k, 's>,
    state: SessionState,
    /// The session so far: its scene and the steps that ran.
    session: Session,
    options: RunOptions,
    /// Metrics, shortfalls and the stop, so far.
    pub report: RunReport,
}

impl<'k, 's> LiveSession<'k, 's> {
    /// Runs the scene of `session` (its steps are ignored); on failure, the report with
    /// the error.
    pub fn start(
        session: &Session,
        options: RunOptions,
        sinks: &'k mut [&'s mut dyn StageSink],
    ) -> Result<Self, Box<RunReport>> {
        let mut out = Emitter::new(sinks);
        let mut report = RunReport::default();
        let mut scope = out.step(0, "scene");
        match scene::run(&mut scope, session, &options) {
            Ok(body) => {
                report.steps.push(scope.done().0);
                let mut session = session.clone();
                session.steps.clear();
                Ok(Self {
                    out,
                    state: SessionState::new(body),
                    session,
                    options,
                    report,
                })
            }
            Err(e) => {
                let (metrics, error) = scope.fail(&session.name, session.scene.body_line, e);
                report.steps.push(metrics);
                report.error = Some(error);
                Err(Box::new(report))
            }
        }
    }

    /// The session so far (the scene and the steps that ran).
    pub fn session(&self) -> &Session {
        &self.session
    }

    /// Runs one more step. On success it joins the session; on failure its `failed` stage
    /// is emitted, its metrics kept, and the error returned (the garment is as before).
    pub fn step(&mut self, step: &Step) -> Result<(), Box<RunError>> {
        let n = self.session.steps.len() + 1;
        let mut scope = self.out.step(n, step.op.keyword());
        match run_worn(&mut scope, &mut self.state, (&self.session, &self.options), step) {
            Ok(()) => {
                self.state.keep_last(self.options.undo_limit());
                let (metrics, shortfalls) = scope.done();
                self.report.steps.push(metrics);
                self.report.shortfalls.extend(shortfalls.into_iter().map(|s| (n, s)));
                self.session.steps.push(step.clone());
                Ok(())
            }
            Err(e) => {
                let (metrics, error) = scope.fail(&self.session.name, step.line, e);
                self.report.steps.push(metrics);
                Err(Box::new(error))
            }
        }
    }

    /// Whether [`RunOptions::stop`] was set; if so, says so in an `interrupted` stage.
    fn stopped(&mut self) -> bool {
        let stop = self
            .options
            .stop
            .as_ref()
            .is_some_and(|s| s.load(std::sync::atomic::Ordering::SeqCst));
        if stop {
            let after = self.session.steps.len();
            self.out
                .step(after, "interrupt")
                .emit("interrupted", Stage::Step(StepEnd::Interrupted { after }));
            self.report.interrupted = Some(after);
        }
        stop
    }

    /// Ends the session: the report, with the sinks' failures if there were any.
    pub fn finish(mut self) -> RunReport {
        if !self.out.errors.is_empty() && self.report.error.is_none() {
            self.report.error = Some(RunError {
                session: self.session.name.clone(),
                line: 1,
                step: 0,
                op: "log",
                source: StepError::Sinks(std::mem::take(&mut self.out.errors)),
            });
        }
        self.report
    }
}

/// Runs a session: the scene (step 0), then each step. Stops at the first failure, which
/// is emitted as a failed step and returned in the report. A sink's failure does not stop
/// the run; the sinks' failures are reported after the last step.
pub fn run_session(session: &Session, options: &RunOptions, sinks: &mut [&mut dyn StageSink]) -> RunReport {
    let mut live = match LiveSession::start(session, options.clone(), sinks) {
        Ok(live) => live,
        Err(report) => return *report,
    };
    for step in &session.steps {
        if live.stopped() {
            return live.report;
        }
        if let Err(error) = live.step(step) {
            live.report.error = Some(*error);
            return live.report;
        }
    }
    live.finish()
}
