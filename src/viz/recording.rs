//! The recording as the logger writes it: one chunk per log call in call order
//! ([`OrderedRecording`]), and the metric paths by unit ([`metric_path`]).

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
/// `metrics/ratio/...` for stretches and relative errors, `metrics/size/...` for mesh sizes
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
    } else if rest.contains("stretch") || rest.contains("relative_error") {
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

/// A recording stream that makes every log call its own chunk, written in call order.
///
/// Rerun's batcher turns the rows of one flush into one chunk per entity, in the order of
/// a hash map: two runs of the same session would write the same chunks in different
/// orders, which `rerun rrd compare` (plain) calls different. Flushing after each call
/// leaves one entity per flush, so the file's chunks follow the calls.
///
/// A garment worn over another logs its entities under `layers/<name>/` (see
/// [`Self::set_layer`]), so that each garment keeps its own.
pub struct OrderedRecording(RecordingStream, bool, Option<String>);

/// The entity roots that belong to a garment (moved under `layers/<name>/` for a garment
/// worn over another).
const GARMENT_ROOTS: [&str; 5] = ["garment", "collision", "constraints", "sculpt", "patterns"];

impl OrderedRecording {
    /// Writes to `rec`; with `metrics_only`, only the metrics, the log and the legends.
    pub(super) fn new(rec: RecordingStream, metrics_only: bool) -> Self {
        Self(rec, metrics_only, None)
    }

    /// The garment the next calls log, when it is worn over another (`None`: the innermost
    /// or only garment, at the usual entities).
    pub fn set_layer(&mut self, layer: Option<String>) {
        self.2 = layer;
    }

    /// Logs `data` at `path` on the current timelines, as its own chunk.
    pub fn log<AS: ?Sized + rerun::AsComponents>(
        &self,
        path: impl Into<rerun::EntityPath>,
        data: &AS,
    ) -> Result<(), SinkError> {
        let mut path = path.into();
        if let Some(layer) = &self.2
            && path
                .iter()
                .next()
                .is_some_and(|p| GARMENT_ROOTS.contains(&p.unescaped_str()))
        {
            path = rerun::EntityPath::from(format!("layers/{layer}")).join(&path);
        }
        // With metrics only (the flag), anything but the metrics, the log and the legends
        // is left out.
        if self.1 && !["metrics", "log", "legend"].contains(&path.iter().next().map_or("", |p| p.unescaped_str())) {
            return Ok(());
        }
        self.0.log(path, data)?;
        self.0.flush_async()?;
        Ok(())
    }

    /// Logs static `data` at `path`, as its own chunk.
    pub fn log_static<AS: ?Sized + rerun::AsComponents>(
        &self,
        path: impl Into<rerun::EntityPath>,
        data: &AS,
    ) -> Result<(), SinkError> {
        self.0.log_static(path, data)?;
        self.0.flush_async()?;
        Ok(())
    }
}

impl std::ops::Deref for OrderedRecording {
    type Target = RecordingStream;

    fn deref(&self) -> &RecordingStream {
        &self.0
    }
}
