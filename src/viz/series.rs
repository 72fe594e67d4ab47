//! The entities and series the step figures are plotted in: each figure a series named by
//! its path, in one entity per unit and set of figures of an op ([`Series`]), so that a
//! step's figures of a unit go out as one row of scalars.

use std::collections::BTreeMap;

/// The figures the Collision plot shows, in their own entity (`metrics/count/guarantee`):
/// what detection found and the response moved, and what was left in the body after M0's
/// collision and after M1's.
const GUARANTEE_FIGURES: [&str; 8] = [
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
const GUARANTEE_ENTITY: &str = "metrics/count/guarantee";

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
/// other figures than one that ran, and one whose collision took more rounds counts each).
/// Each is plotted as points, a series by name, in the same colour wherever it appears.
#[derive(Debug, Default)]
pub struct Series {
    /// The sets of figures of each entity and op, in the order first met.
    sets: BTreeMap<(String, String), Vec<FigureSet>>,
    /// Each series name's place in the order names were first met, in any entity.
    met: BTreeMap<String, usize>,
}

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
    pub fn row(
        &mut self,
        entity: &str,
        op: &str,
        figures: &[(String, f64)],
    ) -> (String, Vec<f64>, Option<Vec<String>>) {
        let mut sorted: Vec<String> = figures.iter().map(|(name, _)| name.clone()).collect();
        sorted.sort_unstable();
        let sets = self.sets.entry((entity.to_string(), op.to_string())).or_default();
        let (k, new) = match sets.iter().position(|s| s.sorted == sorted) {
            Some(k) => (k, false),
            None => {
                let names = figures.iter().map(|(name, _)| name.clone()).collect();
                sets.push(FigureSet { names, sorted });
                (sets.len() - 1, true)
            }
        };
        let set = &sets[k];
        // The set's names are the figures' (the same sorted lists), so every one is found.
        let by_name: BTreeMap<&str, f64> = figures.iter().map(|(name, v)| (name.as_str(), *v)).collect();
        let values = (set.names.iter())
            .map(|n| by_name.get(n.as_str()).copied().unwrap_or(f64::NAN))
            .collect();
        let path = match k {
            0 => format!("{entity}/{op}"),
            k => format!("{entity}/{op}_{}", k + 1),
        };
        (path, values, new.then(|| set.names.clone()))
    }

    /// The place of series `name` in the order names were first met (its colour's).
    pub fn place(&mut self, name: &str) -> usize {
        let next = self.met.len();
        *self.met.entry(name.to_string()).or_insert(next)
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
        // A series' colour place is where its name was first met, whatever the entity.
        let places: Vec<usize> = ["b", "a", "hits", "c", "b"].iter().map(|n| series.place(n)).collect();
        assert_eq!(places, vec![0, 1, 2, 3, 0]);
    }
}
