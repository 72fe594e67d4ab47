//! Logging the mesh-layer collision: hits per partition (points coloured by partition,
//! with their depth as a line to the skin), response arrows coloured by rule, the edges the
//! edge rounds lifted (orange, where they crossed), M0 after response, what is left inside
//! or crossing, and the collision scalars.

use rerun::{Arrows3D, LineStrips3D, Points3D, TextDocument, TextLogLevel};

use super::colors::{CLEARANCE_BANDS, clearance_band, partition_color, rule_color};
use super::draw::{f32s, log_face_outlines};
use super::logger::{RerunLogger, to_sink};
use super::parts::{Parted, log_mesh_parts};
use crate::collision::{AppliedRule, BodyIndex, Collision};
use crate::session::{CollisionOutcome, CollisionPart, CollisionStage, SinkError};

impl RerunLogger {
    /// The fit map: M0 after the response, each vertex coloured by the least clearance of
    /// the faces around it (the distance to the body of their nearest point, where a face
    /// dips nearer the body than its corners; else the vertex's own distance), in the bands
    /// of [`CLEARANCE_BANDS`], and the scale as a text document beside it.
    fn clearance_map(
        &self,
        (mesh, parted): (&crate::mesh::TriMesh, Option<&Parted>),
        clearance: &[f64],
        near_faces: &[(u32, f64)],
    ) -> Result<(), SinkError> {
        let rec = self.recording();
        let mut shown = clearance.to_vec();
        for &(f, d) in near_faces {
            for v in mesh.triangles[f as usize] {
                shown[v as usize] = shown[v as usize].min(d);
            }
        }
        let bands: Vec<usize> = shown.iter().map(|&d| clearance_band(d)).collect();
        let colors: Vec<[u8; 3]> = bands.iter().map(|&k| CLEARANCE_BANDS[k].1).collect();
        if let Some(parted) = parted {
            log_mesh_parts(rec, "garment/clearance", parted, &colors)?;
        }
        let mut counts = [0usize; CLEARANCE_BANDS.len()];
        for k in bands {
            counts[k] += 1;
        }
        let mut text = String::from(
            "## Clearance (fit map)\n\nEach M0 vertex after the response, by the least distance to the body of the faces around it (the vertex's own where no face dips nearer).\n\n| colour | band | vertices |\n|---|---|---:|\n",
        );
        for ((_, [r, g, b], label), n) in CLEARANCE_BANDS.iter().zip(counts) {
            text.push_str(&format!("| rgb({r}, {g}, {b}) | {label} | {n} |\n"));
        }
        rec.log("legend/clearance", &TextDocument::from_markdown(text))
            .map_err(to_sink)
    }

    pub(super) fn log_collision(&self, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        let CollisionStage { outcome, index, part } = stage;
        match part {
            CollisionPart::Detect => self.collision_detect(outcome, index),
            CollisionPart::Respond => self.collision_respond(outcome),
        }
    }

    fn collision_detect(&self, outcome: &CollisionOutcome, index: &BodyIndex) -> Result<(), SinkError> {
        let rec = self.recording();
        let d = &outcome.collision.detection;
        let positions = &outcome.garment.mesh.positions;
        let mut summary = Vec::new();
        for (k, p) in index.partitions.iter().enumerate() {
            let path = format!("collision/mesh/hits/{}", p.id.letter());
            let hits: Vec<_> = d.hits.iter().filter(|h| h.partition == k).collect();
            if hits.is_empty() {
                rec.clear_tree(&path)?;
                continue;
            }
            let points: Vec<_> = hits.iter().map(|h| positions[h.vertex as usize]).collect();
            let color = partition_color(p.id);
            rec.log(
                path.as_str(),
                &Points3D::new(f32s(&points))
                    .with_radii([0.006])
                    .with_colors([color])
                    .with_labels(hits.iter().map(|h| format!("v{} {:.1} mm", h.vertex, h.depth * 1e3)))
                    .with_show_labels(false),
            )
            .map_err(to_sink)?;
            let depth: Vec<Vec<[f32; 3]>> = hits
                .iter()
                .map(|h| f32s(&[positions[h.vertex as usize], h.foot]))
                .collect();
            rec.log(
                format!("{path}/depth"),
                &LineStrips3D::new(depth).with_radii([0.0012]).with_colors([color]),
            )
            .map_err(to_sink)?;
            let deepest = hits.iter().map(|h| h.depth).fold(0.0, f64::max);
            summary.push(format!(
                "{} {} ({}, deepest {:.1} mm)",
                p.id.letter(),
                hits.len(),
                if hits[0].method == crate::body::DetectionMethod::LineLine {
                    "line-line"
                } else {
                    "point-face"
                },
                deepest * 1e3
            ));
        }
        self.text(
            TextLogLevel::INFO,
            format!(
                "detection: {} vertices tested ({} point-face, {} line-line), {} skipped as inert, {} with {} unchanged patches; {} inside{}{}",
                d.tested,
                d.by_method[0],
                d.by_method[1],
                d.skipped_inert,
                d.skipped_patch,
                d.patches_skipped,
                d.hits.len(),
                if summary.is_empty() { "" } else { ": " },
                summary.join(", ")
            ),
        )
    }

    fn collision_respond(&self, outcome: &CollisionOutcome) -> Result<(), SinkError> {
        let c = &outcome.collision;
        let g = &outcome.garment;
        let counts = self.log_response_arrows(c)?;
        let parted = self.m0(&c.mesh, &g.face_patch, &g.edges)?;
        self.clearance_map((&c.mesh, parted.as_ref()), &c.quality.clearance, &c.quality.near_faces)?;
        let q = &c.quality;
        self.log_left_over(outcome)?;
        let verify = outcome.verify.as_ref().map_or(String::new(), |v| {
            format!(
                "; verified by brute force: {} inside before ({} missed: {}; {} false hits, line-line {}; verdicts the skips changed {}), {} inside, {} crossing and {} pierced faces after, quality agrees: {}, equals a full check: {}",
                v.inside_before,
                v.missed,
                v.missed_by,
                v.false_hits,
                v.false_line_line,
                v.skips_changed,
                v.inside_after,
                v.crossing_after,
                v.pierced_after,
                v.quality_agrees,
                v.full_check_agrees
            )
        });
        self.log_guarantee(outcome)?;
        let rounds: Vec<String> = c.edge_rounds.iter().map(ToString::to_string).collect();
        let face_rounds: Vec<String> = c.face_rounds.iter().map(ToString::to_string).collect();
        self.text(
            TextLogLevel::INFO,
            format!(
                "response to {:.1} mm off the body: {} vertices moved ({}); crossing edges per edge round {}; pierced faces per face round {}; after: {} inside (deepest {:.2} mm), {} crossing edges, {} pierced faces, face clearance {:.3} mm, ease error max {:.3} mm, farthest move {:.1} mm, largest edge stretch {:.2}x{}",
                c.ease * 1e3,
                c.responses.len(),
                if counts.is_empty() { "none".to_string() } else { counts.join(", ") },
                if rounds.is_empty() { "-".to_string() } else { rounds.join(" -> ") },
                if face_rounds.is_empty() { "-".to_string() } else { face_rounds.join(" -> ") },
                q.penetrating_vertices,
                q.max_depth_m * 1e3,
                q.crossing_edges,
                q.pierced_faces,
                q.face_clearance_m * 1e3,
                q.max_ease_error_m * 1e3,
                q.max_move_m * 1e3,
                q.max_stretch,
                verify
            ),
        )
    }

    /// The response's moves as arrows, one entity per rule (cleared where a rule moved
    /// nothing); returns each rule's count.
    fn log_response_arrows(&self, c: &Collision) -> Result<Vec<String>, SinkError> {
        let rec = self.recording();
        let mut counts = Vec::new();
        for rule in AppliedRule::ALL {
            let path = format!("collision/response/{}", rule.name());
            let moved: Vec<_> = c.responses.iter().filter(|r| r.rule == rule).collect();
            if moved.is_empty() {
                rec.clear(&path)?;
                continue;
            }
            counts.push(format!("{} {}", rule.name(), moved.len()));
            rec.log(
                path.as_str(),
                &Arrows3D::from_vectors(moved.iter().map(|r| (r.to - r.from).as_vec3().to_array()))
                    .with_origins(moved.iter().map(|r| r.from.as_vec3().to_array()))
                    .with_radii([0.002])
                    .with_colors([rule_color(rule)]),
            )
            .map_err(to_sink)?;
        }
        Ok(counts)
    }

    /// What the response left or met on its way: the edges that crossed after the vertex
    /// response (where they stood then: what the edge rounds lifted), the vertices still
    /// inside, the edges still crossing, and the faces pierced before the face rounds and
    /// after.
    fn log_left_over(&self, outcome: &CollisionOutcome) -> Result<(), SinkError> {
        let rec = self.recording();
        let (c, g) = (&outcome.collision, &outcome.garment);
        let q = &c.quality;
        // The edges that crossed after the vertex response, where they stood then (M0 as
        // built with the penetrating vertices moved): what the edge rounds lifted.
        if c.crossing_before_rounds.is_empty() {
            rec.clear("collision/mesh/crossing_before_rounds")?;
        } else {
            let mut then = g.mesh.positions.clone();
            for r in c.responses.iter().filter(|r| r.edge_round == 0) {
                then[r.vertex as usize] = r.to;
            }
            let lines: Vec<Vec<[f32; 3]>> = c
                .crossing_before_rounds
                .iter()
                .map(|&[a, b]| f32s(&[then[a as usize], then[b as usize]]))
                .collect();
            rec.log(
                "collision/mesh/crossing_before_rounds",
                &LineStrips3D::new(lines)
                    .with_radii([0.0012])
                    .with_colors([[255, 90, 0]]),
            )
            .map_err(to_sink)?;
        }
        if q.inside.is_empty() {
            rec.clear("collision/mesh/remaining")?;
        } else {
            let pts: Vec<_> = q.inside.iter().map(|&v| c.mesh.positions[v as usize]).collect();
            rec.log(
                "collision/mesh/remaining",
                &Points3D::new(f32s(&pts)).with_radii([0.006]).with_colors([[255, 0, 0]]),
            )
            .map_err(to_sink)?;
        }
        if q.crossing.is_empty() {
            rec.clear("collision/mesh/crossing_edges")?;
        } else {
            let lines: Vec<Vec<[f32; 3]>> = q
                .crossing
                .iter()
                .map(|&e| {
                    let [a, b] = g.edges[e as usize];
                    f32s(&[c.mesh.positions[a as usize], c.mesh.positions[b as usize]])
                })
                .collect();
            rec.log(
                "collision/mesh/crossing_edges",
                &LineStrips3D::new(lines).with_radii([0.002]).with_colors([[255, 0, 0]]),
            )
            .map_err(to_sink)?;
        }
        for (path, faces, radius, colour) in [
            (
                "collision/mesh/pierced_before_rounds",
                &c.pierced_before_rounds,
                0.0012,
                [255, 150, 40],
            ),
            ("collision/mesh/pierced_faces", &q.pierced, 0.002, [255, 0, 0]),
        ] {
            let mesh = (g.mesh.triangles.as_slice(), c.mesh.positions.as_slice());
            log_face_outlines(rec, path, mesh, faces, (radius, colour))?;
        }
        Ok(())
    }

    /// The guarantee: nothing inside, nothing crossing, no face pierced; said loudly (a
    /// labelled point at the centre of what is wrong, and a warning) when it is not met.
    fn log_guarantee(&self, outcome: &CollisionOutcome) -> Result<(), SinkError> {
        let rec = self.recording();
        let (c, g) = (&outcome.collision, &outcome.garment);
        let q = &c.quality;
        if q.is_clear() {
            rec.clear("collision/guarantee")?;
        } else {
            let mut spots: Vec<_> = q.inside.iter().map(|&v| c.mesh.positions[v as usize]).collect();
            spots.extend(q.crossing.iter().map(|&e| {
                let [a, b] = g.edges[e as usize];
                c.mesh.positions[a as usize].lerp(c.mesh.positions[b as usize], 0.5)
            }));
            spots.extend(q.pierced.iter().map(|&f| {
                let corners = g.mesh.triangles[f as usize].map(|v| c.mesh.positions[v as usize]);
                (corners[0] + corners[1] + corners[2]) / 3.0
            }));
            let centre = spots.iter().copied().sum::<glam::DVec3>() / spots.len() as f64;
            let label = format!(
                "GUARANTEE NOT MET: {} inside, {} crossing, {} faces pierced",
                q.penetrating_vertices, q.crossing_edges, q.pierced_faces
            );
            rec.log(
                "collision/guarantee",
                &Points3D::new(f32s(&[centre]))
                    .with_radii([0.03])
                    .with_colors([[255, 0, 0]])
                    .with_labels([label.clone()])
                    .with_show_labels(true),
            )
            .map_err(to_sink)?;
            self.text(TextLogLevel::WARN, format!("{label} after the response"))?;
        }
        Ok(())
    }
}
