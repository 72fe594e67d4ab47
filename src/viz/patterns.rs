//! Logging the pattern pieces: in 2D (`patterns/pieces`, millimetres, `y` up as on the
//! table) every piece's edges coloured by their strain, its cut line, its seams (both sides
//! of a seam in one colour), notches, grain line and name; in 3D the garment's panels, one
//! colour each (`patterns/garment/panels`), and coloured by strain
//! (`patterns/garment/strain`). Strain colours run from blue (0) to red (5% or more).

use glam::DVec2;
use rerun::{Clear, LineStrips2D, Points2D, TextLogLevel};

use super::colors::error_color;
use super::draw::colored_mesh;
use super::garment::patch_color;
use super::logger::{RerunLogger, to_sink};
use crate::pattern::Pattern;
use crate::session::{PatternStage, SinkError};

/// The strain shown red, a fraction.
const RED_STRAIN: f64 = 0.05;

/// 2D points in mm with `y` up (the 2D view's `y` points down).
fn mm(p: DVec2) -> [f32; 2] {
    [(1e3 * p.x) as f32, (-1e3 * p.y) as f32]
}

impl RerunLogger {
    pub(super) fn log_patterns(&self, stage: PatternStage<'_>) -> Result<(), SinkError> {
        let rec = self.recording();
        let pattern = match stage.result {
            Ok(p) => p,
            Err(e) => {
                rec.log("patterns", &Clear::recursive()).map_err(to_sink)?;
                return self.text(TextLogLevel::WARN, format!("no pattern for the {}: {e}", stage.garment));
            }
        };
        self.log_pieces(pattern)?;
        self.log_panels_3d(pattern)?;
        let strain = pattern
            .pieces
            .iter()
            .map(|p| p.distortion.max_strain)
            .fold(0.0, f64::max);
        let mean =
            pattern.pieces.iter().map(|p| p.distortion.mean_strain).sum::<f64>() / pattern.pieces.len().max(1) as f64;
        let worst = pattern.seams.iter().map(|s| s.mismatch).fold(0.0, f64::max);
        self.text(
            TextLogLevel::INFO,
            format!(
                "pattern of the {} from {}: {} pieces ({} flattened again, the rest kept), edge strain max {:.2}% mean {:.2}%, {} flipped triangles; {} seams along {}, worst mismatch {:.3} mm, {} over tolerance",
                stage.garment,
                pattern.source.name(),
                pattern.pieces.len(),
                pattern.flattened(),
                100.0 * strain,
                100.0 * mean,
                pattern.pieces.iter().map(|p| p.distortion.flipped).sum::<usize>(),
                pattern.seams.len(),
                pattern.seam_curves.join(", "),
                1e3 * worst,
                pattern.seams.iter().filter(|s| !s.sews()).count()
            ),
        )
    }

    /// The pieces in 2D.
    fn log_pieces(&self, pattern: &Pattern) -> Result<(), SinkError> {
        let rec = self.recording();
        let (mut edges, mut edge_colors) = (Vec::new(), Vec::new());
        let (mut cuts, mut grains, mut notches) = (Vec::new(), Vec::new(), Vec::new());
        let (mut centres, mut names) = (Vec::new(), Vec::new());
        for piece in &pattern.pieces {
            for ([a, b], s) in
                crate::pattern::distortion::edge_strains(&piece.panel.positions, &piece.panel.triangles, &piece.uv)
            {
                edges.push(vec![mm(piece.uv[a as usize]), mm(piece.uv[b as usize])]);
                edge_colors.push(error_color(s, RED_STRAIN));
            }
            let mut cut: Vec<[f32; 2]> = piece.panel.boundary.iter().map(|&v| mm(piece.uv[v as usize])).collect();
            if let Some(&first) = cut.first() {
                cut.push(first);
            }
            cuts.push(cut);
            grains.push(piece.grain.map(mm).to_vec());
            for &(p, inward) in &piece.notches {
                notches.push(vec![mm(p), mm(p + 0.008 * inward)]);
            }
            centres.push(mm(0.5 * (piece.grain[0] + piece.grain[1])));
            names.push(piece.panel.name.clone());
        }
        let (mut seams, mut seam_colors) = (Vec::new(), Vec::new());
        for (k, s) in pattern.seams.iter().enumerate() {
            for side in 0..2 {
                let piece = &pattern.pieces[s.panels[side]];
                seams.push(
                    s.sides[side]
                        .iter()
                        .map(|&v| mm(piece.uv[v as usize]))
                        .collect::<Vec<_>>(),
                );
                seam_colors.push(patch_color(k));
            }
        }
        rec.log(
            "patterns/pieces/edges",
            &LineStrips2D::new(edges).with_colors(edge_colors).with_radii([0.6]),
        )
        .map_err(to_sink)?;
        rec.log(
            "patterns/pieces/cut",
            &LineStrips2D::new(cuts).with_colors([[30, 30, 30]]).with_radii([1.2]),
        )
        .map_err(to_sink)?;
        rec.log(
            "patterns/pieces/seams",
            &LineStrips2D::new(seams).with_colors(seam_colors).with_radii([2.5]),
        )
        .map_err(to_sink)?;
        rec.log(
            "patterns/pieces/notches",
            &LineStrips2D::new(notches)
                .with_colors([[200, 20, 40]])
                .with_radii([1.5]),
        )
        .map_err(to_sink)?;
        rec.log(
            "patterns/pieces/grain",
            &LineStrips2D::new(grains).with_colors([[26, 95, 180]]).with_radii([1.0]),
        )
        .map_err(to_sink)?;
        rec.log(
            "patterns/pieces/names",
            &Points2D::new(centres)
                .with_labels(names)
                .with_radii([2.0])
                .with_colors([[40, 40, 40]]),
        )
        .map_err(to_sink)
    }

    /// The garment by panel and by strain, in 3D.
    fn log_panels_3d(&self, pattern: &Pattern) -> Result<(), SinkError> {
        let rec = self.recording();
        let mut mesh = crate::mesh::TriMesh::default();
        let (mut by_panel, mut by_strain) = (Vec::new(), Vec::new());
        for (k, piece) in pattern.pieces.iter().enumerate() {
            let base = mesh.positions.len() as u32;
            mesh.positions.extend_from_slice(&piece.panel.positions);
            mesh.triangles
                .extend(piece.panel.triangles.iter().map(|t| t.map(|v| v + base)));
            by_panel.extend(std::iter::repeat_n(patch_color(k), piece.panel.positions.len()));
            by_strain.extend(piece.vertex_strain.iter().map(|&s| error_color(s, RED_STRAIN)));
        }
        rec.log("patterns/garment/panels", &colored_mesh(&mesh, by_panel))
            .map_err(to_sink)?;
        rec.log("patterns/garment/strain", &colored_mesh(&mesh, by_strain))
            .map_err(to_sink)
    }
}
