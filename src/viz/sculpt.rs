//! Logging sculpts: the session's sculpted garment (`garment/sculpt`, the region's faces
//! tinted, its edges drawn), the pick point and radius (`sculpt/pick`, `sculpt/radius`, a
//! circle in the tangent plane, `sculpt/direction`), the displacement field
//! (`sculpt/displacement`, an arrow per moved vertex coloured by its length), the active
//! faces of each adaptive level (`sculpt/levels/<k>`), and for `drape sculpt-compare` the
//! results side by side (`sculpt_compare/{none,uniform,adaptive,adaptive_matched}`, the
//! last refined adaptively to the longest edge uniform Loop reached).

use glam::DVec3;
use rerun::{Arrows3D, Clear, LineStrips3D, Mesh3D, Points3D, Radius, TextLogLevel};

use super::colors::error_color;
use super::draw::{colored_mesh, edge_paths, f32s};
use super::logger::{RerunLogger, to_sink};
use crate::mesh::TriMesh;
use crate::sculpt::{Comparison, Displacement, Level, Variant};
use crate::session::{SculptStage, SinkError};

/// The garment outside the sculpted region.
const GARMENT: [u8; 3] = [150, 165, 200];
/// The sculpted region.
const REGION: [u8; 3] = [235, 160, 90];
/// Active faces, level by level (cycled).
const LEVELS: [[u8; 3]; 4] = [[220, 60, 60], [230, 150, 30], [60, 170, 80], [60, 110, 220]];
/// Segments of the radius circle.
const CIRCLE: usize = 96;

/// A mesh with its region's faces' corners tinted.
fn region_mesh(mesh: &TriMesh, region: &[bool]) -> Mesh3D {
    let mut colors = vec![GARMENT; mesh.positions.len()];
    for (t, _) in mesh.triangles.iter().zip(region).filter(|(_, r)| **r) {
        for &v in t {
            colors[v as usize] = REGION;
        }
    }
    colored_mesh(mesh, colors)
}

/// The edges of the region's faces, moved by `shift`, as paths ([`edge_paths`]).
fn region_edges(mesh: &TriMesh, region: &[bool], shift: DVec3) -> Vec<Vec<[f32; 3]>> {
    let mut edges: Vec<[u32; 2]> = mesh
        .triangles
        .iter()
        .zip(region)
        .filter(|(_, r)| **r)
        .flat_map(|(t, _)| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])]))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edge_paths(&shifted(mesh, shift).positions_f32(), &edges)
}

fn shifted(mesh: &TriMesh, shift: DVec3) -> TriMesh {
    TriMesh {
        positions: mesh.positions.iter().map(|p| *p + shift).collect(),
        triangles: mesh.triangles.clone(),
    }
}

impl RerunLogger {
    /// The pick, the radius circle, the direction and the displacement field of a drag on
    /// `base`, under `path`.
    fn log_drag(&self, path: &str, d: &Displacement, radius: f64, peak: f64) -> Result<(), SinkError> {
        let rec = self.recording();
        let pick = d.pick.point;
        rec.log(
            format!("{path}/pick"),
            &Points3D::new(f32s(&[pick]))
                .with_radii([Radius::new_ui_points(8.0)])
                .with_colors([[255, 40, 200]]),
        )
        .map_err(to_sink)?;
        let n = d.pick.normal;
        let u = n.any_orthonormal_vector();
        let v = n.cross(u);
        let circle: Vec<DVec3> = (0..=CIRCLE)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / CIRCLE as f64;
                pick + radius * (a.cos() * u + a.sin() * v)
            })
            .collect();
        rec.log(
            format!("{path}/radius"),
            &LineStrips3D::new([f32s(&circle)])
                .with_radii([Radius::new_ui_points(1.5)])
                .with_colors([[255, 40, 200]]),
        )
        .map_err(to_sink)?;
        rec.log(
            format!("{path}/direction"),
            &Arrows3D::from_vectors([(d.direction * peak).as_vec3().to_array()])
                .with_origins([pick.as_vec3().to_array()])
                .with_colors([[255, 40, 200]]),
        )
        .map_err(to_sink)?;
        let largest = d.offsets.iter().map(|(_, o)| o.length()).fold(0.0, f64::max);
        let origins: Vec<DVec3> = d.offsets.iter().map(|&(v, o)| d.positions[v as usize] - o).collect();
        let vectors: Vec<DVec3> = d.offsets.iter().map(|&(_, o)| o).collect();
        let colors: Vec<[u8; 3]> = vectors.iter().map(|o| error_color(o.length(), largest)).collect();
        rec.log(
            format!("{path}/displacement"),
            &Arrows3D::from_vectors(f32s(&vectors))
                .with_origins(f32s(&origins))
                .with_colors(colors)
                .with_radii([Radius::new_ui_points(1.0)]),
        )
        .map_err(to_sink)
    }

    /// The active faces of each level, under `path/<k>` (their outlines, thinner each level).
    fn log_levels(&self, path: &str, levels: &[Level], shift: DVec3) -> Result<(), SinkError> {
        let rec = self.recording();
        rec.log(path, &Clear::recursive()).map_err(to_sink)?;
        for (k, level) in levels.iter().enumerate() {
            let outlines: Vec<Vec<[f32; 3]>> = level
                .active
                .iter()
                .map(|[a, b, c]| f32s(&[*a + shift, *b + shift, *c + shift, *a + shift]))
                .collect();
            rec.log(
                format!("{path}/{k}"),
                &LineStrips3D::new(outlines)
                    .with_radii([Radius::new_ui_points(1.5 - 0.3 * k.min(3) as f32)])
                    .with_colors([LEVELS[k % LEVELS.len()]]),
            )
            .map_err(to_sink)?;
        }
        Ok(())
    }

    /// A session's sculpt: the sculpted garment, the drag and the levels.
    pub(super) fn log_sculpt(&self, stage: SculptStage<'_>) -> Result<(), SinkError> {
        let rec = self.recording();
        let Some(outcome) = stage.outcome else {
            rec.log("garment/sculpt", &Clear::recursive()).map_err(to_sink)?;
            rec.log("sculpt", &Clear::recursive()).map_err(to_sink)?;
            return self.text(TextLogLevel::INFO, "sculpt: none (taken back)".into());
        };
        let s = &outcome.sculpt;
        let q = &outcome.collision.quality;
        let line = outcome.summary();
        if let Some(why) = stage.refused {
            return self.text(TextLogLevel::WARN, format!("REFUSED {line}: {why}"));
        }
        let mesh = outcome.mesh();
        rec.log("garment/sculpt", &region_mesh(&mesh, &s.refined.region))
            .map_err(to_sink)?;
        rec.log(
            "garment/sculpt/edges",
            &LineStrips3D::new(region_edges(&mesh, &s.refined.region, DVec3::ZERO))
                .with_radii([Radius::new_ui_points(0.6)])
                .with_colors([[60, 40, 30]]),
        )
        .map_err(to_sink)?;
        self.log_drag("sculpt", &s.displacement, outcome.drag.radius, outcome.drag.peak)?;
        self.log_levels("sculpt/levels", &s.refined.levels, DVec3::ZERO)?;
        self.text(
            if q.is_clear() {
                TextLogLevel::INFO
            } else {
                TextLogLevel::WARN
            },
            line,
        )
    }

    /// `drape sculpt-compare`: the input with the drag, then no, uniform and adaptive
    /// subdivision side by side (each shifted along x by `spacing`), with the adaptive
    /// levels over the adaptive result.
    pub(super) fn log_sculpt_compare(&self, cmp: &Comparison) -> Result<(), SinkError> {
        let spacing = cmp.spacing();
        self.log_sculpt_compare_at(cmp, spacing)
    }

    fn log_sculpt_compare_at(&self, cmp: &Comparison, spacing: f64) -> Result<(), SinkError> {
        let rec = self.recording();
        let variants: [(&str, &Variant); 4] = [
            ("none", &cmp.none),
            ("uniform", &cmp.uniform),
            ("adaptive", &cmp.adaptive),
            ("adaptive_matched", &cmp.adaptive_matched),
        ];
        let low = cmp.none.mesh.bounds().map_or(0.0, |(lo, _)| lo.y);
        for (k, (name, v)) in variants.iter().enumerate() {
            let shift = DVec3::X * spacing * k as f64;
            let path = format!("sculpt_compare/{name}");
            rec.log(path.as_str(), &region_mesh(&shifted(&v.mesh, shift), &v.region))
                .map_err(to_sink)?;
            rec.log(
                format!("{path}/edges"),
                &LineStrips3D::new(region_edges(&v.mesh, &v.region, shift))
                    .with_radii([Radius::new_ui_points(0.6)])
                    .with_colors([[60, 40, 30]]),
            )
            .map_err(to_sink)?;
            let m = &v.measures;
            rec.log(
                format!("{path}/label"),
                &Points3D::new(f32s(&[DVec3::new(
                    cmp.displacement.pick.point.x + shift.x,
                    low - 0.06,
                    cmp.displacement.pick.point.z,
                )]))
                .with_radii([Radius::new_ui_points(0.1)])
                .with_labels([format!(
                    "{name}: {} faces\nmax edge {:.1} mm\nmin angle {:.1} deg\nsmoothness {:.2} deg",
                    m.faces,
                    m.max_edge_m * 1e3,
                    m.min_angle_deg,
                    m.smoothness
                )])
                .with_show_labels(true),
            )
            .map_err(to_sink)?;
        }
        self.log_drag(
            "sculpt_compare/none/drag",
            &cmp.displacement,
            cmp.drag.radius,
            cmp.drag.peak,
        )?;
        self.log_levels(
            "sculpt_compare/adaptive/levels",
            &cmp.adaptive_levels,
            DVec3::X * spacing * 2.0,
        )?;
        self.text(
            TextLogLevel::INFO,
            format!(
                "sculpt-compare: epsilon {:.4} m; none {} faces, uniform {} ({} levels), adaptive {} ({} levels)",
                cmp.epsilon,
                cmp.none.measures.faces,
                cmp.uniform.measures.faces,
                cmp.uniform.levels,
                cmp.adaptive.measures.faces,
                cmp.adaptive.levels
            ),
        )
    }
}
