//! Per-step metrics: timings and every figure a step measured, for `--metrics`.

use std::collections::BTreeMap;

use serde_json::{Map, Value};

/// What one step measured. Serialized flat: `step`, `op`, `timings_ms`, then the figures.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepMetrics {
    /// Step index (0 is the scene).
    pub step: usize,
    /// Operation keyword (`scene` for step 0).
    pub op: String,
    /// Stage name to milliseconds of compute (not logging).
    pub timings_ms: BTreeMap<String, f64>,
    /// Counts and figures, by name (sorted).
    pub figures: Map<String, Value>,
    /// The error that stopped this step, if any.
    pub error: Option<String>,
}

impl StepMetrics {
    /// Records a figure.
    pub fn set(&mut self, key: &str, value: impl Into<Value>) {
        self.figures.insert(key.to_string(), value.into());
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
