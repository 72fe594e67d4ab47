//! Logging the garment framework: planes, rings through their sub-steps, open curves,
//! contours, labelled control points, patches coloured by patch, M0, and edits.

use glam::DVec3;
use rerun::{Arrows3D, Clear, LineStrips3D, Mesh3D, Points3D, TextLogLevel};

use super::columns::{self, triangles, vec3s};
use super::draw::{closed, f32_words, f32s};
use super::logger::{RerunLogger, to_sink};
use super::parts::{Parted, log_edge_parts, log_mesh_parts};
use crate::garment::{Framework, GarmentRing, RingStages};
use crate::mesh::TriMesh;
use crate::session::{GarmentPart, RingStep, SinkError};

/// Colour of a ring sub-step.
fn step_color(step: RingStep) -> [u8; 3] {
    match step {
        RingStep::Raw => [200, 200, 200],
        RingStep::Convex => [250, 210, 40],
        RingStep::Resampled => [30, 170, 230],
        RingStep::Eased => [255, 130, 40],
        RingStep::Fitted => [220, 40, 150],
    }
}

/// A distinct colour per patch (golden-angle hues).
pub fn patch_color(index: usize) -> [u8; 3] {
    let h = (index as f64 * 137.508).rem_euclid(360.0) / 60.0;
    let (s, v) = (0.55, 0.92);
    let c = v * s;
    let x = c * (1.0 - (h.rem_euclid(2.0) - 1.0).abs());
    let (r, g, b) = match h as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = v - c;
    [r, g, b].map(|t| ((t + m) * 255.0).round() as u8)
}

fn stage_points(stages: &RingStages, step: RingStep) -> Vec<Vec<DVec3>> {
    match step {
        RingStep::Raw => stages.raw.clone(),
        RingStep::Convex => vec![stages.convex.clone()],
        RingStep::Resampled => vec![stages.resampled.clone()],
        RingStep::Eased => vec![stages.eased.clone()],
        RingStep::Fitted => vec![stages.fitted.clone()],
    }
}

fn girth_note(r: &GarmentRing) -> String {
    match (r.target, r.girth_error()) {
        (Some(t), Some(error)) => format!("{} {:.4} m (target {:.4}, error {:+.2e})", r.name, r.girth, t, error),
        _ => format!("{} {:.4} m (body tape {:.4})", r.name, r.girth, r.body_girth),
    }
}

impl RerunLogger {
    pub(super) fn log_garment_part(&self, fw: &Framework, part: GarmentPart) -> Result<(), SinkError> {
        match part {
            GarmentPart::Planes => self.log_planes(fw),
            GarmentPart::Rings(step) => self.log_ring_step(fw, step),
            GarmentPart::Curves => self.log_curves(fw),
            GarmentPart::Patches => self.log_patches(fw),
            GarmentPart::Mesh => self.log_mesh(fw),
        }
    }

    /// The planes the curves were cut in (the collision of an earlier garment cleared).
    fn log_planes(&self, fw: &Framework) -> Result<(), SinkError> {
        let rec = self.recording();
        rec.log("collision", &Clear::recursive()).map_err(to_sink)?;
        for p in &fw.planes {
            let (u, v) = p.plane.frame();
            let c = p.centre - p.plane.normal * p.plane.signed_distance(p.centre);
            let e = p.extent;
            let corners = [c + (u + v) * e, c + (v - u) * e, c - (u + v) * e, c + (u - v) * e];
            rec.log(
                format!("garment/planes/{}", p.name),
                &LineStrips3D::new([closed(&corners)])
                    .with_radii([0.0015])
                    .with_colors([[120, 160, 255]])
                    .with_labels([p.name.clone()])
                    .with_show_labels(false),
            )
            .map_err(to_sink)?;
        }
        let names: Vec<&str> = fw.planes.iter().map(|p| p.name.as_str()).collect();
        self.text(
            TextLogLevel::INFO,
            format!("{} planes: {}", fw.template.name(), names.join(", ")),
        )
    }

    /// Every ring and open curve at one sub-step; the girths once fitted.
    fn log_ring_step(&self, fw: &Framework, step: RingStep) -> Result<(), SinkError> {
        let rec = self.recording();
        let color = step_color(step);
        let mut counts = Vec::new();
        for (name, stages, is_closed) in fw
            .rings
            .iter()
            .map(|r| (r.name.as_str(), &r.stages, true))
            .chain(fw.open_curves.iter().map(|c| (c.name.as_str(), &c.stages, false)))
        {
            let loops = stage_points(stages, step);
            let strips: Vec<Vec<[f32; 3]>> = loops
                .iter()
                .map(|l| if is_closed { closed(l) } else { f32s(l) })
                .collect();
            let path = format!("garment/curves/rings/{name}");
            rec.log(
                path.as_str(),
                &LineStrips3D::new(strips)
                    .with_radii([0.0018])
                    .with_colors([color])
                    .with_labels([format!("{name} ({})", step.name())])
                    .with_show_labels(false),
            )
            .map_err(to_sink)?;
            let points: Vec<DVec3> = loops.iter().flatten().copied().collect();
            rec.log(
                format!("{path}/points"),
                &Points3D::new(f32s(&points)).with_radii([0.003]).with_colors([color]),
            )
            .map_err(to_sink)?;
            if step == RingStep::Raw {
                // The body section stays in view under the later sub-steps.
                let strips: Vec<Vec<[f32; 3]>> = loops
                    .iter()
                    .map(|l| if is_closed { closed(l) } else { f32s(l) })
                    .collect();
                rec.log(
                    format!("garment/sections/{name}"),
                    &LineStrips3D::new(strips)
                        .with_radii([0.0012])
                        .with_colors([[150, 150, 150]]),
                )
                .map_err(to_sink)?;
            }
            counts.push(format!("{name} {}", points.len()));
        }
        let mut text = format!("rings {}: points {}", step.name(), counts.join(", "));
        if step == RingStep::Convex {
            let removed: Vec<String> = fw
                .rings
                .iter()
                .map(|r| {
                    format!(
                        "{} {}",
                        r.name,
                        r.stages.raw.iter().map(Vec::len).sum::<usize>() - r.stages.convex.len()
                    )
                })
                .collect();
            text.push_str(&format!("; points removed: {}", removed.join(", ")));
        }
        if step == RingStep::Fitted {
            let girths: Vec<String> = fw.rings.iter().map(girth_note).collect();
            text.push_str(&format!("; girths: {}", girths.join("; ")));
            self.control_points(fw)?;
        }
        self.text(TextLogLevel::INFO, text)
    }

    /// The contours, the seams and junctions, and the loose fit's straightening.
    fn log_curves(&self, fw: &Framework) -> Result<(), SinkError> {
        let rec = self.recording();
        // A curve the step did not move is not sent again (the recording shows it already).
        for c in &fw.contours {
            let label = Some(c.name.as_str());
            log_curve(
                rec,
                &format!("garment/curves/contours/{}", c.name),
                &c.polyline(),
                label,
            )?;
        }
        for l in &fw.lines {
            log_curve(rec, &format!("garment/curves/lines/{}", l.name), &l.points, None)?;
        }
        let (mut origins, mut vectors) = (Vec::new(), Vec::new());
        for s in &fw.straightened {
            for (a, b) in s.before.iter().zip(&s.after) {
                if a != b {
                    origins.push(a.as_vec3().to_array());
                    vectors.push((*b - *a).as_vec3().to_array());
                }
            }
        }
        if !vectors.is_empty() {
            rec.log(
                "garment/curves/straightened",
                &Arrows3D::from_vectors(vectors)
                    .with_origins(origins)
                    .with_radii([0.002])
                    .with_colors([[255, 80, 80]]),
            )
            .map_err(to_sink)?;
        }
        let names: Vec<&str> = fw.contours.iter().map(|c| c.name.as_str()).collect();
        self.text(
            TextLogLevel::INFO,
            format!(
                "{} contours ({}), {} open curves, {} seams/junctions; {} contours straightened ({} fit)",
                fw.contours.len(),
                names.join(", "),
                fw.open_curves.len(),
                fw.lines.len(),
                fw.straightened.len(),
                fw.fit.name()
            ),
        )
    }

    /// The Coons patches, one colour each.
    fn log_patches(&self, fw: &Framework) -> Result<(), SinkError> {
        let rec = self.recording();
        // Every patch's grid, its points and faces as words, made into Rerun's arrays at once.
        let (mut points, mut faces, mut colors) = (Vec::new(), Vec::new(), Vec::new());
        for (i, p) in fw.patches.iter().enumerate() {
            let base = (points.len() / 3) as u32;
            points.extend(f32_words(&p.points));
            colors.extend(std::iter::repeat_n(patch_color(i), p.points.len()));
            faces.extend(p.triangles().into_iter().flat_map(|t| t.map(|k| k + base)));
        }
        let mut mesh = Mesh3D::update_fields();
        mesh.vertex_positions = Some(vec3s(Mesh3D::descriptor_vertex_positions(), &points));
        mesh.triangle_indices = Some(triangles(Mesh3D::descriptor_triangle_indices(), &faces));
        mesh.vertex_colors = Some(columns::colors(Mesh3D::descriptor_vertex_colors(), colors.into_iter()));
        rec.log("garment/patches", &mesh).map_err(to_sink)?;
        let sizes: Vec<String> = fw
            .patches
            .iter()
            .map(|p| {
                if p.triangular {
                    format!("{} triangle {}", p.name, p.nu)
                } else {
                    format!("{} {}x{}", p.name, p.nu, p.nv)
                }
            })
            .collect();
        let triangles = fw.patches.iter().filter(|p| p.triangular).count();
        let kinds = if triangles == 0 {
            format!("{} Coons patches (segments u x v)", fw.patches.len())
        } else {
            format!(
                "{} Coons patches (segments u x v) and {triangles} three-sided (segments a side)",
                fw.patches.len() - triangles
            )
        };
        self.text(TextLogLevel::INFO, format!("{kinds}: {}", sizes.join(", ")))
    }

    /// M0, with its figures.
    fn log_mesh(&self, fw: &Framework) -> Result<(), SinkError> {
        let rec = self.recording();
        let m0 = &fw.m0;
        rec.clear("garment/patches")?;
        self.m0(&m0.mesh, &m0.face_patch, &m0.edges)?;
        let worst = fw
            .rings
            .iter()
            .filter_map(|r| r.girth_error().map(f64::abs))
            .fold(0.0, f64::max);
        self.text(
            TextLogLevel::INFO,
            format!(
                "M0 ({} {}, {} fit): {} vertices, {} faces, {} edges ({} directed); welded {} of {} patch vertices, {} degenerate and {} duplicate faces dropped; worst girth error {:.2e}",
                fw.template.name(),
                fw.patches.len(),
                fw.fit.name(),
                m0.mesh.positions.len(),
                m0.mesh.triangles.len(),
                m0.edges.len(),
                m0.directed_edges.len(),
                m0.report.welded,
                m0.report.input_vertices,
                m0.report.degenerate_faces,
                m0.report.duplicate_faces,
                worst
            ),
        )
    }

    /// Logs a garment mesh as `garment/m0/mesh/<part>` (vertices coloured by patch) with its
    /// edges at `garment/m0/edges/<part>`, only the parts that changed (see [`super::parts`]);
    /// returns the mesh as logged, for other views of it.
    /// `None` when the recording leaves the garment out (metrics only).
    pub(super) fn m0(
        &self,
        mesh: &TriMesh,
        face_patch: &std::sync::Arc<Vec<u32>>,
        edges: &std::sync::Arc<Vec<[u32; 2]>>,
    ) -> Result<Option<Parted>, SinkError> {
        let rec = self.recording();
        if !rec.keeps("garment/m0") {
            return Ok(None);
        }
        rec.clear("garment/m0/muted")?;
        // Vertex colour: the patch of the first face that uses the vertex.
        let patches = face_patch.iter().max().map_or(0, |&p| p as usize + 1);
        let by_patch: Vec<[u8; 3]> = (0..patches).map(patch_color).collect();
        let mut colors = vec![[200u8, 200, 200]; mesh.positions.len()];
        let mut seen = vec![false; mesh.positions.len()];
        for (t, &p) in mesh.triangles.iter().zip(face_patch.iter()) {
            for &v in t {
                if !seen[v as usize] {
                    seen[v as usize] = true;
                    colors[v as usize] = by_patch[p as usize];
                }
            }
        }
        let parted = self.parted("garment/m0", (&mesh.positions, &mesh.triangles), face_patch, edges);
        log_mesh_parts(rec, "garment/m0/mesh", &parted, &colors)?;
        log_edge_parts(rec, "garment/m0/edges", &parted, (0.0004, [60, 60, 70]))?;
        Ok(Some(parted))
    }

    fn control_points(&self, fw: &Framework) -> Result<(), SinkError> {
        let named = fw.control_points();
        let points: Vec<DVec3> = named.iter().map(|(_, p)| *p).collect();
        self.recording()
            .log(
                "garment/control_points",
                &Points3D::new(f32s(&points))
                    .with_labels(named.iter().map(|(n, _)| n.clone()))
                    .with_radii([0.005])
                    .with_colors([[20, 20, 20]])
                    .with_show_labels(false),
            )
            .map_err(to_sink)
    }

    pub(super) fn log_garment_edit(&self, name: &str, before: &Framework, after: &Framework) -> Result<(), SinkError> {
        let (a, b) = (&before.m0.mesh.positions, &after.m0.mesh.positions);
        let (mut origins, mut vectors) = (Vec::new(), Vec::new());
        let mut largest: f64 = 0.0;
        for (p, q) in a.iter().zip(b) {
            let d = *q - *p;
            largest = largest.max(d.length());
            if d.length() > 1e-6 {
                origins.push(p.as_vec3().to_array());
                vectors.push(d.as_vec3().to_array());
            }
        }
        self.recording()
            .log(
                "garment/edit/moves",
                &Arrows3D::from_vectors(vectors.clone())
                    .with_origins(origins)
                    .with_radii([0.0008])
                    .with_colors([[255, 60, 60]]),
            )
            .map_err(to_sink)?;
        let (old, new) = (before.dimension(name), after.dimension(name));
        self.text(
            TextLogLevel::INFO,
            format!(
                "set {name}: {} -> {} m; {} of {} M0 vertices moved, the largest by {:.4} m; same topology: {}",
                old.map_or("?".into(), |v| format!("{v:.4}")),
                new.map_or("?".into(), |v| format!("{v:.4}")),
                vectors.len(),
                a.len(),
                largest,
                before.m0.mesh.triangles == after.m0.mesh.triangles
            ),
        )
    }
}

/// Logs a framework curve at `path` (with its hidden `label`, if any) through
/// [`super::recording::OrderedRecording::log_part`]: its points when they moved, its style
/// the first time.
fn log_curve(
    rec: &super::recording::OrderedRecording,
    path: &str,
    points: &[DVec3],
    label: Option<&str>,
) -> Result<(), SinkError> {
    const RADIUS: f32 = 0.0018;
    const COLOR: [u8; 3] = [40, 200, 120];
    let fields = vec![
        ("points", std::sync::Arc::new(f32_words(points))),
        ("style", std::sync::Arc::new(vec![RADIUS.to_bits()])),
    ];
    rec.log_part(path, fields, |changed: &[bool]| {
        let mut strips = LineStrips3D::update_fields();
        if changed[0] {
            strips = strips.with_strips([f32s(points)]);
        }
        if changed[1] {
            strips = strips.with_radii([RADIUS]).with_colors([COLOR]);
            if let Some(label) = label {
                strips = strips.with_labels([label]).with_show_labels(false);
            }
        }
        strips
    })?;
    Ok(())
}
