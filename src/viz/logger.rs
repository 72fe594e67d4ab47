//! [`RerunLogger`]: the stage sink that logs to a Rerun recording.

use glam::DVec3;
use rerun::{RecordingStream, Scalars, SeriesPoints, TextLog, TextLogLevel, ViewCoordinates};

use crate::mannequin::{MannequinResult, Region};
use crate::session::{
    BodyStage, CollisionStage, ConstraintStage, GarmentStage, LogDetail, M1Stage, SectionCut, SinkError, Stage,
    StageInfo, StageSink, StepEnd,
};

/// What the logger logs.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LogOptions {
    /// Also log compute timings as `metrics/ms/timings/*` scalars. They are wall-clock, so two
    /// runs then differ; off by default so that a session's recording is reproducible.
    /// Default value: false.
    pub timings: bool,
    /// Where the mannequin surfaces stand, beside the body (x offset of the polar one; the
    /// chord one is 0.6 m further), clear of the partition legend. Default value: 1.6.
    pub mannequin_offset_x: f64,
    /// What is logged: every stage, the final meshes, or the metrics and the log only.
    /// Default value: all.
    pub detail: LogDetail,
    /// Wait at the end of every step until its data has been written (a file target): a
    /// step reported done is in the file whole, and on one core the next step's compute does
    /// not share the core with the encoding and writing of the last one (the wait counts as
    /// the step's logging). Off for a viewer or a server, whose flush waits on the network.
    /// Default value: false.
    pub settle: bool,
}

impl Default for LogOptions {
    fn default() -> Self {
        Self {
            timings: false,
            mannequin_offset_x: 1.6,
            detail: LogDetail::All,
            settle: false,
        }
    }
}

impl LogOptions {
    /// Sets [`Self::timings`].
    #[must_use]
    pub fn with_timings(mut self, timings: bool) -> Self {
        self.timings = timings;
        self
    }

    /// Sets [`Self::detail`].
    #[must_use]
    pub fn with_detail(mut self, detail: LogDetail) -> Self {
        self.detail = detail;
        self
    }

    /// Sets [`Self::settle`].
    #[must_use]
    pub fn with_settle(mut self, settle: bool) -> Self {
        self.settle = settle;
        self
    }

    /// Sets [`Self::mannequin_offset_x`].
    #[must_use]
    pub fn with_mannequin_offset_x(mut self, x: f64) -> Self {
        self.mannequin_offset_x = x;
        self
    }
}

/// Logs every stage to a recording.
pub struct RerunLogger {
    pub(super) rec: OrderedRecording,
    pub(super) options: LogOptions,
    iter: i64,
}

impl From<rerun::RecordingStreamError> for SinkError {
    fn from(e: rerun::RecordingStreamError) -> Self {
        Self::Backend {
            what: "rerun",
            source: Box::new(e),
        }
    }
}

impl From<rerun::sink::SinkFlushError> for SinkError {
    fn from(e: rerun::sink::SinkFlushError) -> Self {
        Self::Backend {
            what: "rerun flush",
            source: Box::new(e),
        }
    }
}

pub(super) fn to_sink(e: impl Into<SinkError>) -> SinkError {
    e.into()
}

/// A mesh with smooth vertex normals and one colour per vertex.
pub(super) fn colored_mesh(mesh: &crate::mesh::TriMesh, colors: Vec<[u8; 3]>) -> rerun::Mesh3D {
    let normals: Vec<[f32; 3]> = mesh.vertex_normals().iter().map(|n| n.as_vec3().to_array()).collect();
    rerun::Mesh3D::new(mesh.positions_f32())
        .with_triangle_indices(mesh.triangles.iter().copied())
        .with_vertex_normals(normals)
        .with_vertex_colors(colors)
}

/// A mesh's edges as few polylines, every edge in exactly one: from each vertex in turn,
/// a walk along unused edges (the first unused one at each vertex, by edge order) until it
/// reaches a vertex with none left. The same segments as one two-point strip per edge, in
/// about half the points and far fewer strips; deterministic.
pub(super) fn edge_paths(positions: &[DVec3], edges: &[[u32; 2]]) -> Vec<Vec<[f32; 3]>> {
    let n = positions.len();
    // Incident edges of every vertex, by edge order (counting sort).
    let mut start = vec![0usize; n + 1];
    for &[a, b] in edges {
        start[a as usize + 1] += 1;
        start[b as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut incident = vec![0u32; 2 * edges.len()];
    for (e, &[a, b]) in edges.iter().enumerate() {
        for v in [a, b] {
            incident[fill[v as usize]] = e as u32;
            fill[v as usize] += 1;
        }
    }
    let mut next = start.clone();
    let mut used = vec![false; edges.len()];
    let mut unused_at = |v: usize, used: &[bool]| -> Option<u32> {
        while next[v] < start[v + 1] {
            let e = incident[next[v]];
            if !used[e as usize] {
                return Some(e);
            }
            next[v] += 1;
        }
        None
    };
    let point = |v: usize| positions[v].as_vec3().to_array();
    let mut paths = Vec::new();
    for v in 0..n {
        while let Some(e) = unused_at(v, &used) {
            let mut path = vec![point(v)];
            let (mut at, mut edge) = (v, e);
            loop {
                used[edge as usize] = true;
                let [a, b] = edges[edge as usize];
                at = if a as usize == at { b as usize } else { a as usize };
                path.push(point(at));
                match unused_at(at, &used) {
                    Some(e) => edge = e,
                    None => break,
                }
            }
            paths.push(path);
        }
    }
    paths
}

pub(super) fn f32s(points: &[DVec3]) -> Vec<[f32; 3]> {
    points.iter().map(|p| p.as_vec3().to_array()).collect()
}

/// Logs the closed outlines of `faces` (indices into `triangles`, corners at `positions`)
/// at `path`, or clears it when there are none.
pub(super) fn log_face_outlines(
    rec: &OrderedRecording,
    path: &str,
    (triangles, positions): (&[[u32; 3]], &[DVec3]),
    faces: &[u32],
    (radius, colour): (f32, [u8; 3]),
) -> Result<(), SinkError> {
    if faces.is_empty() {
        return rec.log(path, &rerun::Clear::flat());
    }
    let outlines: Vec<Vec<[f32; 3]>> = faces
        .iter()
        .map(|&f| closed(&triangles[f as usize].map(|v| positions[v as usize])))
        .collect();
    rec.log(
        path,
        &rerun::LineStrips3D::new(outlines)
            .with_radii([radius])
            .with_colors([colour]),
    )
}

pub(super) fn closed(points: &[DVec3]) -> Vec<[f32; 3]> {
    let mut v = f32s(points);
    if let Some(first) = v.first().copied() {
        v.push(first);
    }
    v
}

/// Whether a stage is logged at [`LogDetail::Final`]: the body's mesh, M0 as built and
/// after its collision, M1 with its cut lines, refusals, and the ends of steps.
fn is_final(stage: &Stage<'_>) -> bool {
    match stage {
        Stage::Body(b) => matches!(b, BodyStage::Mesh(_)),
        Stage::Garment(g) => !matches!(g, GarmentStage::Part(_, part) if *part != crate::session::GarmentPart::Mesh),
        Stage::Collision(c) => c.part == crate::session::CollisionPart::Respond,
        Stage::Constraints(c) => matches!(c, ConstraintStage::Refused { .. }),
        Stage::M1(_) | Stage::Step(_) | Stage::Nurbs(_) | Stage::Sculpt(_) | Stage::SculptCompare(_) => true,
        _ => false,
    }
}

/// The units the metrics are plotted by: the folder under `metrics/` each figure goes to.
pub const METRIC_UNITS: [(&str, &str); 6] = [
    ("count", "Counts"),
    ("size", "Mesh sizes"),
    ("m", "Lengths (m)"),
    ("mm", "Mannequin (mm)"),
    ("ratio", "Ratios"),
    ("ms", "Time (ms)"),
];

/// `metrics/<group>/<name>` placed under its unit: `metrics/ms/...` for timings,
/// `metrics/mm/...` for names ending in `_mm`, `metrics/m/...` for lengths and residuals
/// (`_m`, `girth_m`, `residual`), `metrics/ratio/...` for stretches, `metrics/size/...` for
/// mesh sizes and the vertices a detection tested or skipped (thousands, which would flatten
/// the collision counts beside them), `metrics/count/...` otherwise.
pub fn metric_path(path: &str) -> String {
    let Some(rest) = path.strip_prefix("metrics/") else {
        return path.to_string();
    };
    let unit = if rest.starts_with("timings/") {
        "ms"
    } else if rest.ends_with("_mm") {
        "mm"
    } else if rest.ends_with("_m") || rest.contains("_m/") || rest.contains("residual") {
        "m"
    } else if rest.contains("stretch") {
        "ratio"
    } else if rest.ends_with("faces")
        || (rest.ends_with("_vertices") && !rest.contains("penetrating"))
        || rest.contains("skipped")
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
pub struct OrderedRecording(RecordingStream, bool);

impl OrderedRecording {
    /// Logs `data` at `path` on the current timelines, as its own chunk.
    pub fn log<AS: ?Sized + rerun::AsComponents>(
        &self,
        path: impl Into<rerun::EntityPath>,
        data: &AS,
    ) -> Result<(), SinkError> {
        let path = path.into();
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

impl RerunLogger {
    /// Logs into `rec`; sends the static scene settings (y up, series styles) first.
    pub fn new(rec: RecordingStream, options: LogOptions) -> Result<Self, SinkError> {
        let rec = OrderedRecording(rec, options.detail == LogDetail::Metrics);
        rec.log_static("/", &ViewCoordinates::RIGHT_HAND_Y_UP())
            .map_err(to_sink)?;
        // The mannequin figures are one value per run: markers, polar warm and chord cool.
        for region in Region::ALL {
            for (method, stat, color) in [
                ("polar", "max", [220, 40, 30]),
                ("polar", "rms", [250, 150, 60]),
                ("chord", "max", [30, 110, 230]),
                ("chord", "rms", [90, 200, 230]),
            ] {
                let name = format!("{} {method} {stat} (mm)", region.name());
                rec.log_static(
                    metric_path(&format!("metrics/mannequin/{}/{method}_{stat}_mm", region.name())),
                    &SeriesPoints::new()
                        .with_names([name])
                        .with_colors([color])
                        .with_marker_sizes([4.0]),
                )
                .map_err(to_sink)?;
            }
        }
        Ok(Self { rec, options, iter: 0 })
    }

    /// The recording.
    pub fn recording(&self) -> &OrderedRecording {
        &self.rec
    }

    /// The next value of the `iter` timeline (solver iterations, counted over the session).
    pub(super) fn next_iter(&mut self) -> i64 {
        self.iter += 1;
        self.iter
    }

    pub(super) fn text(&self, level: &str, text: String) -> Result<(), SinkError> {
        self.rec
            .log("log", &TextLog::new(text).with_level(level))
            .map_err(to_sink)
    }

    /// Logs a figure under `metrics/<unit>/...` (see [`metric_path`]), so that each plot
    /// of the default layout holds one unit.
    pub(super) fn scalar(&self, path: &str, value: f64) -> Result<(), SinkError> {
        self.rec
            .log(metric_path(path), &Scalars::single(value))
            .map_err(to_sink)
    }
}

impl StageSink for RerunLogger {
    fn stage(&mut self, info: &StageInfo, stage: Stage<'_>) -> Result<(), SinkError> {
        self.rec.set_time_sequence("step", info.step as i64);
        self.rec.set_time_sequence("stage", info.stage as i64);
        if self.options.detail != LogDetail::Final || is_final(&stage) {
            stage.dispatch(info, self)?;
        }
        // Every log call is already its own chunk (OrderedRecording); this sends what is left.
        self.rec.flush_async().map_err(|e| SinkError::Backend {
            what: "rerun flush",
            source: Box::new(e),
        })
    }

    fn body(&mut self, _info: &StageInfo, stage: BodyStage<'_>) -> Result<(), SinkError> {
        match stage {
            BodyStage::Mesh(body) => self.log_body_mesh(body),
            BodyStage::Landmarks(_, landmarks) => self.log_landmarks(landmarks),
            BodyStage::Rings(rings) => self.log_rings(rings),
            BodyStage::Partitions(body, partitions) => self.log_partitions(body, partitions),
        }
    }

    fn mannequin(&mut self, _info: &StageInfo, result: &MannequinResult) -> Result<(), SinkError> {
        self.log_mannequin(result)
    }

    fn nurbs_experiment(&mut self, _info: &StageInfo, result: &crate::nurbs::Experiment) -> Result<(), SinkError> {
        self.log_nurbs_experiment(result)
    }

    fn nurbs(&mut self, _info: &StageInfo, stage: crate::session::NurbsStage<'_>) -> Result<(), SinkError> {
        self.log_nurbs_parts(stage)
    }

    fn section(&mut self, _info: &StageInfo, cut: SectionCut<'_>) -> Result<(), SinkError> {
        self.log_section(cut)
    }

    fn garment(&mut self, _info: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        match stage {
            GarmentStage::Part(fw, part) => self.log_garment_part(fw, part),
            GarmentStage::Edit { name, before, after } => self.log_garment_edit(name, before, after),
            GarmentStage::Refused { name, value, message } => self.text(
                TextLogLevel::WARN,
                format!("set {name} {value} refused: {message}; the garment is as before"),
            ),
            GarmentStage::CutRefused { message, .. } => {
                self.text(TextLogLevel::WARN, format!("{message}; the garment is as before"))
            }
            GarmentStage::Undone { framework, net } => self.log_undone(framework, net),
        }
    }

    fn collision(&mut self, _info: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        self.log_collision(stage)
    }

    fn constraints(&mut self, _info: &StageInfo, stage: ConstraintStage<'_>) -> Result<(), SinkError> {
        match stage {
            ConstraintStage::Network(fw, net) => self.log_network_built(fw, net),
            ConstraintStage::Solve {
                edit, net, solution, ..
            } => self.log_solve(edit, net, solution),
            ConstraintStage::Refused { edit, message } => self.log_refused(edit, message),
        }
    }

    fn m1(&mut self, _info: &StageInfo, stage: M1Stage<'_>) -> Result<(), SinkError> {
        self.log_m1(stage)
    }

    fn sculpt(&mut self, _info: &StageInfo, stage: crate::session::SculptStage<'_>) -> Result<(), SinkError> {
        self.log_sculpt(stage)
    }

    fn sculpt_compare(&mut self, _info: &StageInfo, cmp: &crate::sculpt::Comparison) -> Result<(), SinkError> {
        self.log_sculpt_compare(cmp)
    }

    fn step_end(&mut self, _info: &StageInfo, end: StepEnd<'_>) -> Result<(), SinkError> {
        match end {
            StepEnd::Done(metrics) => {
                if self.options.timings {
                    for (name, ms) in &metrics.timings_ms {
                        self.scalar(&format!("metrics/timings/{name}"), *ms)?;
                    }
                }
                self.text(
                    TextLogLevel::DEBUG,
                    format!("step {} ({}) done", metrics.step, metrics.op),
                )?;
                if self.options.settle {
                    self.rec.flush_blocking()?;
                }
                Ok(())
            }
            StepEnd::Failed(error) => self.text(TextLogLevel::ERROR, error.to_string()),
            StepEnd::Interrupted { after } => self.text(
                TextLogLevel::WARN,
                format!("interrupted by a signal after step {after}: the steps after it did not run"),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every edge of a mesh (a grid with both diagonals here and there, a fan, a lone edge,
    /// an isolated vertex) is drawn exactly once by the paths, and nothing else is.
    #[test]
    fn edge_paths_draw_every_edge_once_and_nothing_else() {
        let w = 7;
        let mut positions: Vec<DVec3> = (0..w * w)
            .map(|k| DVec3::new((k % w) as f64, (k / w) as f64, 0.1 * ((k * 7919) % 13) as f64))
            .collect();
        let id = |i: usize, j: usize| (j * w + i) as u32;
        let mut edges = Vec::new();
        for j in 0..w {
            for i in 0..w {
                if i + 1 < w {
                    edges.push([id(i, j), id(i + 1, j)]);
                }
                if j + 1 < w {
                    edges.push([id(i, j + 1), id(i, j)]);
                }
                if i + 1 < w && j + 1 < w {
                    edges.push([id(i, j), id(i + 1, j + 1)]);
                    if (i + j) % 3 == 0 {
                        edges.push([id(i + 1, j), id(i, j + 1)]);
                    }
                }
            }
        }
        let lone = positions.len() as u32;
        positions.extend([
            DVec3::new(9.0, 9.0, 9.0),
            DVec3::new(9.5, 9.0, 9.0),
            DVec3::new(-3.0, 0.0, 0.0),
        ]);
        edges.push([lone, lone + 1]);
        let key = |p: [f32; 3]| p.map(f32::to_bits);
        let mut expected: Vec<_> = edges
            .iter()
            .map(|&[a, b]| {
                let (p, q) = (
                    key(positions[a as usize].as_vec3().to_array()),
                    key(positions[b as usize].as_vec3().to_array()),
                );
                if p <= q { (p, q) } else { (q, p) }
            })
            .collect();
        expected.sort_unstable();
        let paths = edge_paths(&positions, &edges);
        let mut drawn: Vec<_> = paths
            .iter()
            .flat_map(|path| path.windows(2).map(|s| (key(s[0]), key(s[1]))))
            .map(|(p, q)| if p <= q { (p, q) } else { (q, p) })
            .collect();
        drawn.sort_unstable();
        assert_eq!(drawn, expected);
        let points: usize = paths.iter().map(Vec::len).sum();
        assert!(
            points < 2 * edges.len() * 3 / 4,
            "{points} points for {} edges",
            edges.len()
        );
        assert!(edge_paths(&positions, &[]).is_empty());
    }
}
