//! Logging the constraint layer: the network (a line from each curve's centre through the
//! constrained point to the other curve's centre, green when met, red when violated; self
//! constraints as a dot at the curve's centre), every solver iteration on the `iter`
//! timeline (the curve solved, its node-layer pushes, its residuals), the dragged point's
//! path, and a text summary per step.

use glam::DVec3;
use rerun::{Arrows3D, Clear, LineStrips3D, Points3D, TextLogLevel};

use super::draw::{closed, f32s};
use super::logger::{RerunLogger, to_sink};
use crate::constraint::{ConstraintNet, CurveKind, Edit, Iteration, Solution};
use crate::garment::Framework;
use crate::session::SinkError;

const MET: [u8; 3] = [60, 200, 90];
const VIOLATED: [u8; 3] = [235, 40, 40];
const SOLVED: [u8; 3] = [255, 200, 0];

fn centre(fw: &Framework, net: &ConstraintNet, c: usize) -> DVec3 {
    let node = &net.curves[c];
    let p = crate::constraint::curves::points(fw, node);
    if node.kind == CurveKind::Contour {
        return p[p.len() / 2];
    }
    p.iter().sum::<DVec3>() / p.len().max(1) as f64
}

impl RerunLogger {
    /// The network on `fw`, coloured by each constraint's residual.
    pub(super) fn network(&self, fw: &Framework, net: &ConstraintNet, tolerance: f64) -> Result<(), SinkError> {
        let rec = self.recording();
        let residuals = net.residuals(fw);
        let mut strips = Vec::new();
        let mut colors = Vec::new();
        let mut labels = Vec::new();
        let mut own_points = Vec::new();
        let mut own_colors = Vec::new();
        let mut own_labels = Vec::new();
        for (c, node) in net.curves.iter().enumerate() {
            let own: Vec<usize> = net
                .touching(c)
                .into_iter()
                .filter(|&k| net.constraints[k].is_self())
                .collect();
            if own.is_empty() {
                continue;
            }
            let bad: Vec<String> = own
                .iter()
                .filter(|&&k| net.violated(k, residuals[k], tolerance))
                .map(|&k| format!("{} {:.2e}", net.constraints[k].kind.name(), residuals[k]))
                .collect();
            own_points.push(centre(fw, net, c));
            own_colors.push(if bad.is_empty() { MET } else { VIOLATED });
            own_labels.push(if bad.is_empty() {
                node.name.clone()
            } else {
                format!("{}: {}", node.name, bad.join(", "))
            });
        }
        for (k, con) in net.constraints.iter().enumerate() {
            if con.is_self() {
                continue;
            }
            let (a, b) = con.anchor_points(fw, &net.curves);
            strips.push(f32s(&[centre(fw, net, con.i), a, b, centre(fw, net, con.j)]));
            colors.push(if net.violated(k, residuals[k], tolerance) {
                VIOLATED
            } else {
                MET
            });
            labels.push(format!(
                "{} {} - {}: {:.2e} {}",
                con.kind.name(),
                net.curves[con.i].name,
                net.curves[con.j].name,
                residuals[k],
                con.kind.unit()
            ));
        }
        rec.log(
            "constraints/network/links",
            &LineStrips3D::new(strips)
                .with_radii([0.0015])
                .with_colors(colors)
                .with_labels(labels)
                .with_show_labels(false),
        )
        .map_err(to_sink)?;
        rec.log(
            "constraints/network/curves",
            &Points3D::new(f32s(&own_points))
                .with_radii([0.008])
                .with_colors(own_colors)
                .with_labels(own_labels)
                .with_show_labels(false),
        )
        .map_err(to_sink)?;
        let violated = (0..residuals.len())
            .filter(|&k| net.violated(k, residuals[k], tolerance))
            .count();
        self.scalar("metrics/constraints/violated", violated as f64)?;
        self.scalar(
            "metrics/constraints/max_residual",
            residuals.iter().copied().fold(0.0, f64::max),
        )
    }

    /// The network as built.
    pub(super) fn log_network_built(&self, fw: &Framework, net: &ConstraintNet) -> Result<(), SinkError> {
        self.network(fw, net, crate::constraint::SolverOptions::default().tolerance)?;
        let mut by_kind = std::collections::BTreeMap::<&str, usize>::new();
        for c in &net.constraints {
            *by_kind.entry(c.kind.name()).or_default() += 1;
        }
        let kinds: Vec<String> = by_kind.iter().map(|(k, n)| format!("{k} {n}")).collect();
        self.text(
            TextLogLevel::INFO,
            format!(
                "constraint network: {} curves, {} constraints in {} matrix entries ({})",
                net.curves.len(),
                net.constraints.len(),
                net.matrix.len(),
                kinds.join(", ")
            ),
        )
    }

    /// A refused edit: the garment is as before; the last drag's path (an earlier step's) is
    /// cleared.
    pub(super) fn log_refused(&self, edit: &Edit, message: &str) -> Result<(), SinkError> {
        self.recording()
            .log("constraints/drag", &Clear::recursive())
            .map_err(to_sink)?;
        self.text(
            TextLogLevel::WARN,
            format!("{edit} refused: {message}; the garment is as before"),
        )
    }

    /// `undo`: the network redrawn on the restored curves, the last drag's path cleared.
    pub(super) fn log_undone(&self, fw: &Framework, net: Option<&ConstraintNet>) -> Result<(), SinkError> {
        self.recording()
            .log("constraints/drag", &Clear::recursive())
            .map_err(to_sink)?;
        if let Some(net) = net {
            self.network(fw, net, crate::constraint::SolverOptions::default().tolerance)?;
        }
        self.text(
            TextLogLevel::INFO,
            format!(
                "undo: the garment is back to its state before the last step ({} M0 vertices)",
                fw.m0.mesh.positions.len()
            ),
        )
    }

    /// Every solver iteration on the `iter` timeline, then the network after the solve, the
    /// dragged point's path and the summary (on the step and stage timelines).
    pub(super) fn log_solve(&mut self, edit: &Edit, net: &ConstraintNet, s: &Solution) -> Result<(), SinkError> {
        let tolerance = s.tolerance;
        // The iterations differ only on the `iter` timeline: each entity's rows go out as
        // one chunk (each chunk costs about 80 us to encode and write, whatever its size),
        // sent before anything the solve logs after them.
        self.recording().hold();
        let iterations = s
            .iterations
            .iter()
            .try_for_each(|it| self.log_iteration(net, it, tolerance));
        let released = self.recording().release();
        iterations.and(released)?;
        let rec = self.recording();
        rec.disable_timeline("iter");
        rec.log("constraints/solve", &Clear::recursive()).map_err(to_sink)?;
        self.network(&s.framework, net, tolerance)?;
        self.log_drag_path(s)?;
        let worst = s.max_residual();
        let violations = s.violation_lines(net);
        let (level, verdict) = if violations.is_empty() {
            (
                TextLogLevel::INFO,
                format!(
                    "all {} constraints met (largest residual {worst:.2e})",
                    s.residuals.len()
                ),
            )
        } else {
            (
                TextLogLevel::WARN,
                format!(
                    "{} constraint(s) still violated after {} pass(es): {}",
                    violations.len(),
                    s.passes,
                    violations.join("; ")
                ),
            )
        };
        let moved = s.path.first().zip(s.path.last()).map_or(String::new(), |(a, b)| {
            format!("; the point moved {:.1} mm", a.distance(*b) * 1e3)
        });
        self.text(
            level,
            format!(
                "{}: {} curve(s) solved in {} iteration(s), {} pass(es){}{moved}; {verdict}",
                edit,
                s.solved.len(),
                s.iterations.len(),
                s.passes,
                if s.converged { "" } else { ", not converged" },
            ),
        )
    }

    /// One iteration of the solver on the `iter` timeline: the curve it solved, its
    /// control points, the node layer's pushes, its figures and a note.
    fn log_iteration(&mut self, net: &ConstraintNet, it: &Iteration, tolerance: f64) -> Result<(), SinkError> {
        let iter = self.next_iter();
        let rec = self.recording();
        rec.set_time_sequence("iter", iter);
        let node = &net.curves[it.curve];
        let line = if node.kind == CurveKind::Ring {
            closed(&it.control)
        } else {
            f32s(&it.control)
        };
        rec.log(
            "constraints/solve/curve",
            &LineStrips3D::new([line])
                .with_radii([0.003])
                .with_colors([if it.broken.is_empty() { SOLVED } else { VIOLATED }])
                .with_labels([format!("pass {}: {}", it.pass, node.name)]),
        )
        .map_err(to_sink)?;
        rec.log(
            "constraints/solve/control",
            &Points3D::new(f32s(&it.control))
                .with_radii([0.005])
                .with_colors([SOLVED]),
        )
        .map_err(to_sink)?;
        if it.node.is_empty() {
            rec.log("constraints/solve/node_hits", &Clear::flat())
                .map_err(to_sink)?;
        } else {
            let origins: Vec<DVec3> = it.node.iter().map(|h| h.before).collect();
            let vectors: Vec<DVec3> = it.node.iter().map(|h| h.after - h.before).collect();
            rec.log(
                "constraints/solve/node_hits",
                &Arrows3D::from_vectors(f32s(&vectors))
                    .with_origins(f32s(&origins))
                    .with_colors([VIOLATED])
                    .with_radii([0.0015]),
            )
            .map_err(to_sink)?;
        }
        let worst = it.residuals.iter().map(|r| r.1).fold(0.0, f64::max);
        self.scalar("metrics/solver/max_residual_touched", worst)?;
        self.scalar("metrics/solver/curve_deficit_m", it.curve_layer.deficit_after)?;
        self.text(TextLogLevel::DEBUG, iteration_note(net, it, iter, tolerance))
    }

    /// The drag's path (start, asked, final), or nothing where there was no drag.
    fn log_drag_path(&self, s: &Solution) -> Result<(), SinkError> {
        let rec = self.recording();
        if s.path.len() >= 2 {
            rec.log(
                "constraints/drag/path",
                &LineStrips3D::new([f32s(&s.path)])
                    .with_radii([0.002])
                    .with_colors([[80, 160, 255]]),
            )
            .map_err(to_sink)?;
            let n = s.path.len();
            let labels: Vec<String> = (0..n)
                .map(|k| match k {
                    0 => "start".to_string(),
                    1 => "asked".to_string(),
                    k if k == n - 1 => "final".to_string(),
                    _ => String::new(),
                })
                .collect();
            rec.log(
                "constraints/drag/points",
                &Points3D::new(f32s(&s.path))
                    .with_radii([0.006])
                    .with_colors([[80, 160, 255]])
                    .with_labels(labels)
                    .with_show_labels(true),
            )
            .map_err(to_sink)?;
        } else {
            rec.log("constraints/drag", &Clear::recursive()).map_err(to_sink)?;
        }
        Ok(())
    }
}

/// The note of one solver iteration: the curve, what drove it, the node and curve layers,
/// the residuals it touched and any closed chain it broke.
fn iteration_note(net: &ConstraintNet, it: &Iteration, iter: i64, tolerance: f64) -> String {
    let node = &net.curves[it.curve];
    let touched: Vec<String> = it
        .residuals
        .iter()
        .map(|&(k, r)| {
            let c = &net.constraints[k];
            let other = if c.is_self() {
                String::new()
            } else {
                format!("-{}", net.curves[c.other(it.curve)].name)
            };
            format!(
                "{}{other} {:.1e}{}",
                c.kind.name(),
                r,
                if net.violated(k, r, tolerance) { "!" } else { "" }
            )
        })
        .collect();
    let driven: Vec<String> = it
        .driven_by
        .iter()
        .map(|&k| {
            let c = &net.constraints[k];
            format!("{} from {}", c.kind.name(), net.curves[c.other(it.curve)].name)
        })
        .collect();
    let cl = &it.curve_layer;
    format!(
        "iter {iter} pass {}: solved {}{}; node layer {} point(s) pushed out; curve layer {} of {} samples short (worst {:.2} -> {:.2} mm, {} round(s), moved {:?}{}); residuals: {}{}",
        it.pass,
        node.name,
        if driven.is_empty() {
            " (active)".to_string()
        } else {
            format!(" driven by {}", driven.join(", "))
        },
        it.node.len(),
        cl.short_before,
        cl.samples,
        cl.deficit_before * 1e3,
        cl.deficit_after * 1e3,
        cl.rounds,
        cl.moved,
        if cl.pinned.is_empty() {
            String::new()
        } else {
            format!(", pinned {:?}", cl.pinned)
        },
        touched.join(", "),
        if it.broken.is_empty() {
            String::new()
        } else {
            format!(
                "; BROKE {} (closed chain)",
                it.broken
                    .iter()
                    .map(|&k| net.constraints[k].kind.name())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    )
}
