//! The emitter: hands every stage to every sink, counts the stages, and times a step's
//! compute and its sinks apart.

use std::time::Instant;

use serde::Serialize;

use super::error::SinkError;
use super::error::{RunError, StepError};
use super::metrics::StepMetrics;
use super::stage::{Stage, StageInfo, StepEnd};

/// The sinks of a run, the global stage counter and the sinks' failures.
pub(crate) struct Emitter<'k, 's> {
    sinks: &'k mut [&'s mut dyn super::stage::StageSink],
    stage: u64,
    /// Sink failures, with the stage each happened at; the run goes on and reports them.
    pub(crate) errors: Vec<(&'static str, SinkError)>,
}

impl<'k, 's> Emitter<'k, 's> {
    /// An emitter over `sinks`, starting at stage 0.
    pub(crate) fn new(sinks: &'k mut [&'s mut dyn super::stage::StageSink]) -> Self {
        Self {
            sinks,
            stage: 0,
            errors: Vec::new(),
        }
    }

    /// A scope for step `step` with keyword `op`.
    pub(crate) fn step(&mut self, step: usize, op: &'static str) -> StepScope<'_, 'k, 's> {
        StepScope {
            out: self,
            step,
            op,
            metrics: StepMetrics::new(step, op),
            shortfalls: Vec::new(),
            layer: None,
            started: Instant::now(),
        }
    }
}

/// One step's view of the run: emits its stages, times its compute, records its figures.
pub(crate) struct StepScope<'e, 'k, 's> {
    out: &'e mut Emitter<'k, 's>,
    /// Step index (0 is the scene).
    pub(crate) step: usize,
    /// The step's keyword.
    pub(crate) op: &'static str,
    /// The step's metrics so far.
    pub(crate) metrics: StepMetrics,
    /// What the step left short of a promise: the garment inside or crossing the body after
    /// its collision, or an edit it refused.
    pub(crate) shortfalls: Vec<Shortfall>,
    /// The garment the step is working on when it is worn over another: its stages are
    /// marked with it, its figures and timings go under its name.
    pub(crate) layer: Option<String>,
    /// When the step began.
    started: Instant,
}

/// A promise a step could not keep; the session goes on, `--strict` makes the run fail.
#[derive(Clone, Debug, PartialEq)]
pub enum Shortfall {
    /// After the step's collision response, vertices are still inside the body or edges
    /// cross it (the exact quality check).
    Guarantee {
        /// Vertices inside.
        inside: usize,
        /// Edges crossing.
        crossing: usize,
        /// Faces the body pokes through.
        pierced: usize,
    },
    /// The step's edit was refused (it names the limit); the garment is as before.
    Refused(String),
    /// A garment worn over another could not be kept in front of it (the message names
    /// the garments and the counts).
    Layers(String),
}

impl StepScope<'_, '_, '_> {
    /// Hands stage `name` to every sink; the time the sinks take goes to `log.<name>`.
    pub(crate) fn emit(&mut self, name: &'static str, stage: Stage<'_>) {
        let info = StageInfo {
            step: self.step,
            op: self.op,
            stage: self.out.stage,
            name,
            layer: self.layer.clone(),
        };
        self.out.stage += 1;
        let start = Instant::now();
        for sink in self.out.sinks.iter_mut() {
            if let Err(e) = sink.stage(&info, stage) {
                self.out.errors.push((name, e));
            }
        }
        let key = self.timing_key(&format!("log.{name}"));
        *self.metrics.timings_ms.entry(key).or_insert(0.0) += start.elapsed().as_secs_f64() * 1e3;
    }

    /// The key of timing `name`: under the garment's name when it is worn over another.
    pub(crate) fn timing_key(&self, name: &str) -> String {
        match &self.layer {
            Some(layer) => format!("{layer}/{name}"),
            None => name.to_string(),
        }
    }

    /// Runs `f`, recording its wall time as the compute time of stage `name`.
    pub(crate) fn timed<T>(&mut self, name: &str, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let out = f();
        self.metrics
            .timings_ms
            .insert(self.timing_key(name), start.elapsed().as_secs_f64() * 1e3);
        out
    }

    /// Refuses the step's edit with `message` (which names the limit): the metrics record
    /// it as `refused`, stage `name` goes to the sinks and the refusal to the shortfalls.
    /// The caller keeps the garment as it was.
    pub(crate) fn refuse(&mut self, message: &str, name: &'static str, stage: Stage<'_>) {
        /// An edit refused.
        #[derive(Serialize)]
        struct Refusal<'a> {
            /// Why, naming the limit.
            refused: &'a str,
        }
        self.record(&Refusal { refused: message });
        self.emit(name, stage);
        self.shortfalls.push(Shortfall::Refused(message.to_string()));
    }

    /// Adds a note to the step's metrics (see [`StepMetrics::notes`]).
    pub(crate) fn note(&mut self, note: String) {
        self.metrics.notes.push(note);
    }

    /// Records a group of figures (see [`StepMetrics::record`]); under the garment's name
    /// when it is worn over another.
    pub(crate) fn record<T: Serialize + ?Sized>(&mut self, figures: &T) {
        match &self.layer {
            Some(layer) => self.metrics.record_under(layer, figures),
            None => self.metrics.record(figures),
        }
    }

    /// Ends the step: its `done` stage, then its metrics and shortfalls. The step's wall
    /// time outside its timed stages and sinks (copies of the garment's state, the
    /// collision's view of M0, ...) is recorded as `step.other`, so that the timings add up
    /// to the whole step.
    pub(crate) fn done(mut self) -> (StepMetrics, Vec<Shortfall>) {
        let timed: f64 = self.metrics.timings_ms.values().sum();
        let other = (self.started.elapsed().as_secs_f64() * 1e3 - timed).max(0.0);
        self.metrics.timings_ms.insert("step.other".to_string(), other);
        let done = self.metrics.clone();
        self.emit("done", Stage::Step(StepEnd::Done(&done)));
        (self.metrics, self.shortfalls)
    }

    /// Ends the step with `error`: its `failed` stage, then its metrics (with the message)
    /// and the error placed at `line` of `session`.
    pub(crate) fn fail(mut self, session: &str, line: usize, source: StepError) -> (StepMetrics, RunError) {
        let error = RunError {
            session: session.to_string(),
            line,
            step: self.step,
            op: self.op,
            source,
        };
        self.metrics.error = Some(error.message());
        self.emit("failed", Stage::Step(StepEnd::Failed(&error)));
        (self.metrics, error)
    }
}
