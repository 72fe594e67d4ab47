//! The figures a step recorded ([`crate::session::StepMetrics::figures`]) logged as
//! scalars when the step ends: every number, as a series named by its path among the
//! figures, in the entity of its unit (placed by [`super::recording::metric_path`]) and of
//! the step's op ([`Series`]): one chunk per unit and step, where a chunk per figure cost
//! most of the logging of a small step. Nested figures extend the path: an object's field
//! by its name, a list's element by its name (its `name`, `ring`, `region` or `id` field,
//! else its text fields joined) or its index. Text and flags are left to the log.

use std::collections::BTreeMap;

use rerun::{Scalars, SeriesPoints};
use serde_json::Value;

use super::colors::series_color;
use super::logger::{RerunLogger, to_sink};
use super::recording::metric_path;
use super::series::series_of;
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
    pub(super) fn log_figures(&mut self, metrics: &StepMetrics) -> Result<(), SinkError> {
        let figures = numeric_figures("metrics/step", &metrics.figures);
        let timings = (self.options.timings).then(|| {
            metrics
                .timings_ms
                .iter()
                .map(|(name, ms)| (format!("metrics/timings/{name}"), *ms))
        });
        self.log_series(&metrics.op, figures.into_iter().chain(timings.into_iter().flatten()))
    }

    /// Logs each figure of a step of `op` as a series of its entity ([`series_of`]): one row
    /// of scalars per entity and set of figures ([`Series`]). The series' names, colours and
    /// markers are logged (static) with an entity's first row.
    fn log_series(&mut self, op: &str, figures: impl Iterator<Item = (String, f64)>) -> Result<(), SinkError> {
        let mut by_entity: BTreeMap<String, Vec<(String, f64)>> = BTreeMap::new();
        for (path, value) in figures {
            let (entity, name) = series_of(&metric_path(&path));
            by_entity.entry(entity).or_default().push((name, value));
        }
        for (entity, figures) in by_entity {
            let (entity, values, names) = self.series.row(&entity, op, &figures);
            if let Some(names) = names {
                let colors: Vec<[u8; 3]> = names.iter().map(|n| series_color(self.series.place(n))).collect();
                let points = (SeriesPoints::new().with_names(names))
                    .with_colors(colors)
                    .with_marker_sizes([3.0]);
                self.rec.log_static(entity.as_str(), &points).map_err(to_sink)?;
            }
            self.rec.log(entity.as_str(), &Scalars::new(values)).map_err(to_sink)?;
        }
        Ok(())
    }
}
