//! The figures a step recorded ([`crate::session::StepMetrics::figures`]) logged as
//! scalars when the step ends: every number, as a series named by its path among the
//! figures, in the entity of its unit (placed by [`super::recording::metric_path`]) and of
//! the step's op ([`Series`]): one chunk per unit and step, where a chunk per figure cost
//! most of the logging of a small step. Nested figures extend the path: an object's field
//! by its name, a list's element by its name (its `name`, `ring`, `region` or `id` field,
//! else its text fields joined) or its index. Text and flags are left to the log.

use serde_json::Value;

use std::collections::BTreeMap;

use rerun::{Scalars, SeriesPoints};

use super::colors::series_color;
use super::logger::{RerunLogger, to_sink};
use super::recording::metric_path;
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

/// The figures the Collision plot shows, in their own entity (`metrics/count/guarantee`):
/// what detection found and the response moved, and what was left in the body after M0's
/// collision and after M1's.
pub(super) const GUARANTEE_FIGURES: [&str; 8] = [
    "hits",
    "responses",
    "penetrating_vertices",
    "crossing_edges",
    "pierced_faces",
    "m1_penetrating_vertices",
    "m1_crossing_edges",
    "m1_pierced_faces",
];

/// The entity the guarantee's figures are plotted in.
pub(super) const GUARANTEE_ENTITY: &str = "metrics/count/guarantee";

/// The entity a figure is plotted in, and its series' name there: `metrics/<unit>/<group>`
/// and the rest of its path (`metrics/count/step/hits_by_partition/A` is series
/// `hits_by_partition/A` of `metrics/count/step`); the guarantee's figures go to
/// `metrics/count/guarantee`.
pub fn series_of(path: &str) -> (String, String) {
    let parts: Vec<&str> = path.splitn(4, '/').collect();
    match parts.as_slice() {
        ["metrics", unit, group, name] => {
            if *unit == "count" && *group == "step" && GUARANTEE_FIGURES.contains(name) {
                (GUARANTEE_ENTITY.to_string(), (*name).to_string())
            } else {
                (format!("metrics/{unit}/{group}"), (*name).to_string())
            }
        }
        _ => (path.to_string(), String::new()),
    }
}

/// The entities the step figures are plotted in. Rerun plots an entity's scalars by their
/// place in the row, and every row of an entity must hold as many, with no gaps (a NaN
/// would make two equal recordings compare different). So each set of figures a kind of
/// step records has its own entity, `<entity>/<op>` ([`series_of`]'s entity and the step's
/// op), or `<op>_2`, `<op>_3` for the next sets of that op (a drag that was refused records
/// other figures than one that ran). Each is plotted as points, a series by name, in the
/// same colour wherever it appears.
#[derive(Debug, Default)]
pub(super) struct Series(BTreeMap<(String, String), Vec<FigureSet>>);

/// One set of figures: its names in the order of the first step that recorded it, and
/// sorted, to know it again.
#[derive(Debug)]
struct FigureSet {
    names: Vec<String>,
    sorted: Vec<String>,
}

impl Series {
    /// Where `figures` (of entity `entity`, by series name) of a step of `op` are logged,
    /// the row of scalars in the order of its names, and the names when they are new.
    fn row(&mut self, entity: &str, op: &str, figures: &[(String, f64)]) -> (String, Vec<f64>, Option<Vec<String>>) {
        let mut sorted: Vec<String> = figures.iter().map(|(name, _)| name.clone()).collect();
        sorted.sort_unstable();
        let sets = self.0.entry((entity.to_string(), op.to_string())).or_default();
        let (k, new) = match sets.iter().position(|s| s.sorted == sorted) {
            Some(k) => (k, false),
            None => {
                let names = figures.iter().map(|(name, _)| name.clone()).collect();
                sets.push(FigureSet { names, sorted });
                (sets.len() - 1, true)
            }
        };
        let set = &sets[k];
        let values = (set.names.iter())
            .map(|n| figures.iter().find(|(name, _)| name == n).map_or(f64::NAN, |f| f.1))
            .collect();
        let path = match k {
            0 => format!("{entity}/{op}"),
            k => format!("{entity}/{op}_{}", k + 1),
        };
        (path, values, new.then(|| set.names.clone()))
    }
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
                let colors: Vec<[u8; 3]> = names.iter().map(|n| series_color(n)).collect();
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

#[cfg(test)]
mod tests {
    use super::{Series, series_of};

    /// A figure's entity and series name, from its placed path; the guarantee's figures in
    /// their own entity.
    #[test]
    fn a_figure_is_a_series_of_its_unit_and_group() {
        let pair = |e: &str, n: &str| (e.to_string(), n.to_string());
        assert_eq!(
            series_of("metrics/count/step/hits_by_partition/A"),
            pair("metrics/count/step", "hits_by_partition/A")
        );
        assert_eq!(
            series_of("metrics/count/step/hits"),
            pair("metrics/count/guarantee", "hits")
        );
        assert_eq!(series_of("metrics/size/step/hits"), pair("metrics/size/step", "hits"));
        assert_eq!(
            series_of("metrics/ms/timings/m1.collide"),
            pair("metrics/ms/timings", "m1.collide")
        );
    }

    /// Each set of figures of an op has its own entity, and its rows keep their series'
    /// places: a step with the same figures in another order goes to the same entity, a
    /// step with other figures to the next (`<op>_2`), and another op to its own. Checked
    /// against rows written out by hand.
    #[test]
    fn each_set_of_figures_of_an_op_has_its_own_entity() {
        let mut series = Series::default();
        let figures =
            |list: &[(&str, f64)]| -> Vec<(String, f64)> { list.iter().map(|&(n, v)| (n.to_string(), v)).collect() };
        let names = |list: &[&str]| Some(list.iter().map(|n| n.to_string()).collect::<Vec<_>>());
        let m = "metrics/m/step";
        let row = series.row(m, "drag", &figures(&[("b", 1.0), ("a", 2.0)]));
        assert_eq!(row, ("metrics/m/step/drag".into(), vec![1.0, 2.0], names(&["b", "a"])));
        let row = series.row(m, "drag", &figures(&[("a", 3.0), ("b", 4.0)]));
        assert_eq!(row, ("metrics/m/step/drag".into(), vec![4.0, 3.0], None));
        let row = series.row(m, "drag", &figures(&[("a", 5.0)]));
        assert_eq!(row, ("metrics/m/step/drag_2".into(), vec![5.0], names(&["a"])));
        let row = series.row(m, "set", &figures(&[("a", 6.0), ("b", 7.0)]));
        assert_eq!(row, ("metrics/m/step/set".into(), vec![6.0, 7.0], names(&["a", "b"])));
        let row = series.row(m, "drag", &figures(&[("a", 8.0)]));
        assert_eq!(row, ("metrics/m/step/drag_2".into(), vec![8.0], None));
        let row = series.row("metrics/count/guarantee", "drag", &figures(&[("hits", 9.0)]));
        assert_eq!(
            row,
            ("metrics/count/guarantee/drag".into(), vec![9.0], names(&["hits"]))
        );
    }
}
