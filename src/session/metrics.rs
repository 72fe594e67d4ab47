//! Per-step metrics: timings and every figure a step measured, for `--metrics`.
//!
//! Each step records its figures as typed structs (`#[derive(Serialize)]`, one per group of
//! figures, beside the step's code in `session/steps/`); their fields become the keys of the
//! step's JSON object.

use std::collections::BTreeMap;

use serde::Serialize;
use serde_json::{Map, Value};

/// What one step measured. Serialized flat: `step`, `op`, `timings_ms`, then the figures.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepMetrics {
    /// Step index (0 is the scene).
    pub step: usize,
    /// Operation keyword (`scene` for step 0).
    pub op: String,
    /// Stage name to milliseconds of compute (not logging); the sinks' time under `log.*`.
    pub timings_ms: BTreeMap<String, f64>,
    /// Counts and figures, by name (sorted).
    pub figures: Map<String, Value>,
    /// The error that stopped this step, if any.
    pub error: Option<String>,
    /// What the step says about how it ran that is not a figure of its result (where the
    /// body index came from, say): printed with the progress, kept in `--metrics`, never
    /// logged to the recording.
    pub notes: Vec<String>,
    /// How much of the step's work it took from earlier steps instead of doing it again
    /// (M1's patches kept, say), by name: in `--metrics` under `work`, never logged to the
    /// recording (it depends on the run's history and settings, not on the garment).
    pub work: Map<String, Value>,
}

impl StepMetrics {
    /// Empty metrics of a step.
    pub fn new(step: usize, op: &str) -> Self {
        Self {
            step,
            op: op.to_string(),
            ..Self::default()
        }
    }

    /// Records a group of figures: each field of `figures` (a struct serialized as a JSON
    /// object) becomes a key, replacing an earlier value of the same name.
    pub fn record<T: Serialize + ?Sized>(&mut self, figures: &T) {
        match serde_json::to_value(figures) {
            Ok(Value::Object(fields)) => self.figures.extend(fields),
            // Figures are plain structs; anything else is a bug in the caller.
            other => debug_assert!(false, "figures must serialize to an object: {other:?}"),
        }
    }

    /// Records a group of figures under `key` (an object of them, merged with what is
    /// there already).
    pub fn record_under<T: Serialize + ?Sized>(&mut self, key: &str, figures: &T) {
        match serde_json::to_value(figures) {
            Ok(Value::Object(fields)) => {
                let slot = self
                    .figures
                    .entry(key.to_string())
                    .or_insert_with(|| Value::Object(Map::new()));
                if let Value::Object(under) = slot {
                    under.extend(fields);
                }
            }
            other => debug_assert!(false, "figures must serialize to an object: {other:?}"),
        }
    }

    /// Records a count of the step's work under `key` (see [`Self::work`]).
    pub fn record_work(&mut self, key: String, count: usize) {
        self.work.insert(key, count.into());
    }

    /// The flat JSON object.
    pub fn to_json(&self) -> Value {
        let mut object = Map::new();
        object.insert("step".into(), self.step.into());
        object.insert("op".into(), self.op.clone().into());
        let timings: Map<String, Value> = self.timings_ms.iter().map(|(k, v)| (k.clone(), (*v).into())).collect();
        object.insert("timings_ms".into(), Value::Object(timings));
        for (k, v) in &self.figures {
            object.insert(k.clone(), v.clone());
        }
        if !self.notes.is_empty() {
            object.insert("notes".into(), self.notes.clone().into());
        }
        if !self.work.is_empty() {
            object.insert("work".into(), Value::Object(self.work.clone()));
        }
        if let Some(e) = &self.error {
            object.insert("error".into(), e.clone().into());
        }
        Value::Object(object)
    }
}

/// A JSON array of the steps' objects.
pub fn metrics_json(steps: &[StepMetrics]) -> Value {
    Value::Array(steps.iter().map(StepMetrics::to_json).collect())
}
