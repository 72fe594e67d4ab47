//! [`RerunLogger`]: the stage sink that logs to a Rerun recording.

use rerun::{RecordingStream, Scalars, TextLog, TextLogLevel, ViewCoordinates};

use super::parts::{Layout, Parted};
use super::recording::{OrderedRecording, metric_path};
use crate::mannequin::MannequinResult;
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
    /// Send a garment mesh's parts (M0, its clearance map, M1, their edges) only where they
    /// differ from what the recording shows at their entity already: the latest-at scene at
    /// every step is the one logging every part gives. Off logs every part at every step
    /// (to compare). Default value: true.
    pub only_changed: bool,
    /// The fewest faces of a part a garment mesh is logged in (consecutive patches grouped
    /// until they have as many; see `viz::parts`): smaller parts send less again after
    /// a local change, and each costs a chunk of its own. Default value: 4096.
    pub part_faces: usize,
}

impl Default for LogOptions {
    fn default() -> Self {
        Self {
            timings: false,
            mannequin_offset_x: 1.6,
            detail: LogDetail::All,
            settle: false,
            only_changed: true,
            part_faces: super::parts::PART_FACES,
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

    /// Sets [`Self::only_changed`].
    #[must_use]
    pub fn with_only_changed(mut self, only_changed: bool) -> Self {
        self.only_changed = only_changed;
        self
    }

    /// Sets [`Self::part_faces`].
    #[must_use]
    pub fn with_part_faces(mut self, part_faces: usize) -> Self {
        self.part_faces = part_faces;
        self
    }

    /// Sets [`Self::mannequin_offset_x`].
    #[must_use]
    pub fn with_mannequin_offset_x(mut self, x: f64) -> Self {
        self.mannequin_offset_x = x;
        self
    }
}

/// How many layouts of each mesh the logger keeps (see [`RerunLogger::parted`]).
const LAYOUTS_KEPT: usize = 2;

/// Logs every stage to a recording.
pub struct RerunLogger {
    pub(super) rec: OrderedRecording,
    pub(super) options: LogOptions,
    iter: i64,
    /// The garments worn over others logged so far (the layout names them).
    pub(super) layered: Vec<String>,
    /// The last layouts of each mesh logged in parts, by entity root, the latest first (at
    /// most [`LAYOUTS_KEPT`]): a refinement undone, or one that goes back and forth between
    /// two steps, finds its layout again.
    layouts: std::sync::Mutex<std::collections::BTreeMap<&'static str, Vec<std::sync::Arc<Layout>>>>,
    /// The buffer the meshes' normals are summed in, kept from mesh to mesh so that the sums
    /// take no new pages.
    normals: std::sync::Mutex<Vec<glam::DVec3>>,
    /// The series of each entity the step figures are plotted in.
    pub(super) series: super::series::Series,
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

/// Whether a stage is logged at [`LogDetail::Final`]: the body's mesh, M0 as built and
/// after its collision, M1 with its cut lines, refusals, and the ends of steps.
fn is_final(stage: &Stage<'_>) -> bool {
    match stage {
        Stage::Body(b) => matches!(b, BodyStage::Mesh(_)),
        Stage::Garment(g) => !matches!(g, GarmentStage::Part(_, part) if *part != crate::session::GarmentPart::Mesh),
        Stage::Collision(c) => c.part == crate::session::CollisionPart::Respond,
        Stage::Constraints(c) => matches!(c, ConstraintStage::Refused { .. }),
        Stage::M1(_)
        | Stage::Patterns(_)
        | Stage::Step(_)
        | Stage::Nurbs(_)
        | Stage::Sculpt(_)
        | Stage::SculptCompare(_) => true,
        _ => false,
    }
}

impl RerunLogger {
    /// Logs into `rec`; sends the static scene settings (y up) first.
    pub fn new(rec: RecordingStream, options: LogOptions) -> Result<Self, SinkError> {
        let rec = OrderedRecording::new(rec, options.detail == LogDetail::Metrics, options.only_changed);
        rec.log_static("/", &ViewCoordinates::RIGHT_HAND_Y_UP())
            .map_err(to_sink)?;
        Ok(Self {
            rec,
            options,
            iter: 0,
            layered: Vec::new(),
            layouts: Default::default(),
            normals: Default::default(),
            series: Default::default(),
        })
    }

    /// The recording.
    pub fn recording(&self) -> &OrderedRecording {
        &self.rec
    }

    /// The mesh at `root` (`triangles` over `positions`, its faces' patches and its edges)
    /// as it is logged in parts, its layout kept from one of the last meshes logged there
    /// whose faces, patches and edges are the same (a layout depends on nothing else, so the
    /// data logged is the same as with a new one).
    pub(super) fn parted(
        &self,
        root: &'static str,
        (positions, triangles): (&[glam::DVec3], &[[u32; 3]]),
        face_patch: &std::sync::Arc<Vec<u32>>,
        edges: &std::sync::Arc<Vec<[u32; 2]>>,
    ) -> Parted {
        let part_faces = self.options.part_faces;
        let mut layouts = self.layouts.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let kept = layouts.entry(root).or_default();
        let fitting = (kept.iter()).position(|l| l.fits((positions.len(), triangles), (face_patch, edges), part_faces));
        let layout = match fitting {
            Some(k) => kept.remove(k),
            None => std::sync::Arc::new(Layout::new(
                positions.len(),
                triangles,
                (face_patch, edges),
                (part_faces, kept.first().map(|b| &**b)),
            )),
        };
        kept.insert(0, std::sync::Arc::clone(&layout));
        kept.truncate(LAYOUTS_KEPT);
        drop(layouts);
        let mut sums = self.normals.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        Parted::of(positions, layout, &mut sums)
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
        self.rec.set_layer(info.layer.clone());
        let logged = if self.options.detail != LogDetail::Final || is_final(&stage) {
            stage.dispatch(info, self)
        } else {
            Ok(())
        };
        self.rec.set_layer(None);
        // Every log call is its own chunk, already sent (OrderedRecording): nothing to flush.
        logged
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

    fn patterns(&mut self, _info: &StageInfo, stage: crate::session::PatternStage<'_>) -> Result<(), SinkError> {
        self.log_patterns(stage)
    }

    fn layers(&mut self, info: &StageInfo, layered: &crate::session::Layered) -> Result<(), SinkError> {
        self.log_layers(info, layered)
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
                self.log_figures(metrics)?;
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
