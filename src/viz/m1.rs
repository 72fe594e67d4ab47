//! Logging M1: the display mesh beside M0 (`garment/m1/mesh/<part>`, vertices coloured by
//! the rule that selected their patch, grey where M0 is kept; only the parts that changed),
//! its edges and new vertices likewise, its edges crossing the
//! body before and after its own collision, the cut lines on M1 and their stored form on
//! M0, and the M1 scalars.

use glam::DVec3;
use rerun::{Clear, LineStrips3D, TextLogLevel};

use super::colors::m1_rule_color;
use super::draw::{f32s, log_face_outlines};
use super::logger::{RerunLogger, to_sink};
use super::parts::{log_edge_parts, log_mesh_parts, log_point_parts};
use crate::session::{M1Outcome, M1Stage, SinkError};

/// Unrefined patches in M1.
const KEPT: [u8; 3] = [185, 185, 190];

impl RerunLogger {
    pub(super) fn log_m1(&self, stage: M1Stage<'_>) -> Result<(), SinkError> {
        let rec = self.recording();
        let M1Stage { outcome, .. } = stage;
        let m1 = &outcome.m1;
        let c = &outcome.collision;
        let positions = &c.positions;
        self.m1_parts(m1, positions)?;
        let edges = m1.edges();
        let strips = |list: &[[u32; 2]], at: &[DVec3]| -> Vec<Vec<[f32; 3]>> {
            list.iter()
                .map(|e| f32s(&[at[e[0] as usize], at[e[1] as usize]]))
                .collect()
        };
        for (path, list, at) in [
            (
                "collision/m1/crossing_before",
                &c.crossing_before_edges,
                &m1.mesh.positions,
            ),
            (
                "collision/m1/crossing_edges",
                &c.quality.crossing.iter().map(|&e| edges[e as usize]).collect(),
                positions,
            ),
        ] {
            if list.is_empty() {
                rec.clear(path)?;
            } else {
                rec.log(
                    path,
                    &LineStrips3D::new(strips(list, at))
                        .with_radii([0.002])
                        .with_colors([[255, 0, 0]]),
                )
                .map_err(to_sink)?;
            }
        }
        log_face_outlines(
            rec,
            "collision/m1/pierced_faces",
            (&m1.mesh.triangles, positions),
            &c.pierced_after,
            (0.002, [255, 0, 0]),
        )?;
        self.log_cut_lines(outcome)?;
        let q = &c.quality;
        let by_rule: Vec<String> = m1
            .selection
            .by_rule()
            .iter()
            .map(|(rule, n)| format!("{rule} {n}"))
            .collect();
        self.text(
            if q.is_clear() {
                TextLogLevel::INFO
            } else {
                TextLogLevel::WARN
            },
            format!(
                "M1: {} vertices, {} faces; {} of {} patches refined ({}); {} new vertices tested, {} inside; crossing edges {} before -> {} after; pierced faces {} before -> {} after; {} inside after; {} cut line(s)",
                positions.len(),
                m1.mesh.triangles.len(),
                m1.selection.count(),
                m1.selection.rules.len(),
                if by_rule.is_empty() { "none".to_string() } else { by_rule.join(", ") },
                c.tested,
                c.hits,
                c.crossing_before,
                q.crossing_edges,
                c.pierced_before,
                q.pierced_faces,
                q.penetrating_vertices,
                outcome.stored.len()
            ),
        )
    }

    /// M1's mesh (vertices coloured by the rule that selected their patch, grey where M0 is
    /// kept), its edges and its new vertices, in parts, only what changed; nothing when the
    /// recording leaves the garment out.
    fn m1_parts(&self, m1: &crate::m1::M1, positions: &[DVec3]) -> Result<(), SinkError> {
        let rec = self.recording();
        if !rec.keeps("garment/m1") {
            return Ok(());
        }
        // The colour of each refined patch: that of the first rule that selected it.
        let by_patch: Vec<Option<[u8; 3]>> = (m1.selection.rules.iter())
            .map(|r| r.first().copied().map(m1_rule_color))
            .collect();
        let mut colors = vec![KEPT; positions.len()];
        for (t, &p) in m1.mesh.triangles.iter().zip(m1.face_patch.iter()) {
            if let Some(color) = by_patch.get(p as usize).copied().flatten() {
                for &v in t {
                    colors[v as usize] = color;
                }
            }
        }
        let parted = self.parted("garment/m1", (positions, &m1.mesh.triangles), &m1.face_patch, &m1.edges);
        log_mesh_parts(rec, "garment/m1/mesh", &parted, &colors)?;
        log_edge_parts(rec, "garment/m1/edges", &parted, (0.0003, [70, 70, 80]))?;
        log_point_parts(
            rec,
            "garment/m1/new_vertices",
            (&parted, m1.m0_vertices),
            (0.0015, [30, 30, 200]),
        )?;
        Ok(())
    }

    /// The cut lines, drawn on M1 and in their stored form on M0 (the old ones cleared).
    fn log_cut_lines(&self, outcome: &M1Outcome) -> Result<(), SinkError> {
        let rec = self.recording();
        rec.log("garment/cut_lines", &Clear::recursive()).map_err(to_sink)?;
        rec.log("garment/m0/cut_lines", &Clear::recursive()).map_err(to_sink)?;
        for ((stored, on_m1), on_m0) in outcome.stored.iter().zip(&outcome.cuts).zip(&outcome.cuts_on_m0) {
            for (path, pieces, color, radius) in [
                (
                    format!("garment/cut_lines/{}", stored.name),
                    on_m1,
                    [230, 20, 120],
                    0.003,
                ),
                (
                    format!("garment/m0/cut_lines/{}", stored.name),
                    on_m0,
                    [250, 200, 0],
                    0.0015,
                ),
            ] {
                let lines: Vec<Vec<[f32; 3]>> = pieces
                    .iter()
                    .map(|(points, closed)| {
                        let mut line = f32s(points);
                        if *closed && let Some(&first) = line.first() {
                            line.push(first);
                        }
                        line
                    })
                    .collect();
                rec.log(
                    path.as_str(),
                    &LineStrips3D::new(lines).with_radii([radius]).with_colors([color]),
                )
                .map_err(to_sink)?;
            }
        }
        Ok(())
    }
}
