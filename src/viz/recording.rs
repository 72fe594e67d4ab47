//! The recording as the logger writes it: one chunk per log call in call order (or per
//! entity, for rows held together)
//! ([`OrderedRecording`]), and the metric paths by unit ([`metric_path`]).

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, Mutex};

use rerun::RecordingStream;

use crate::session::SinkError;

/// The units the metrics are plotted by: the folder under `metrics/` each figure goes to.
pub const METRIC_UNITS: [(&str, &str); 6] = [
    ("count", "Counts"),
    ("size", "Mesh sizes"),
    ("m", "Lengths (m)"),
    ("deg", "Angles (deg)"),
    ("ratio", "Ratios"),
    ("ms", "Time (ms)"),
];

/// `metrics/<group>/<name>` placed under its unit: `metrics/ms/...` for timings,
/// `metrics/m/...` for lengths, gaps, heights, points and residuals (`_m`, `_gap`, `girth`, `_y`,
/// `point`, `dragged_to`, `residual`), `metrics/deg/...` for names ending in `_deg`,
/// `metrics/ratio/...` for stretches (`_stretch`) and relative errors, `metrics/size/...` for mesh sizes
/// (vertices, faces, edges, triangles) and what a check tested, skipped, reused or welded
/// (thousands, which would flatten the collision counts beside them), `metrics/count/...`
/// otherwise.
pub fn metric_path(path: &str) -> String {
    let Some(rest) = path.strip_prefix("metrics/") else {
        return path.to_string();
    };
    let unit = if rest.starts_with("timings/") {
        "ms"
    } else if rest.ends_with("_deg") {
        "deg"
    } else if rest.ends_with("_m")
        || rest.ends_with("_gap")
        || rest.contains("_m/")
        || rest.contains("residual")
        || rest.ends_with("girth")
        || rest.ends_with("_y")
        || rest.ends_with("/y")
        || rest.contains("/point/")
        || rest.contains("dragged_to/")
    {
        "m"
    } else if rest.ends_with("_stretch") || rest.contains("relative_error") {
        "ratio"
    } else if (rest.ends_with("faces") && !rest.contains("pierced"))
        || (rest.ends_with("vertices") && !rest.contains("penetrating"))
        || (rest.ends_with("_edges") && !rest.contains("crossing"))
        || rest.contains("skipped")
        || rest.contains("tested")
        || rest.contains("reused/")
        || rest.contains("welded")
        || rest.ends_with("triangles")
        || rest.ends_with("triangle_count")
    {
        "size"
    } else {
        "count"
    };
    format!("metrics/{unit}/{rest}")
}

/// A recording stream that makes every log call its own chunk, written in call order
/// (rows logged between [`Self::hold`] and [`Self::release`] go out as one chunk per entity).
///
/// Rerun's batcher turns the rows of one flush into one chunk per entity, in the order of
/// a hash map: two runs of the same session would write the same chunks in different
/// orders, which `rerun rrd compare` (plain) calls different. Each call here builds its own
/// chunk and sends it past the batcher, so the file's chunks follow the calls (and a call
/// costs about half what a log and a flush of the batcher do).
///
/// A garment worn over another logs its entities under `layers/<name>/` (see
/// [`Self::set_layer`]), so that each garment keeps its own.
///
/// It also remembers what each entity shows now: [`Self::log_part`] skips a part whose
/// content is the one the entity already shows (the latest-at scene is the same without
/// it), and any other log call at an entity, a [`rerun::Clear`] among them, forgets what it
/// knew of that entity and of everything under it.
pub struct OrderedRecording {
    rec: RecordingStream,
    metrics_only: bool,
    layer: Option<String>,
    only_changed: bool,
    /// Entities that show something now, by full path, with the content of each field of
    /// those a part was logged to (the exact words [`Self::log_part`] was given).
    shown: Mutex<BTreeMap<String, Fields>>,
    /// Entities that may show something: every path data was sent to since it was last
    /// cleared (by [`Self::clear`] or [`Self::clear_tree`], which alone take paths out).
    /// Unlike `shown`, a log at a parent leaves its children here: they still show.
    maybe: Mutex<BTreeSet<String>>,
    /// While rows are held ([`Self::hold`]): each entity's rows in call order, the entities
    /// in the order of their first row.
    held: Mutex<Option<Vec<HeldRows>>>,
}

/// One row of a chunk: its id, its time and its data.
type Row = (
    rerun::log::RowId,
    rerun::TimePoint,
    Vec<rerun::SerializedComponentBatch>,
);

/// The rows held for one entity.
type HeldRows = (rerun::EntityPath, Vec<Row>);

/// The words that make a field of a part. A layout's fields (a part's faces, its edges)
/// are shared from step to step: the same `Arc` is the same content without a look.
pub type Words = Arc<Vec<u32>>;

/// The content of each field of a part, by field name.
type Fields = BTreeMap<&'static str, Words>;

/// The entity roots that belong to a garment (moved under `layers/<name>/` for a garment
/// worn over another).
const GARMENT_ROOTS: [&str; 5] = ["garment", "collision", "constraints", "sculpt", "patterns"];

impl OrderedRecording {
    /// Writes to `rec`; with `metrics_only`, only the metrics, the log and the legends; with
    /// `only_changed`, [`Self::log_part`] skips the parts the recording shows already.
    pub(super) fn new(rec: RecordingStream, metrics_only: bool, only_changed: bool) -> Self {
        Self {
            rec,
            metrics_only,
            layer: None,
            only_changed,
            shown: Mutex::new(BTreeMap::new()),
            maybe: Mutex::new(BTreeSet::new()),
            held: Mutex::new(None),
        }
    }

    /// The garment the next calls log, when it is worn over another (`None`: the innermost
    /// or only garment, at the usual entities).
    pub fn set_layer(&mut self, layer: Option<String>) {
        self.layer = layer;
    }

    /// `path` where it is logged: under `layers/<name>/` for a garment worn over another;
    /// `None` when the metrics-only filter leaves it out.
    fn placed(&self, path: rerun::EntityPath) -> Option<rerun::EntityPath> {
        let mut path = path;
        if let Some(layer) = &self.layer
            && path
                .iter()
                .next()
                .is_some_and(|p| GARMENT_ROOTS.contains(&p.unescaped_str()))
        {
            path = rerun::EntityPath::from(format!("layers/{layer}")).join(&path);
        }
        // With metrics only (the flag), anything but the metrics, the log and the legends
        // is left out.
        let root = path.iter().next().map_or("", |p| p.unescaped_str());
        (!self.metrics_only || ["metrics", "log", "legend"].contains(&root)).then_some(path)
    }

    /// Whether what is logged at `path` reaches the recording (not left out by the
    /// metrics-only filter): a caller can skip making what would be dropped.
    pub fn keeps(&self, path: &str) -> bool {
        self.placed(path.into()).is_some()
    }

    fn shown(&self) -> std::sync::MutexGuard<'_, BTreeMap<String, Fields>> {
        self.shown.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Remembers `key` as showing `content`, and nothing under it.
    fn remember(&self, key: String, content: Fields) {
        self.forget(&key);
        self.shown().insert(key, content);
    }

    /// Forgets `key` and everything under it.
    fn forget(&self, key: &str) {
        let mut shown = self.shown();
        let under = format!("{key}/");
        shown.remove(key);
        let stale: Vec<String> = shown
            .range(under.clone()..)
            .take_while(|(k, _)| k.starts_with(&under))
            .map(|(k, _)| k.clone())
            .collect();
        for k in stale {
            shown.remove(&k);
        }
    }

    /// Sends `data` at `path` as one chunk, at the current time on the user timelines (none:
    /// static). The chunk goes to the sink as it is, after every chunk sent before it: no
    /// batching, no flush, nothing reordered.
    fn send<AS: ?Sized + rerun::AsComponents>(
        &self,
        path: rerun::EntityPath,
        data: &AS,
        timepoint: rerun::TimePoint,
    ) -> Result<(), SinkError> {
        let batches = data.as_serialized_batches();
        if batches.is_empty() {
            return Ok(());
        }
        {
            let key = path.to_string();
            let mut maybe = self.maybe();
            if !maybe.contains(&key) {
                maybe.insert(key);
            }
        }
        let row = rerun::log::RowId::new();
        let mut guard = self.held();
        let Some(held) = guard.as_mut() else {
            drop(guard);
            return self.send_rows(path, vec![(row, timepoint, batches)]);
        };
        // Held: one more row of the entity's chunk, sent by `release`. A chunk's rows share
        // their timelines: a row on other timelines sends the entity's rows so far first.
        let same = |a: &rerun::TimePoint| a.timeline_names().eq(timepoint.timeline_names());
        match held.iter().position(|(p, _)| *p == path) {
            Some(k) if same(&held[k].1[0].1) => held[k].1.push((row, timepoint, batches)),
            Some(k) => {
                let (path, rows) = std::mem::replace(&mut held[k], (path, vec![(row, timepoint, batches)]));
                self.send_rows(path, rows)?;
            }
            None => held.push((path, vec![(row, timepoint, batches)])),
        }
        Ok(())
    }

    /// Sends `rows` of `path` as one chunk.
    fn send_rows(&self, path: rerun::EntityPath, rows: Vec<Row>) -> Result<(), SinkError> {
        let mut builder = rerun::log::Chunk::builder(path);
        for (row, timepoint, batches) in rows {
            builder = builder.with_serialized_batches(row, timepoint, batches);
        }
        let chunk = builder.build().map_err(|e| SinkError::Backend {
            what: "rerun chunk",
            source: Box::new(e),
        })?;
        self.rec.send_chunk(chunk);
        Ok(())
    }

    fn held(&self) -> std::sync::MutexGuard<'_, Option<Vec<HeldRows>>> {
        self.held.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Holds what is logged from now on until [`Self::release`], which sends each entity's
    /// rows as one chunk. For a run of rows that only a timeline of their own tells apart (a
    /// solver's iterations): the rows, their times and their order within each entity are
    /// those of logging them one by one, in a chunk each entity, where each would cost a
    /// chunk of its own. A row on other timelines than its entity's rows before it sends
    /// those first (a chunk's rows share their timelines).
    pub fn hold(&self) {
        self.held().get_or_insert_with(Vec::new);
    }

    /// Sends the rows held since [`Self::hold`], one chunk per entity, the entities in the
    /// order of their first row, and stops holding.
    pub fn release(&self) -> Result<(), SinkError> {
        let held = self.held().take().unwrap_or_default();
        for (path, rows) in held {
            self.send_rows(path, rows)?;
        }
        Ok(())
    }

    /// Logs `data` at `path` on the current timelines, as its own chunk.
    pub fn log<AS: ?Sized + rerun::AsComponents>(
        &self,
        path: impl Into<rerun::EntityPath>,
        data: &AS,
    ) -> Result<(), SinkError> {
        let Some(path) = self.placed(path.into()) else {
            return Ok(());
        };
        self.remember(path.to_string(), Fields::new());
        self.send(path, data, self.rec.now())
    }

    /// Logs a part at `path`: `fields` are the words that make each of its fields (the same
    /// words, the same data), and `build` makes the part's data from the fields to send
    /// (true where one is sent). When only changed parts are logged, the fields the entity
    /// shows already are left out (Rerun's latest-at takes them from the earlier log), and
    /// nothing is sent when none changed; else every field is sent. Returns whether
    /// anything was sent.
    pub fn log_part<AS: rerun::AsComponents>(
        &self,
        path: impl Into<rerun::EntityPath>,
        fields: Vec<(&'static str, Words)>,
        build: impl FnOnce(&[bool]) -> AS,
    ) -> Result<bool, SinkError> {
        let Some(path) = self.placed(path.into()) else {
            return Ok(false);
        };
        let key = path.to_string();
        let changed: Vec<bool> = {
            let shown = self.shown();
            let before = shown.get(&key);
            fields
                .iter()
                .map(|(name, words)| {
                    !self.only_changed
                        || before
                            .and_then(|b| b.get(name))
                            .is_none_or(|w| !Arc::ptr_eq(w, words) && w != words)
                })
                .collect()
        };
        if !changed.contains(&true) {
            return Ok(false);
        }
        let data = build(&changed);
        let mut content = self.shown().remove(&key).unwrap_or_default();
        if self.only_changed {
            content.extend(fields);
        }
        self.remember(key, content);
        self.send(path, &data, self.rec.now())?;
        Ok(true)
    }

    /// Clears the entities right under `parent` that show something and whose names are
    /// not in `keep` (the parts a mesh no longer has).
    pub fn clear_others(&self, parent: &str, keep: &BTreeSet<String>) -> Result<(), SinkError> {
        let Some(parent) = self.placed(parent.into()) else {
            return Ok(());
        };
        let under = format!("{parent}/");
        let gone: Vec<String> = self
            .shown()
            .range(under.clone()..)
            .take_while(|(k, _)| k.starts_with(&under))
            .map(|(k, _)| k[under.len()..].to_string())
            .filter(|name| !name.contains('/') && !keep.contains(name))
            .collect();
        for name in gone {
            self.clear_placed(parent.join(&rerun::EntityPath::from(name.as_str())), false)?;
        }
        Ok(())
    }

    fn maybe(&self) -> std::sync::MutexGuard<'_, BTreeSet<String>> {
        self.maybe.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Clears what `path` shows (not its children). When only changed parts are logged, an
    /// entity that shows nothing (never logged, or cleared since its last data) is left as
    /// it is: the latest-at scene is the same without a second `Clear`.
    pub fn clear(&self, path: &str) -> Result<(), SinkError> {
        self.clear_where(path, false)
    }

    /// Clears `path` and everything under it, as [`Self::clear`] does one entity: nothing is
    /// sent when none of them may show something.
    pub fn clear_tree(&self, path: &str) -> Result<(), SinkError> {
        self.clear_where(path, true)
    }

    fn clear_where(&self, path: &str, tree: bool) -> Result<(), SinkError> {
        match self.placed(path.into()) {
            Some(path) => self.clear_placed(path, tree),
            None => Ok(()),
        }
    }

    /// [`Self::clear`] (or, with `tree`, [`Self::clear_tree`]) of a path already placed.
    fn clear_placed(&self, path: rerun::EntityPath, tree: bool) -> Result<(), SinkError> {
        let key = path.to_string();
        let under = format!("{key}/");
        let cleared: Vec<String> = {
            let maybe = self.maybe();
            let below = maybe
                .range(under.clone()..)
                .take_while(|k| tree && k.starts_with(&under));
            maybe.get(&key).into_iter().chain(below).cloned().collect()
        };
        if self.only_changed && cleared.is_empty() {
            return Ok(());
        }
        let clear = if tree {
            rerun::Clear::recursive()
        } else {
            rerun::Clear::flat()
        };
        self.send(path, &clear, self.rec.now())?;
        self.forget(&key);
        let mut maybe = self.maybe();
        for k in cleared.iter().chain([&key]) {
            maybe.remove(k);
        }
        Ok(())
    }

    /// Logs static `data` at `path`, as its own chunk.
    pub fn log_static<AS: ?Sized + rerun::AsComponents>(
        &self,
        path: impl Into<rerun::EntityPath>,
        data: &AS,
    ) -> Result<(), SinkError> {
        self.send(path.into(), data, rerun::TimePoint::default())
    }
}

impl std::ops::Deref for OrderedRecording {
    type Target = RecordingStream;

    fn deref(&self) -> &RecordingStream {
        &self.rec
    }
}

#[cfg(test)]
mod tests {
    use super::metric_path;

    /// The patches each of M1's rules refined are counts, plotted together: the stretch
    /// rule's count is not a stretch (it went among the ratios once, by its name).
    #[test]
    fn the_patches_each_rule_refined_share_the_counts_plot_and_a_stretch_is_a_ratio() {
        for rule in crate::m1::Rule::ALL.map(crate::m1::Rule::name).iter().chain(&["total"]) {
            let path = metric_path(&format!("metrics/step/m1_patches_refined/{rule}"));
            assert_eq!(path, format!("metrics/count/step/m1_patches_refined/{rule}"));
        }
        assert_eq!(
            metric_path("metrics/step/max_stretch"),
            "metrics/ratio/step/max_stretch"
        );
    }

    /// Rows held go out one chunk per entity, in order, each row at the time it was logged;
    /// a row on other timelines than the entity's rows before it starts a chunk of its own
    /// (a chunk's rows share their timelines). The truth is the calls the test makes.
    #[test]
    fn held_rows_go_out_one_chunk_per_entity_and_run_of_timelines() {
        use rerun::log::{Chunk, LogMsg};
        let (stream, storage) = crate::viz::target::memory_recording("held").expect("a memory recording");
        let rec = super::OrderedRecording::new(stream, false, true);
        rec.set_time_sequence("step", 1);
        rec.hold();
        for iter in 1..=3 {
            rec.set_time_sequence("iter", iter);
            rec.log("a", &rerun::Scalars::single(iter as f64)).expect("logs");
            rec.log("b", &rerun::Scalars::single(-iter as f64)).expect("logs");
        }
        rec.disable_timeline("iter");
        rec.log("a", &rerun::Scalars::single(9.0)).expect("logs");
        rec.release().expect("sends");
        rec.log("a", &rerun::Scalars::single(10.0)).expect("logs");
        rec.flush_blocking().expect("flushes");
        let chunks: Vec<(String, usize, Vec<i64>)> = (storage.take().into_iter())
            .filter_map(|m| match m {
                LogMsg::ArrowMsg(store, arrow) if store.kind() == rerun::StoreKind::Recording => {
                    let c = Chunk::from_arrow_msg(&arrow).expect("decodes");
                    let iters = c
                        .timelines()
                        .get(&"iter".into())
                        .map_or(Vec::new(), |t| t.times_raw().to_vec());
                    Some((c.entity_path().to_string(), c.num_rows(), iters))
                }
                _ => None,
            })
            .filter(|(e, _, _)| !e.starts_with("/__"))
            .collect();
        // `a`'s three iterations go out when its row off the `iter` timeline comes; that row
        // waits for the release in `a`'s place, before `b`; the last row is not held.
        let want = [
            ("/a", 3, vec![1, 2, 3]),
            ("/a", 1, vec![]),
            ("/b", 3, vec![1, 2, 3]),
            ("/a", 1, vec![]),
        ];
        let want: Vec<(String, usize, Vec<i64>)> = want.into_iter().map(|(e, n, t)| (e.to_string(), n, t)).collect();
        assert_eq!(chunks, want);
    }
}
