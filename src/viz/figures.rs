//! The figures a step recorded ([`crate::session::StepMetrics::figures`]) logged as
//! scalars when the step ends: every number, under `metrics/<unit>/step/<figure>` (placed
//! by [`super::recording::metric_path`]). Nested figures extend the path: an object's field
//! by its name, a list's element by its name (its `name`, `ring`, `region` or `id` field,
//! else its text fields joined) or its index. Text and flags are left to the log.

use serde_json::Value;

use super::logger::RerunLogger;
use crate::session::{SinkError, StepMetrics};

/// Every numeric figure of `figures`, with its path below `prefix`, in the figures' order.
fn numeric_figures(prefix: &str, figures: &serde_json::Map<String, Value>) -> Vec<(String, f64)> {
    fn walk(path: String, value: &Value, out: &mut Vec<(String, f64)>) {
        match value {
            Value::Number(n) => {
                if let Some(x) = n.as_f64() {
                    out.push((path, x));
                }
            }
            Value::Object(fields) => {
                for (k, v) in fields {
                    walk(format!("{path}/{k}"), v, out);
                }
            }
            Value::Array(items) => {
                let mut seen = std::collections::BTreeSet::new();
                for (i, item) in items.iter().enumerate() {
                    let mut name = element_name(item).unwrap_or_else(|| i.to_string());
                    if !seen.insert(name.clone()) {
                        name = format!("{name}_{i}");
                    }
                    walk(format!("{path}/{name}"), item, out);
                }
            }
            Value::Null | Value::Bool(_) | Value::String(_) => {}
        }
    }
    let mut out = Vec::new();
    for (k, v) in figures {
        walk(format!("{prefix}/{k}"), v, &mut out);
    }
    out
}

/// A list element's name: its `name`, `ring`, `region` or `id` text, else its text fields
/// joined by `_`; `None` for an element with no text.
fn element_name(item: &Value) -> Option<String> {
    let fields = item.as_object()?;
    for key in ["name", "ring", "region", "id"] {
        if let Some(Value::String(s)) = fields.get(key) {
            return Some(s.clone());
        }
    }
    let texts: Vec<&str> = fields.values().filter_map(Value::as_str).collect();
    (!texts.is_empty()).then(|| texts.join("_"))
}

impl RerunLogger {
    /// Logs every number the step recorded (see the module's notes).
    pub(super) fn log_figures(&self, metrics: &StepMetrics) -> Result<(), SinkError> {
        for (path, value) in numeric_figures("metrics/step", &metrics.figures) {
            self.scalar(&path, value)?;
        }
        Ok(())
    }
}
