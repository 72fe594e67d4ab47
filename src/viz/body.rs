//! Logging the scene's body: the mesh, its landmarks, the landmark rings, the partitions
//! A-G with their legend, and body sections.

use rerun::{LineStrips3D, Mesh3D, Points3D, TextDocument, TextLogLevel};

use super::colors::{partition_color, partition_tint};
use super::draw::{closed, f32s};
use super::logger::{RerunLogger, to_sink};
use crate::body::{BodyMesh, BodyRing, DetectionMethod, LandmarkKind, Landmarks, Partition, PartitionId, ResponseRule};
use crate::session::{SectionCut, SinkError};

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

impl RerunLogger {
    pub(super) fn log_body_mesh(&self, body: &BodyMesh) -> Result<(), SinkError> {
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
                // The file's name, not its path: a recording must not depend on where the
                // session was run from (replays compare recordings).
                std::path::Path::new(&body.name)
                    .file_name()
                    .map_or_else(|| body.name.clone(), |n| n.to_string_lossy().into_owned()),
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

    pub(super) fn log_landmarks(&self, landmarks: &Landmarks) -> Result<(), SinkError> {
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
                    .with_show_labels(false), // on hover: labels over the body hide it
            )
            .map_err(to_sink)?;
        // Each arm's centre line (the sleeve's axis), shoulder to wrist, the elbow marked.
        for (side, axis) in ["left", "right"].into_iter().zip(&landmarks.arm_axis) {
            if axis.points.len() < 2 {
                continue;
            }
            self.rec
                .log(
                    format!("body/arms/{side}"),
                    &LineStrips3D::new([f32s(&axis.points)])
                        .with_radii([0.003])
                        .with_colors([[255, 200, 40]])
                        .with_labels([format!("{side} arm axis")])
                        .with_show_labels(false),
                )
                .map_err(to_sink)?;
        }
        let listed: Vec<String> = LandmarkKind::ALL
            .iter()
            .chain(&LandmarkKind::ARMS)
            .filter(|k| landmarks.items.iter().any(|l| l.kind == **k))
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

    pub(super) fn log_rings(&self, rings: &[BodyRing]) -> Result<(), SinkError> {
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

    pub(super) fn log_partitions(&self, body: &BodyMesh, partitions: &[Partition]) -> Result<(), SinkError> {
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
        // The tinted body is its own mesh, shown in the Body view only: everywhere else the
        // body keeps its plain skin tone, so that the garment stands apart from it.
        self.rec
            .log(
                "body/partitions/tint",
                &Mesh3D::new(mesh.positions_f32())
                    .with_triangle_indices(mesh.triangles.iter().copied())
                    .with_vertex_normals(mesh.vertex_normals().iter().map(|n| n.as_vec3().to_array()))
                    .with_vertex_colors(colors),
            )
            .map_err(to_sink)?;
        let mut lines = vec!["partitions (bounds m, triangles with margin, test, response):".to_string()];
        // The legend is a table in its own panel, not labels over the body.
        let mut legend = String::from(
            "## Body partitions\n\nEach garment vertex is tested against the partition it falls in, \
             with that partition's test and response.\n\n\
             | | partition | height m | triangles | test | response |\n|---|---|---|---:|---|---|\n",
        );
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
            let [r, g, b] = partition_color(p.id);
            legend.push_str(&format!(
                "| rgb({r}, {g}, {b}) | {} {} | {:.3}..{:.3} | {} | {} | {} |\n",
                p.id.letter(),
                p.id.region(),
                p.lower_y,
                p.upper_y,
                p.triangle_count,
                method_name(p.method),
                response_name(p.response)
            ));
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
            .log("legend/partitions", &TextDocument::from_markdown(legend))
            .map_err(to_sink)?;
        self.text(TextLogLevel::INFO, lines.join("\n"))
    }

    pub(super) fn log_section(&self, cut: SectionCut<'_>) -> Result<(), SinkError> {
        let SectionCut { name, y, loops } = cut;
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
}
