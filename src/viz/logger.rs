//! [`RerunLogger`]: the stage sink that logs to a Rerun recording.

use glam::DVec3;
use rerun::{
    LineStrips3D, Mesh3D, Points3D, RecordingStream, Scalars, SeriesPoints, TextLog, TextLogLevel, Transform3D,
    ViewCoordinates,
};

use super::colors::{error_color, partition_color, partition_tint};
use crate::body::{BodyMesh, LandmarkKind, PartitionId};
use crate::body::{DetectionMethod, ResponseRule};
use crate::mannequin::{MannequinResult, Region, RingGrid};
use crate::session::runner::{SinkError, Stage, StageInfo, StageSink};

/// What the logger logs.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LogOptions {
    /// Also log compute timings as `metrics/timings/*` scalars. They are wall-clock, so two
    /// runs then differ; off by default so that a session's recording is reproducible.
    /// Default value: false.
    pub timings: bool,
    /// Where the mannequin surfaces stand, beside the body (x offset of the polar one; the
    /// chord one is 0.6 m further), clear of the partition legend. Default value: 1.6.
    pub mannequin_offset_x: f64,
}

impl Default for LogOptions {
    fn default() -> Self {
        Self {
            timings: false,
            mannequin_offset_x: 1.6,
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

    /// Sets [`Self::mannequin_offset_x`].
    #[must_use]
    pub fn with_mannequin_offset_x(mut self, x: f64) -> Self {
        self.mannequin_offset_x = x;
        self
    }
}

/// Logs every stage to a recording.
pub struct RerunLogger {
    rec: RecordingStream,
    options: LogOptions,
    iter: i64,
}

pub(super) fn to_sink(e: rerun::RecordingStreamError) -> SinkError {
    SinkError(format!("rerun: {e}"))
}

pub(super) fn f32s(points: &[DVec3]) -> Vec<[f32; 3]> {
    points.iter().map(|p| p.as_vec3().to_array()).collect()
}

pub(super) fn closed(points: &[DVec3]) -> Vec<[f32; 3]> {
    let mut v = f32s(points);
    if let Some(first) = v.first().copied() {
        v.push(first);
    }
    v
}

impl RerunLogger {
    /// Logs into `rec`; sends the static scene settings (y up, series styles) first.
    pub fn new(rec: RecordingStream, options: LogOptions) -> Result<Self, SinkError> {
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
                    format!("metrics/mannequin/{}/{method}_{stat}_mm", region.name()),
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
    pub fn recording(&self) -> &RecordingStream {
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

    pub(super) fn scalar(&self, path: &str, value: f64) -> Result<(), SinkError> {
        self.rec.log(path, &Scalars::single(value)).map_err(to_sink)
    }

    fn body_mesh(&self, body: &BodyMesh) -> Result<(), SinkError> {
        let mesh = &body.mesh;
        let normals: Vec<[f32; 3]> = mesh.vertex_normals().iter().map(|n| n.as_vec3().to_array()).collect();
        self.rec
            .log(
                "body/mesh",
                &Mesh3D::new(mesh.positions_f32())
                    .with_triangle_indices(mesh.triangles.iter().copied())
                    .with_vertex_normals(normals)
                    .with_albedo_factor([222, 196, 176, 255]),
            )
            .map_err(to_sink)?;
        let notes = body.report.notes();
        self.text(
            TextLogLevel::INFO,
            format!(
                "body {}: {} vertices, {} triangles ({} polygons triangulated), height {:.3} m; {}",
                body.name,
                mesh.positions.len(),
                mesh.triangles.len(),
                body.polygons_triangulated,
                body.height(),
                if notes.is_empty() {
                    "closed and manifold, no repairs".to_string()
                } else {
                    notes.join("; ")
                }
            ),
        )
    }

    fn mannequin(&self, result: &MannequinResult) -> Result<(), SinkError> {
        let scale = result
            .polar_error
            .iter()
            .chain(&result.chord_error)
            .copied()
            .fold(0.0, f64::max);
        let x0 = self.options.mannequin_offset_x;
        for (name, grid, errors, dx) in [
            ("polar", &result.polar, &result.polar_error, x0),
            ("chord", &result.chord, &result.chord_error, x0 + 0.6),
        ] {
            let base = format!("mannequin/{name}");
            self.rec
                .log(base.as_str(), &Transform3D::from_translation([dx as f32, 0.0, 0.0]))
                .map_err(to_sink)?;
            let colors: Vec<[u8; 3]> = errors.iter().map(|e| error_color(*e, scale)).collect();
            self.rec
                .log(
                    format!("{base}/surface"),
                    &Mesh3D::new(f32s(&grid.positions))
                        .with_triangle_indices(grid.triangles())
                        .with_vertex_colors(colors),
                )
                .map_err(to_sink)?;
            self.rec
                .log(
                    format!("{base}/measured"),
                    &Points3D::new(f32s(&result.measured.positions))
                        .with_radii([0.003])
                        .with_colors([[20, 20, 20]]),
                )
                .map_err(to_sink)?;
            let worst = errors.iter().copied().fold(0.0, f64::max);
            let top = grid_top(grid) + DVec3::new(0.0, 0.06, 0.0);
            self.rec
                .log(
                    format!("{base}/title"),
                    &Points3D::new([top.as_vec3().to_array()])
                        .with_labels([format!("{name}: max {:.2} mm", worst * 1e3)])
                        .with_radii([0.001])
                        .with_show_labels(true),
                )
                .map_err(to_sink)?;
        }
        let mut lines = vec![format!(
            "mannequin {} x {} refined to {} x {}; colour: distance to the true surface, 0 (blue) .. {:.2} mm (red)",
            result.options.layers,
            result.options.points,
            result.polar.points,
            result.polar.layers,
            scale * 1e3
        )];
        for r in &result.regions {
            let [pm, pr, cm, cr] = r.millimetres();
            lines.push(format!(
                "  {:<8} polar max {pm:.3} mm rms {pr:.3} mm | chord max {cm:.3} mm rms {cr:.3} mm",
                r.region
            ));
            for (method, stats) in [("polar", r.polar), ("chord", r.chord)] {
                self.scalar(
                    &format!("metrics/mannequin/{}/{method}_max_mm", r.region),
                    stats.max_m * 1e3,
                )?;
                self.scalar(
                    &format!("metrics/mannequin/{}/{method}_rms_mm", r.region),
                    stats.rms_m * 1e3,
                )?;
            }
        }
        self.text(TextLogLevel::INFO, lines.join("\n"))
    }
}

fn method_name(m: DetectionMethod) -> &'static str {
    match m {
        DetectionMethod::PointFace => "point-face",
        DetectionMethod::LineLine => "line-line",
    }
}

fn response_name(r: ResponseRule) -> &'static str {
    match r {
        ResponseRule::RingCentre => "ring-centre",
        ResponseRule::BodyNormal => "body-normal",
        ResponseRule::ViewDirection => "view-direction",
        ResponseRule::VertexNormal => "vertex-normal",
    }
}

fn grid_top(grid: &RingGrid) -> DVec3 {
    let last = grid.layers.saturating_sub(1);
    let n = grid.points.max(1) as f64;
    (0..grid.points).map(|j| grid.at(last, j)).sum::<DVec3>() / n
}

impl StageSink for RerunLogger {
    fn stage(&mut self, info: &StageInfo, stage: Stage<'_>) -> Result<(), SinkError> {
        self.rec.set_time_sequence("step", info.step as i64);
        self.rec.set_time_sequence("stage", info.stage as i64);
        self.log_stage(stage)?;
        // One chunk boundary per stage (the batcher never flushes on its own, see viz::target).
        self.rec
            .flush_async()
            .map_err(|e| SinkError(format!("rerun flush: {e}")))
    }
}

impl RerunLogger {
    fn log_stage(&mut self, stage: Stage<'_>) -> Result<(), SinkError> {
        match stage {
            Stage::BodyMesh(body) => self.body_mesh(body),
            Stage::Landmarks(_, landmarks) => {
                let points: Vec<[f32; 3]> = landmarks
                    .items
                    .iter()
                    .map(|l| l.position().as_vec3().to_array())
                    .collect();
                let labels: Vec<String> = landmarks.items.iter().map(|l| l.label()).collect();
                let colors: Vec<[u8; 3]> = landmarks
                    .items
                    .iter()
                    .map(|l| if l.overridden { [255, 140, 0] } else { [200, 20, 60] })
                    .collect();
                self.rec
                    .log(
                        "body/landmarks",
                        &Points3D::new(points)
                            .with_labels(labels)
                            .with_colors(colors)
                            .with_radii([0.008])
                            .with_show_labels(true),
                    )
                    .map_err(to_sink)?;
                let listed: Vec<String> = LandmarkKind::ALL
                    .iter()
                    .map(|k| format!("{} {:.3}", k.name(), landmarks.height(*k)))
                    .collect();
                let tilt = landmarks.neck_plane().map_or_else(
                    || "undetermined".to_string(),
                    |p| format!("{:.1} deg", p.tilt().to_degrees()),
                );
                self.text(
                    TextLogLevel::INFO,
                    format!(
                        "landmarks (height, m): {}; neck-base plane tilt {tilt}",
                        listed.join(", ")
                    ),
                )
            }
            Stage::Rings(rings) => {
                for ring in rings {
                    self.rec
                        .log(
                            format!("body/rings/{}", ring.name),
                            &LineStrips3D::new([closed(&ring.points)])
                                .with_radii([0.0025])
                                .with_colors([[250, 250, 250]])
                                .with_labels([format!("{} {:.3} m", ring.name, ring.tape_girth)])
                                .with_show_labels(false),
                        )
                        .map_err(to_sink)?;
                }
                let listed: Vec<String> = rings
                    .iter()
                    .map(|r| format!("{} y={:.3} tape {:.3} m", r.name, r.y, r.tape_girth))
                    .collect();
                self.text(TextLogLevel::INFO, format!("rings: {}", listed.join("; ")))
            }
            Stage::Partitions(body, partitions) => {
                let mesh = &body.mesh;
                let partition_of_vertex: Vec<Option<PartitionId>> = mesh
                    .positions
                    .iter()
                    .map(|p| {
                        partitions
                            .iter()
                            .find(|q| p.y < q.upper_y || q.id == PartitionId::G)
                            .map(|q| q.id)
                    })
                    .collect();
                let colors: Vec<[u8; 3]> = partition_of_vertex
                    .iter()
                    .map(|id| id.map_or([200, 200, 200], partition_tint))
                    .collect();
                self.rec
                    .log("body/mesh", &Mesh3D::update_fields().with_vertex_colors(colors))
                    .map_err(to_sink)?;
                let mut lines = vec!["partitions (bounds m, triangles with margin, test, response):".to_string()];
                // A legend column beside the body, one labelled dot per partition at mid-height.
                // In the gap right of the body (its left hand is at +x), before the mannequins.
                let legend_x = mesh.bounds().map_or(0.8, |(_, hi)| hi.x + 0.35) as f32;
                let mut legend_points = Vec::new();
                let mut legend_labels = Vec::new();
                let mut legend_colors = Vec::new();
                for p in partitions.iter() {
                    let strips: Vec<Vec<[f32; 3]>> = p.rings.iter().map(|r| closed(&r.points)).collect();
                    self.rec
                        .log(
                            format!("body/partitions/{}", p.id.letter()),
                            &LineStrips3D::new(strips)
                                .with_radii([0.004])
                                .with_colors([partition_color(p.id)]),
                        )
                        .map_err(to_sink)?;
                    legend_points.push([legend_x, (0.5 * (p.lower_y + p.upper_y)) as f32, 0.0]);
                    legend_labels.push(format!(
                        "{} {}: {} test, {} response",
                        p.id.letter(),
                        p.id.region(),
                        method_name(p.method),
                        response_name(p.response)
                    ));
                    legend_colors.push(partition_color(p.id));
                    lines.push(format!(
                        "  {} {:<8} {:.3}..{:.3}  {:>5}  {}  {}",
                        p.id.letter(),
                        p.id.region(),
                        p.lower_y,
                        p.upper_y,
                        p.triangle_count,
                        method_name(p.method),
                        response_name(p.response)
                    ));
                }
                self.rec
                    .log(
                        "body/partitions/legend",
                        &Points3D::new(legend_points)
                            .with_labels(legend_labels)
                            .with_colors(legend_colors)
                            .with_radii([0.02])
                            .with_show_labels(true),
                    )
                    .map_err(to_sink)?;
                self.text(TextLogLevel::INFO, lines.join("\n"))
            }
            Stage::Mannequin(result) => self.mannequin(result),
            Stage::Section { name, y, loops } => {
                let strips: Vec<Vec<[f32; 3]>> = loops
                    .iter()
                    .map(|l| if l.closed { closed(&l.points) } else { f32s(&l.points) })
                    .collect();
                self.rec
                    .log(
                        format!("section/{name}"),
                        &LineStrips3D::new(strips)
                            .with_radii([0.003])
                            .with_colors([[255, 220, 0]]),
                    )
                    .map_err(to_sink)?;
                let lengths: Vec<String> = loops.iter().map(|l| format!("{:.3}", l.length())).collect();
                self.text(
                    TextLogLevel::INFO,
                    format!(
                        "section {name} at y = {y:.3} m: {} loop(s), lengths {} m",
                        loops.len(),
                        lengths.join(", ")
                    ),
                )
            }
            Stage::Garment(fw, part) => self.garment(fw, part),
            Stage::GarmentEdit { name, before, after } => self.garment_edit(name, before, after),
            Stage::Collision(outcome, index, part) => self.collision(outcome, index, part),
            Stage::Failed(error) => self.text(TextLogLevel::ERROR, error.to_string()),
            Stage::Network(fw, net) => self.network_built(fw, net),
            Stage::Solve {
                edit, net, solution, ..
            } => self.solve(edit, net, solution),
            Stage::Refused { edit, message } => self.refused(edit, message),
            Stage::Undone { framework, net } => self.undone(framework, net),
            Stage::StepDone(metrics) => {
                if self.options.timings {
                    for (name, ms) in &metrics.timings_ms {
                        self.scalar(&format!("metrics/timings/{name}"), *ms)?;
                    }
                }
                self.text(
                    TextLogLevel::DEBUG,
                    format!("step {} ({}) done", metrics.step, metrics.op),
                )
            }
        }
    }
}
