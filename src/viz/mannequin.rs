//! Logging the \[spline\] mannequin study: both refined surfaces beside the body, coloured by
//! their distance to the true surface on one scale, the measured points, and the per-region
//! figures in the log (the step's figures are plotted from its metrics).

use glam::DVec3;
use rerun::{Mesh3D, Points3D, TextLogLevel, Transform3D};

use super::colors::error_color;
use super::draw::f32s;
use super::logger::{RerunLogger, to_sink};
use crate::mannequin::{MannequinResult, RingGrid};
use crate::session::SinkError;

impl RerunLogger {
    pub(super) fn log_mannequin(&self, result: &MannequinResult) -> Result<(), SinkError> {
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
                        .with_show_labels(false), // on hover; the figures are in the log
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
        }
        self.text(TextLogLevel::INFO, lines.join("\n"))
    }
}

fn grid_top(grid: &RingGrid) -> DVec3 {
    let last = grid.layers.saturating_sub(1);
    let n = grid.points.max(1) as f64;
    (0..grid.points).map(|j| grid.at(last, j)).sum::<DVec3>() / n
}
