//! Logging the [nurbs] experiment: the leaf and the butterfly in both poses (the crossing
//! pose beside the near one), their control nets, and per subdivision level (the `level`
//! timeline) the leaf hulls that the level opens, the nearest control points and the true
//! nearest points, with the figures as scalars.

use glam::DVec3;
use rerun::{LineStrips3D, Mesh3D, Points3D, Radius, TextLogLevel, Transform3D};

use super::draw::f32s;
use super::logger::{RerunLogger, to_sink};
use crate::nurbs::{Experiment, Kdop, NurbsSurface};
use crate::session::{NurbsStage, SinkError};

/// How far the crossing pose is drawn beside the near one, in leaf widths.
const CROSSING_OFFSET: f64 = 3.0;

/// Grid samples per control-point interval when drawing a surface.
const SAMPLES_PER_SPAN: usize = 6;

fn net_lines(s: &NurbsSurface) -> Vec<Vec<[f32; 3]>> {
    let [nu, nv] = s.count();
    let points: Vec<DVec3> = s.control_points().collect();
    let rows = (0..nu).map(|i| f32s(&points[i * nv..(i + 1) * nv]));
    let columns = (0..nv).map(|j| f32s(&(0..nu).map(|i| points[i * nv + j]).collect::<Vec<_>>()));
    rows.chain(columns).collect()
}

fn hull_lines(hulls: &[Kdop]) -> Vec<[[f32; 3]; 2]> {
    hulls
        .iter()
        .flat_map(|h| h.edges())
        .map(|[a, b]| [a.as_vec3().to_array(), b.as_vec3().to_array()])
        .collect()
}

impl RerunLogger {
    /// The parts of a scene after a `nurbs` or `move` step: each surface and net (on the
    /// step's timelines), the moved part's contacts as segments (red: colliding), and a line
    /// in the log.
    pub(super) fn log_nurbs_parts(&self, stage: NurbsStage<'_>) -> Result<(), SinkError> {
        for part in stage.parts {
            self.nurbs_surface(
                &format!("nurbs/parts/{}", part.name),
                &part.surface,
                [240, 150, 40],
                false,
            )?;
        }
        let segments: Vec<[[f32; 3]; 2]> = stage
            .contacts
            .iter()
            .filter(|c| c.distance_m.is_finite())
            .map(|c| [c.points[0].as_vec3().to_array(), c.points[1].as_vec3().to_array()])
            .collect();
        let colors: Vec<[u8; 3]> = stage
            .contacts
            .iter()
            .filter(|c| c.distance_m.is_finite())
            .map(|c| if c.colliding { [230, 30, 30] } else { [40, 160, 60] })
            .collect();
        self.rec
            .log(
                "nurbs/contacts",
                &LineStrips3D::new(segments)
                    .with_colors(colors)
                    .with_radii([Radius::new_ui_points(2.0)]),
            )
            .map_err(to_sink)?;
        let each: Vec<String> = stage
            .contacts
            .iter()
            .map(|c| {
                let inside = if c.inside > 0 {
                    format!(", {} point(s) inside", c.inside)
                } else {
                    String::new()
                };
                format!("{} {:.3} mm{inside}", c.other, c.distance_m * 1e3)
            })
            .collect();
        let colliding = stage.contacts.iter().any(|c| c.colliding);
        let (level, text) = match stage.refused {
            Some(why) => (TextLogLevel::WARN, why.to_string()),
            None if colliding => (
                TextLogLevel::WARN,
                format!("NURBS part '{}' collides: {}", stage.moved, each.join(", ")),
            ),
            None if each.is_empty() => (
                TextLogLevel::INFO,
                format!("NURBS part '{}': clear of the body and the other parts", stage.moved),
            ),
            None => (
                TextLogLevel::INFO,
                format!(
                    "NURBS part '{}': within the threshold of {}",
                    stage.moved,
                    each.join(", ")
                ),
            ),
        };
        self.text(level, text)
    }

    /// A surface (sampled) and its control net under `path`: static when it stands for the
    /// whole recording (the experiment, so that it shows on the `level` timeline too), else
    /// on the current step.
    fn nurbs_surface(&self, path: &str, s: &NurbsSurface, color: [u8; 3], fixed: bool) -> Result<(), SinkError> {
        let [nu, nv] = s.count();
        let (positions, triangles) = s.grid(SAMPLES_PER_SPAN * nu, SAMPLES_PER_SPAN * nv);
        let mesh = Mesh3D::new(f32s(&positions))
            .with_triangle_indices(triangles)
            .with_albedo_factor(rerun::Rgba32::from_unmultiplied_rgba(color[0], color[1], color[2], 255));
        let net = LineStrips3D::new(net_lines(s))
            .with_radii([Radius::new_ui_points(0.5)])
            .with_colors([[60, 60, 60]]);
        let (surface_path, net_path) = (format!("{path}/surface"), format!("{path}/net"));
        if fixed {
            self.rec.log_static(surface_path, &mesh).map_err(to_sink)?;
            self.rec.log_static(net_path, &net).map_err(to_sink)
        } else {
            self.rec.log(surface_path, &mesh).map_err(to_sink)?;
            self.rec.log(net_path, &net).map_err(to_sink)
        }
    }

    pub(super) fn log_nurbs_experiment(&self, e: &Experiment) -> Result<(), SinkError> {
        let width = {
            let h = Kdop::from_points(e.leaf.control_points());
            h.max[0] - h.min[0]
        };
        let shift = (CROSSING_OFFSET * width) as f32;
        self.rec
            .log_static("nurbs/crossing", &Transform3D::from_translation([shift, 0.0, 0.0]))
            .map_err(to_sink)?;
        for scene in ["near", "crossing"] {
            self.nurbs_surface(&format!("nurbs/{scene}/leaf"), &e.leaf, [90, 170, 70], true)?;
        }
        self.nurbs_surface("nurbs/near/butterfly", &e.near, [240, 150, 40], true)?;
        self.nurbs_surface("nurbs/crossing/butterfly", &e.crossing_butterfly, [240, 150, 40], true)?;
        self.text(
            TextLogLevel::INFO,
            format!(
                "nurbs experiment: butterfly {} control points, leaf {}; near pose lifted {:.4} mm (true distance {:.4} mm), crossing pose {:.4} mm",
                e.near.net().len(),
                e.leaf.net().len(),
                e.near_pose.gap * 1e3,
                e.levels.first().map_or(f64::NAN, |r| r.true_distance_m * 1e3),
                e.crossing_pose.gap * 1e3
            ),
        )?;
        for (row, picture) in e.levels.iter().zip(&e.pictures) {
            self.rec.set_time_sequence("level", i64::from(row.level));
            for (scene, hulls) in [("near", &picture.near_hulls), ("crossing", &picture.crossing_hulls)] {
                for (side, color) in [("butterfly", [200, 90, 20]), ("leaf", [30, 110, 40])] {
                    let k = usize::from(side == "leaf");
                    self.rec
                        .log(
                            format!("nurbs/{scene}/hulls/{side}"),
                            &LineStrips3D::new(hull_lines(&hulls[k]))
                                .with_radii([Radius::new_ui_points(0.75)])
                                .with_colors([color]),
                        )
                        .map_err(to_sink)?;
                }
            }
            for (name, points, color) in [
                ("control", picture.cp_points, [220, 30, 30]),
                ("true", picture.true_points, [30, 60, 220]),
            ] {
                let pts = f32s(&points);
                self.rec
                    .log(
                        format!("nurbs/near/closest/{name}"),
                        &Points3D::new(pts.clone())
                            .with_radii([Radius::new_ui_points(5.0)])
                            .with_colors([color]),
                    )
                    .map_err(to_sink)?;
                self.rec
                    .log(
                        format!("nurbs/near/closest/{name}/segment"),
                        &LineStrips3D::new([pts])
                            .with_radii([Radius::new_ui_points(2.0)])
                            .with_colors([color]),
                    )
                    .map_err(to_sink)?;
            }
            self.scalar("metrics/nurbs/cp_min_distance_m", row.cp_min_distance_m)?;
            self.scalar("metrics/nurbs/true_distance_m", row.true_distance_m)?;
            self.scalar("metrics/nurbs/error_m", row.error_m)?;
            self.scalar("metrics/nurbs/pairs_tested", row.pairs_tested as f64)?;
            let crossing = e.crossing.iter().find(|c| c.level == row.level);
            self.text(
                TextLogLevel::INFO,
                format!(
                    "L = {}: {} hull pairs tested, {} leaf pairs compared; control-point distance {:.4} mm, true {:.4} mm, error {:+.4} mm; crossing pose {}",
                    row.level,
                    row.pairs_tested,
                    row.leaf_pairs,
                    row.cp_min_distance_m * 1e3,
                    row.true_distance_m * 1e3,
                    row.error_m * 1e3,
                    crossing.map_or("not run", |c| if c.detected { "detected" } else { "MISSED" })
                ),
            )?;
        }
        self.rec.disable_timeline("level");
        let r = &e.recommended;
        self.text(
            TextLogLevel::INFO,
            format!(
                "recommended: L = {}, T = {:.4} mm for an accuracy of {:.3} mm",
                r.level,
                r.threshold_m * 1e3,
                r.accuracy_m * 1e3
            ),
        )
    }
}
