//! The session runner: scene set-up, then each step, each producing stages that go to a
//! [`StageSink`] (the Rerun logger, the mesh exporter, tests). Timings measure compute
//! only; the sinks' time is kept apart under `log.*` keys.

use std::path::PathBuf;
use std::time::Instant;

use serde_json::json;
use thiserror::Error;

use super::format::{Op, Session};
use super::metrics::StepMetrics;
use crate::body::{
    self, Body, BodyMesh, BodyRing, BodySource, LandmarkOptions, Landmarks, Partition, PartitionOptions,
};
use crate::collision::{self, BodyIndex, Collision, CollisionOptions, DetectState, GarmentMesh, VerifyReport};
use crate::constraint::{self, ConstraintNet, Edit, NetworkOptions, Solution};
use crate::garment::assemble::assemble;
use crate::garment::{BodyProbe, Dimensions, Framework, FrameworkOptions, TemplateKind, build_framework};
use crate::geom::{Plane, SectionLoop, section_mesh};
use crate::mannequin::{DressForm, MannequinResult, Region, run_mannequin};

/// Where a stage sits: its step and its global stage number.
#[derive(Clone, Debug, PartialEq)]
pub struct StageInfo {
    /// Step index (0 is the scene).
    pub step: usize,
    /// The step's operation keyword.
    pub op: &'static str,
    /// Global stage counter, one per stage over the whole session.
    pub stage: u64,
    /// Stage name (`body.load`, `mannequin.refine`, ...).
    pub name: &'static str,
}

/// The data of one stage.
#[derive(Clone, Copy, Debug)]
pub enum Stage<'a> {
    /// The body mesh was loaded and validated.
    BodyMesh(&'a BodyMesh),
    /// Landmarks were found.
    Landmarks(&'a BodyMesh, &'a Landmarks),
    /// Rings were cut at the landmarks.
    Rings(&'a [BodyRing]),
    /// Partitions were built.
    Partitions(&'a BodyMesh, &'a [Partition]),
    /// The mannequin was refined and measured.
    Mannequin(&'a MannequinResult),
    /// A body section.
    Section {
        /// Name.
        name: &'a str,
        /// Height.
        y: f64,
        /// The loops.
        loops: &'a [SectionLoop],
    },
    /// A garment stage: one part of the framework solve.
    Garment(&'a Framework, GarmentPart),
    /// A dimension edit: the framework before and after.
    GarmentEdit {
        /// The dimension changed.
        name: &'a str,
        /// Before.
        before: &'a Framework,
        /// After.
        after: &'a Framework,
    },
    /// Mesh-layer collision of a step's M0.
    Collision(&'a CollisionOutcome, &'a BodyIndex, CollisionPart),
    /// The constraint network of a garment as built.
    Network(&'a Framework, &'a ConstraintNet),
    /// An edit solved by the constraint layer: the framework before, the solution (its
    /// framework is re-surfaced in the stages that follow).
    Solve {
        /// The edit.
        edit: &'a Edit,
        /// The network.
        net: &'a ConstraintNet,
        /// Before the edit.
        before: &'a Framework,
        /// The solve.
        solution: &'a Solution,
    },
    /// An edit was refused; the garment is as before the step.
    Refused {
        /// The edit.
        edit: &'a Edit,
        /// Why.
        message: &'a str,
    },
    /// `undo`: the garment is back to this state (with its constraint network, once one
    /// was built).
    Undone {
        /// The framework restored.
        framework: &'a Framework,
        /// Its constraint network.
        net: Option<&'a ConstraintNet>,
    },
    /// A step failed; everything before it stands.
    Failed(&'a RunError),
    /// A step finished with these metrics.
    StepDone(&'a StepMetrics),
}

/// The parts of a collision, in the order they are emitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CollisionPart {
    /// Detection: the penetrating vertices by partition.
    Detect,
    /// Response: the moved vertices and M0 after it.
    Respond,
}

impl CollisionPart {
    /// Stage name.
    pub fn stage_name(self) -> &'static str {
        match self {
            Self::Detect => "collision.detect",
            Self::Respond => "collision.response",
        }
    }
}

/// A step's collision: M0 as collided, the result, and the ground-truth check.
#[derive(Clone, Debug)]
pub struct CollisionOutcome {
    /// The garment mesh before response, with its roles.
    pub garment: GarmentMesh,
    /// Detection, response, quality.
    pub collision: Collision,
    /// With `--verify`: the brute-force check.
    pub verify: Option<VerifyReport>,
    /// Template name (for file names).
    pub template: &'static str,
}

/// The parts of a garment solve, in the order they are emitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GarmentPart {
    /// The section planes.
    Planes,
    /// Every ring at one sub-step.
    Rings(RingStep),
    /// Open curves, contours, seams (and the loose-fit straightening).
    Curves,
    /// The Coons patches.
    Patches,
    /// The stitched mesh M0.
    Mesh,
}

/// A ring sub-step ([frame] section 2.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RingStep {
    /// The body section.
    Raw,
    /// Convexified.
    Convex,
    /// Resampled at equal chords.
    Resampled,
    /// Eased.
    Eased,
    /// Spline fitted through the control points and resampled.
    Fitted,
}

impl RingStep {
    /// In order.
    pub const ALL: [Self; 5] = [Self::Raw, Self::Convex, Self::Resampled, Self::Eased, Self::Fitted];

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Raw => "raw",
            Self::Convex => "convex",
            Self::Resampled => "resampled",
            Self::Eased => "eased",
            Self::Fitted => "fitted",
        }
    }
}

impl GarmentPart {
    /// Every part in emission order.
    pub fn all() -> Vec<Self> {
        let mut out = vec![Self::Planes];
        out.extend(RingStep::ALL.map(Self::Rings));
        out.extend([Self::Curves, Self::Patches, Self::Mesh]);
        out
    }

    /// Stage name.
    pub fn stage_name(self) -> &'static str {
        match self {
            Self::Planes => "garment.planes",
            Self::Rings(RingStep::Raw) => "garment.rings.raw",
            Self::Rings(RingStep::Convex) => "garment.rings.convex",
            Self::Rings(RingStep::Resampled) => "garment.rings.resampled",
            Self::Rings(RingStep::Eased) => "garment.rings.eased",
            Self::Rings(RingStep::Fitted) => "garment.rings.fitted",
            Self::Curves => "garment.curves",
            Self::Patches => "garment.patches",
            Self::Mesh => "garment.m0",
        }
    }
}

/// Error from a sink (logging or export).
#[derive(Debug, Error)]
#[error("{0}")]
pub struct SinkError(pub String);

/// Receives every stage as it is produced.
pub trait StageSink {
    /// Takes one stage.
    fn stage(&mut self, info: &StageInfo, stage: Stage<'_>) -> Result<(), SinkError>;
}

/// A step that failed at run time.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{session}:{line}: step {step} ({op}) failed: {message}")]
pub struct RunError {
    /// Session name.
    pub session: String,
    /// Line of the step (1 for the scene).
    pub line: usize,
    /// Step index.
    pub step: usize,
    /// Operation.
    pub op: &'static str,
    /// What went wrong.
    pub message: String,
}

/// Run settings from the command line.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Replaces the session's body (`--body`).
    pub body_override: Option<PathBuf>,
    /// Landmark detection settings (overrides come from the session).
    pub landmarks: LandmarkOptions,
    /// Partition settings.
    pub partitions: PartitionOptions,
    /// Collision settings.
    pub collision: CollisionOptions,
    /// Check every collision against the brute-force ground truth (`--verify`; slow).
    pub verify: bool,
}

/// What a run produced.
#[derive(Debug, Default)]
pub struct RunReport {
    /// Metrics of every step that ran (the failed one included, with its error).
    pub steps: Vec<StepMetrics>,
    /// The error that stopped the run.
    pub error: Option<RunError>,
}

struct Driver<'s, 'k> {
    sinks: &'k mut [&'s mut dyn StageSink],
    stage: u64,
    sink_errors: Vec<String>,
}

impl Driver<'_, '_> {
    fn emit(&mut self, step: usize, op: &'static str, name: &'static str, stage: Stage<'_>, metrics: &mut StepMetrics) {
        let info = StageInfo {
            step,
            op,
            stage: self.stage,
            name,
        };
        self.stage += 1;
        let start = Instant::now();
        for sink in self.sinks.iter_mut() {
            if let Err(e) = sink.stage(&info, stage) {
                self.sink_errors.push(format!("{name}: {e}"));
            }
        }
        *metrics.timings_ms.entry(format!("log.{name}")).or_insert(0.0) += start.elapsed().as_secs_f64() * 1e3;
    }
}

fn timed<T>(metrics: &mut StepMetrics, name: &str, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let out = f();
    metrics
        .timings_ms
        .insert(name.to_string(), start.elapsed().as_secs_f64() * 1e3);
    out
}

/// Runs a session: the scene (step 0), then each step. Stops at the first failure,
/// which is reported to the sinks as a [`Stage::Failed`] and returned in the report.
pub fn run_session(session: &Session, options: &RunOptions, sinks: &mut [&mut dyn StageSink]) -> RunReport {
    let mut driver = Driver {
        sinks,
        stage: 0,
        sink_errors: Vec::new(),
    };
    let mut report = RunReport::default();
    let fail = |step: usize, line: usize, op: &'static str, message: String| RunError {
        session: session.name.clone(),
        line,
        step,
        op,
        message,
    };

    // --- Step 0: the scene.
    let mut m = StepMetrics {
        step: 0,
        op: "scene".into(),
        ..StepMetrics::default()
    };
    let source = options
        .body_override
        .clone()
        .map_or_else(|| session.scene.body.clone(), BodySource::File);
    let mut landmark_options = options.landmarks.clone();
    landmark_options.overrides = session.scene.landmarks.clone();
    let scene = (|| -> Result<Body, body::BodyError> {
        let mesh = timed(&mut m, "body.load", || {
            BodyMesh::load(&source, session.scene.units.scale())
        })?;
        m.set("body", mesh.name.clone());
        m.set("vertices", mesh.mesh.positions.len());
        m.set("triangles", mesh.mesh.triangles.len());
        m.set("height_m", mesh.height());
        m.set("repairs", mesh.report.notes());
        m.set("mesh_report", serde_json::to_value(&mesh.report).unwrap_or_default());
        driver.emit(0, "scene", "body.load", Stage::BodyMesh(&mesh), &mut m);
        let landmarks = timed(&mut m, "body.landmarks", || {
            body::find_landmarks(&mesh, &landmark_options)
        })?;
        m.set("landmarks", serde_json::to_value(&landmarks.items).unwrap_or_default());
        if let Some(plane) = landmarks.neck_plane() {
            m.set("neck_plane_tilt_deg", plane.tilt().to_degrees());
        }
        driver.emit(
            0,
            "scene",
            "body.landmarks",
            Stage::Landmarks(&mesh, &landmarks),
            &mut m,
        );
        let rings = timed(&mut m, "body.rings", || body::cut_rings(&mesh, &landmarks))?;
        m.set("rings", serde_json::to_value(&rings).unwrap_or_default());
        driver.emit(0, "scene", "body.rings", Stage::Rings(&rings), &mut m);
        let partitions = timed(&mut m, "body.partitions", || {
            body::build_partitions(&mesh, &landmarks, &options.partitions)
        })?;
        m.set("partitions", serde_json::to_value(&partitions).unwrap_or_default());
        driver.emit(
            0,
            "scene",
            "body.partitions",
            Stage::Partitions(&mesh, &partitions),
            &mut m,
        );
        Ok(Body {
            mesh,
            landmarks,
            rings,
            partitions,
        })
    })();
    let body = match scene {
        Ok(b) => b,
        Err(e) => {
            let error = fail(0, 1, "scene", e.to_string());
            m.error = Some(error.message.clone());
            driver.emit(0, "scene", "failed", Stage::Failed(&error), &mut m);
            report.steps.push(m);
            report.error = Some(error);
            return report;
        }
    };
    let done = m.clone();
    driver.emit(0, "scene", "done", Stage::StepDone(&done), &mut m);
    report.steps.push(m);
    let mut probe: Option<BodyProbe> = None;
    let mut garment: Option<GarmentState> = None;
    // Garment states before each drag or set, for `undo`.
    let mut history: Vec<GarmentState> = Vec::new();

    // --- The steps.
    for (i, step) in session.steps.iter().enumerate() {
        let step_index = i + 1;
        let op = step.op.keyword();
        let mut m = StepMetrics {
            step: step_index,
            op: op.into(),
            ..StepMetrics::default()
        };
        let outcome: Result<(), String> = match &step.op {
            Op::Mannequin(options) => {
                let form = DressForm::default();
                match timed(&mut m, "mannequin.refine", || run_mannequin(&form, options)) {
                    Ok(result) => {
                        m.set("layers", options.layers);
                        m.set("points", options.points);
                        m.set("dense_layers", result.polar.layers);
                        m.set("dense_points", result.polar.points);
                        let regions: Vec<_> = Region::REPORT_ORDER
                            .iter()
                            .filter_map(|r| result.regions.iter().find(|e| e.region == r.name()))
                            .map(|e| json!({"region": e.region, "polar": e.polar, "chord": e.chord}))
                            .collect();
                        m.set("regions", regions);
                        driver.emit(step_index, op, "mannequin.refine", Stage::Mannequin(&result), &mut m);
                        Ok(())
                    }
                    Err(e) => Err(e.to_string()),
                }
            }
            Op::Section { name, y } => {
                let loops = timed(&mut m, "section.cut", || {
                    section_mesh(&body.mesh.mesh, &body.mesh.adjacency, &Plane::horizontal(*y))
                });
                if loops.is_empty() {
                    let (lo, hi) = body.mesh.mesh.bounds().map_or((0.0, 0.0), |(l, h)| (l.y, h.y));
                    Err(format!(
                        "section '{name}' at y = {y:.4} m cuts nothing: the body spans {lo:.4}..{hi:.4} m"
                    ))
                } else {
                    m.set("loops", loops.len());
                    m.set("lengths_m", loops.iter().map(SectionLoop::length).collect::<Vec<_>>());
                    driver.emit(
                        step_index,
                        op,
                        "section.cut",
                        Stage::Section {
                            name,
                            y: *y,
                            loops: &loops,
                        },
                        &mut m,
                    );
                    Ok(())
                }
            }
            Op::Garment {
                template,
                fit,
                resolution,
            } => {
                let fw_options = FrameworkOptions::default().with_fit(*fit).with_resolution(*resolution);
                let state = GarmentState {
                    template: *template,
                    options: fw_options,
                    dims: Dimensions::default(),
                    framework: None,
                    detect: DetectState::default(),
                    collision: None,
                    net: None,
                    edits: Vec::new(),
                };
                history.clear();
                solve_garment(&body, &mut probe, options, state, &mut m).map(|mut state| {
                    if let Some(fw) = &state.framework {
                        for part in GarmentPart::all() {
                            driver.emit(step_index, op, part.stage_name(), Stage::Garment(fw, part), &mut m);
                        }
                        if let Some(net) = &state.net {
                            driver.emit(step_index, op, "constraints.network", Stage::Network(fw, net), &mut m);
                        }
                    }
                    if let Some(probe) = &probe {
                        collide_garment(&body, probe.index(), &mut state, options, &mut m);
                        emit_collision(&mut driver, step_index, op, &state, probe.index(), &mut m);
                    }
                    garment = Some(state);
                })
            }
            Op::Set { name, change } => match garment.as_ref().and_then(|g| g.framework.as_ref().map(|f| (g, f))) {
                None => Err("no garment to change: a 'garment' step must come first".to_string()),
                Some((state, before)) => {
                    let current = before.dimension(name).unwrap_or(0.0);
                    let value = change.apply(current);
                    m.set("dimension", name.clone());
                    m.set("before", current);
                    m.set("value", value);
                    let mut next = GarmentState {
                        template: state.template,
                        options: state.options,
                        dims: state.dims.clone(),
                        framework: None,
                        detect: state.detect.clone(),
                        collision: None,
                        net: None,
                        edits: state.edits.clone(),
                    };
                    next.dims.values.insert(name.clone(), value);
                    let solved = solve_garment(&body, &mut probe, options, next, &mut m)
                        .and_then(|next| replay_edits(next, probe.as_ref(), &session.scene.solver, &mut m));
                    match solved {
                        Ok(mut next) => {
                            if let Some(after) = &next.framework {
                                let moved = before
                                    .m0
                                    .mesh
                                    .positions
                                    .iter()
                                    .zip(&after.m0.mesh.positions)
                                    .map(|(a, b)| a.distance(*b))
                                    .fold(0.0, f64::max);
                                m.set("max_vertex_move_m", moved);
                                driver.emit(
                                    step_index,
                                    op,
                                    "garment.edit",
                                    Stage::GarmentEdit { name, before, after },
                                    &mut m,
                                );
                                for part in GarmentPart::all() {
                                    driver.emit(step_index, op, part.stage_name(), Stage::Garment(after, part), &mut m);
                                }
                            }
                            if let Some(probe) = &probe {
                                collide_garment(&body, probe.index(), &mut next, options, &mut m);
                                emit_collision(&mut driver, step_index, op, &next, probe.index(), &mut m);
                            }
                            if let Some(previous) = garment.replace(next) {
                                history.push(previous);
                            }
                            Ok(())
                        }
                        Err(e) => Err(e),
                    }
                }
            },
            Op::Drag(edit) => match (garment.as_ref(), probe.as_ref()) {
                (Some(state), Some(probe)) if state.framework.is_some() && state.net.is_some() => {
                    match drag(state, edit, probe, &session.scene.solver, &mut m) {
                        Ok((mut next, solution)) => {
                            if let (Some(before), Some(net), Some(after)) =
                                (&state.framework, &state.net, &next.framework)
                            {
                                driver.emit(
                                    step_index,
                                    op,
                                    "constraints.solve",
                                    Stage::Solve {
                                        edit,
                                        net,
                                        before,
                                        solution: &solution,
                                    },
                                    &mut m,
                                );
                                for part in [GarmentPart::Curves, GarmentPart::Patches, GarmentPart::Mesh] {
                                    driver.emit(step_index, op, part.stage_name(), Stage::Garment(after, part), &mut m);
                                }
                            }
                            collide_garment(&body, probe.index(), &mut next, options, &mut m);
                            emit_collision(&mut driver, step_index, op, &next, probe.index(), &mut m);
                            if let Some(previous) = garment.replace(next) {
                                history.push(previous);
                            }
                        }
                        Err(message) => {
                            // Refused: the garment stays as it was (an `undo` of this step
                            // changes nothing); the session goes on.
                            history.push(state.clone());
                            m.set("refused", message.clone());
                            driver.emit(
                                step_index,
                                op,
                                "constraints.refused",
                                Stage::Refused {
                                    edit,
                                    message: &message,
                                },
                                &mut m,
                            );
                        }
                    }
                    Ok(())
                }
                _ => Err("no garment to drag: a 'garment' step must come first".to_string()),
            },
            Op::Undo => match history.pop() {
                None => Err("nothing to undo: no drag or set step of the current garment ran".to_string()),
                Some(previous) => {
                    if let Some(fw) = &previous.framework {
                        m.set("m0_vertices", fw.m0.mesh.positions.len());
                        driver.emit(
                            step_index,
                            op,
                            "garment.undo",
                            Stage::Undone {
                                framework: fw,
                                net: previous.net.as_ref(),
                            },
                            &mut m,
                        );
                        for part in [GarmentPart::Curves, GarmentPart::Patches, GarmentPart::Mesh] {
                            driver.emit(step_index, op, part.stage_name(), Stage::Garment(fw, part), &mut m);
                        }
                    }
                    if let Some(probe) = &probe {
                        emit_collision(&mut driver, step_index, op, &previous, probe.index(), &mut m);
                    }
                    garment = Some(previous);
                    Ok(())
                }
            },
        };
        if let Err(message) = outcome {
            let error = fail(step_index, step.line, op, message);
            m.error = Some(error.message.clone());
            driver.emit(step_index, op, "failed", Stage::Failed(&error), &mut m);
            report.steps.push(m);
            report.error = Some(error);
            return report;
        }
        let done = m.clone();
        driver.emit(step_index, op, "done", Stage::StepDone(&done), &mut m);
        report.steps.push(m);
    }
    if !driver.sink_errors.is_empty() {
        report.error = Some(fail(0, 1, "log", driver.sink_errors.join("; ")));
    }
    report
}

/// The current garment: its template, settings, the dimensions set so far, the solve, the
/// drags made since, its constraint network, and what collision remembers between steps.
#[derive(Clone)]
struct GarmentState {
    template: TemplateKind,
    options: FrameworkOptions,
    dims: Dimensions,
    framework: Option<Framework>,
    detect: DetectState,
    collision: Option<CollisionOutcome>,
    net: Option<ConstraintNet>,
    edits: Vec<Edit>,
}

/// Solves a drag on the state's framework and re-surfaces the changed patches. The state
/// is not touched; the error is the refusal's message.
fn drag(
    state: &GarmentState,
    edit: &Edit,
    probe: &BodyProbe,
    solver: &constraint::SolverOptions,
    m: &mut StepMetrics,
) -> Result<(GarmentState, Solution), String> {
    let (Some(before), Some(net)) = (&state.framework, &state.net) else {
        return Err("no garment to drag".into());
    };
    let solution = timed(m, "constraints.solve", || {
        constraint::solve(before, net, edit, probe, solver)
    })
    .map_err(|e| e.to_string())?;
    let built = timed(m, "garment.assemble", || {
        assemble(&solution.framework, probe, Some(before))
    })
    .map_err(|e| format!("the edited curves cannot be surfaced: {e}"))?;
    let mut after = solution.framework.clone();
    after.lines = built.lines;
    after.patches = built.patches;
    after.m0 = built.m0;
    record_solve(m, net, &solution, built.resurfaced.len(), after.patches.len());
    let mut next = state.clone();
    next.framework = Some(after);
    next.collision = None;
    next.edits.push(edit.clone());
    Ok((next, solution))
}

/// Re-applies the drags made before a dimension change to the re-solved framework.
fn replay_edits(
    mut state: GarmentState,
    probe: Option<&BodyProbe>,
    solver: &constraint::SolverOptions,
    m: &mut StepMetrics,
) -> Result<GarmentState, String> {
    let edits = std::mem::take(&mut state.edits);
    let Some(probe) = probe else {
        return Ok(state);
    };
    for (k, edit) in edits.iter().enumerate() {
        let (next, _) = drag(&state, edit, probe, solver, m)
            .map_err(|e| format!("replaying drag {} of {} after the change: {e}", k + 1, edits.len()))?;
        state = next;
    }
    m.set("replayed_drags", edits.len());
    Ok(state)
}

fn record_solve(m: &mut StepMetrics, net: &ConstraintNet, s: &Solution, resurfaced: usize, patches: usize) {
    m.set("passes", s.passes);
    m.set("solver_iterations", s.iterations.len());
    m.set("converged", s.converged);
    m.set(
        "curves_solved",
        s.solved.iter().map(|&c| net.curves[c].name.clone()).collect::<Vec<_>>(),
    );
    m.set("max_residual", s.max_residual());
    let violations: Vec<_> = s
        .violations
        .iter()
        .map(|&(k, r)| {
            let c = &net.constraints[k];
            json!({
                "constraint": k,
                "kind": c.kind.name(),
                "curves": [net.curves[c.i].name.clone(), net.curves[c.j].name.clone()],
                "residual": r,
                "unit": c.kind.unit(),
            })
        })
        .collect();
    m.set("violations", violations);
    m.set("node_hits", s.iterations.iter().map(|it| it.node.len()).sum::<usize>());
    m.set("collision_gap_m", s.gap);
    m.set("clearance_deficit_m", s.clearance_deficit);
    m.set("resurfaced_patches", resurfaced);
    m.set("kept_patches", patches - resurfaced);
    if let Some(p) = s.path.last() {
        m.set("dragged_to", [p.x, p.y, p.z]);
    }
}

fn emit_collision(
    driver: &mut Driver<'_, '_>,
    step: usize,
    op: &'static str,
    state: &GarmentState,
    index: &BodyIndex,
    m: &mut StepMetrics,
) {
    if let Some(outcome) = &state.collision {
        for part in [CollisionPart::Detect, CollisionPart::Respond] {
            driver.emit(step, op, part.stage_name(), Stage::Collision(outcome, index, part), m);
        }
    }
}

/// Collides the state's M0 with the body, recording the figures in the step's metrics.
fn collide_garment(
    body: &Body,
    index: &BodyIndex,
    state: &mut GarmentState,
    options: &RunOptions,
    m: &mut StepMetrics,
) {
    let Some(fw) = &state.framework else {
        return;
    };
    let garment = GarmentMesh::from_framework(fw, index.height);
    let collision = collision::collide(index, &garment, fw.ease(), &options.collision, &mut state.detect);
    let t = collision.timings;
    for (name, ms) in [
        ("collision.detect", t.detect),
        ("collision.respond", t.respond),
        ("collision.respond_edges", t.respond_edges),
        ("collision.quality", t.quality),
    ] {
        m.timings_ms.insert(name.to_string(), ms);
    }
    let verify = options.verify.then(|| {
        timed(m, "collision.verify", || {
            let before = collision::ground_truth(&body.mesh.mesh, &garment.mesh.positions, &garment.edges);
            let after = collision::ground_truth(&body.mesh.mesh, &collision.mesh.positions, &garment.edges);
            collision::compare(&before, &collision.detection, &after, &collision.quality)
        })
    });
    record_collision(m, index, &collision, verify.as_ref());
    state.collision = Some(CollisionOutcome {
        garment,
        collision,
        verify,
        template: state.template.name(),
    });
}

fn record_collision(m: &mut StepMetrics, index: &BodyIndex, c: &Collision, verify: Option<&VerifyReport>) {
    let d = &c.detection;
    let q = &c.quality;
    m.set("penetrating_vertices", q.penetrating_vertices);
    m.set("crossing_edges", q.crossing_edges);
    m.set("max_depth_m", q.max_depth_m);
    m.set("mean_depth_m", q.mean_depth_m);
    m.set("tested_vertices", d.tested);
    m.set("skipped_inert", d.skipped_inert);
    m.set("skipped_patch", d.skipped_patch);
    m.set("patches_skipped", d.patches_skipped);
    m.set("hits", d.hits.len());
    m.set("depth_before_max_m", d.hits.iter().map(|h| h.depth).fold(0.0, f64::max));
    let mut by_partition = serde_json::Map::new();
    for (k, p) in index.partitions.iter().enumerate() {
        let n = d.hits.iter().filter(|h| h.partition == k).count();
        by_partition.insert(p.id.letter().to_string(), json!(n));
    }
    m.set("hits_by_partition", by_partition);
    m.set(
        "tested_by_method",
        json!({"point_face": d.by_method[0], "line_line": d.by_method[1]}),
    );
    let mut by_rule = serde_json::Map::new();
    for rule in collision::AppliedRule::ALL {
        let n = c.responses.iter().filter(|r| r.rule == rule).count();
        if n > 0 {
            by_rule.insert(rule.name().to_string(), json!(n));
        }
    }
    m.set("responses", c.responses.iter().filter(|r| r.edge_round == 0).count());
    m.set(
        "edge_responses",
        c.responses.iter().filter(|r| r.edge_round > 0).count(),
    );
    m.set("responses_by_rule", by_rule);
    m.set("crossing_edges_by_round", c.edge_rounds.clone());
    m.set("response_ease_m", c.ease);
    m.set("max_ease_error_m", q.max_ease_error_m);
    m.set("mean_ease_error_m", q.mean_ease_error_m);
    if let Some(v) = verify {
        m.set("verify", serde_json::to_value(v).unwrap_or_default());
    }
}

/// Solves the framework, recording its figures in the step's metrics.
fn solve_garment(
    body: &Body,
    probe: &mut Option<BodyProbe>,
    options: &RunOptions,
    mut state: GarmentState,
    m: &mut StepMetrics,
) -> Result<GarmentState, String> {
    // The body's one index (clearance here, collision after), built once per body.
    let probe = probe.get_or_insert_with(|| {
        timed(m, "body.index", || {
            BodyProbe::from_index(BodyIndex::new(body, &options.collision.slices))
        })
    });
    let fw = timed(m, "garment.solve", || {
        build_framework(body, probe, state.template, &state.dims, &state.options)
    })
    .map_err(|e| e.to_string())?;
    m.set("template", state.template.name());
    m.set("fit", fw.fit.name());
    m.set("resolution", state.options.resolution);
    m.set("m0_vertices", fw.m0.mesh.positions.len());
    m.set("m0_faces", fw.m0.mesh.triangles.len());
    m.set("m0_edges", fw.m0.edges.len());
    m.set("patches", fw.patches.len());
    m.set("stitch", serde_json::to_value(fw.m0.report).unwrap_or_default());
    let girths: Vec<_> = fw
        .rings
        .iter()
        .map(|r| {
            json!({
                "ring": r.name,
                "girth_m": r.girth,
                "target_m": r.target,
                "body_tape_m": r.body_girth,
                "relative_error": r.target.map(|t| (r.girth - t) / t),
            })
        })
        .collect();
    m.set("girths", girths);
    m.set("dimensions", serde_json::to_value(&fw.dimensions).unwrap_or_default());
    let net = timed(m, "constraints.network", || {
        ConstraintNet::for_framework(&fw, probe, &NetworkOptions::default())
    });
    m.set("constraints", net.constraints.len());
    m.set("curves", net.curves.len());
    state.net = Some(net);
    state.framework = Some(fw);
    Ok(state)
}
