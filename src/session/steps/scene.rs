//! Step 0, the scene: the body loaded and validated, its landmarks found, its rings cut at
//! the landmarks and its partitions A-G built.

use serde::Serialize;

use crate::body::{self, Body, BodyMesh, BodyRing, BodySource, Landmark, Partition, Side};
use crate::mesh::MeshReport;
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::format::Session;
use crate::session::options::RunOptions;
use crate::session::stage::{BodyStage, Stage};

/// The body mesh as loaded.
#[derive(Serialize)]
struct MeshFigures<'a> {
    /// The body's name (`builtin:...` or the file).
    body: &'a str,
    /// Vertices after repair.
    vertices: usize,
    /// Triangles after repair.
    triangles: usize,
    /// Top minus floor, m.
    height_m: f64,
    /// What validation repaired, one line each.
    repairs: Vec<String>,
    /// The whole validation report.
    mesh_report: &'a MeshReport,
}

/// Each arm found: its centre line's length and the girths across it.
#[derive(Serialize)]
struct ArmsFigures {
    arms: Vec<ArmFigures>,
}

/// One arm's figures.
#[derive(Serialize)]
struct ArmFigures {
    /// `left` or `right`.
    side: &'static str,
    /// Along the centre line, shoulder to wrist, m.
    length_m: f64,
    /// Shoulder to elbow along it, m.
    upper_m: f64,
    /// The centre line's bend at the elbow, degrees.
    bend_deg: f64,
    /// Tape girths across the line at the elbow and at the wrist, m.
    elbow_girth: Option<f64>,
    wrist_girth: Option<f64>,
}

/// The figures of the arm `axis` on `mesh`.
fn arm_figures(mesh: &BodyMesh, side: Side, axis: &body::ArmAxis) -> ArmFigures {
    let (p, e) = (&axis.points, axis.elbow);
    let last = p.len() - 1;
    let upper: f64 = p[..=e].windows(2).map(|w| w[0].distance(w[1])).sum();
    let (u, l) = ((p[e] - p[0]).normalize_or_zero(), (p[last] - p[e]).normalize_or_zero());
    ArmFigures {
        side: if side == Side::Left { "left" } else { "right" },
        length_m: axis.length(),
        upper_m: upper,
        bend_deg: u.dot(l).clamp(-1.0, 1.0).acos().to_degrees(),
        elbow_girth: body::girth_across(mesh, p[e], axis.direction(e)),
        wrist_girth: body::girth_across(mesh, p[last], axis.direction(last)),
    }
}

/// The landmarks.
#[derive(Serialize)]
struct LandmarkFigures<'a> {
    /// Every landmark (kind, side, point in metres).
    landmarks: &'a [Landmark],
    /// Tilt of the neck-base plane from horizontal, degrees (when the neck landmarks span
    /// a plane).
    #[serde(skip_serializing_if = "Option::is_none")]
    neck_plane_tilt_deg: Option<f64>,
}

/// The landmark rings.
#[derive(Serialize)]
struct RingFigures<'a> {
    /// Each ring with its height and tape girth.
    rings: &'a [BodyRing],
}

/// The partitions.
#[derive(Serialize)]
struct PartitionFigures<'a> {
    /// Each partition with its bounds, triangle count, test and response rule.
    partitions: &'a [Partition],
}

/// Loads and analyses the scene's body (or `--body`'s), emitting a stage after each part.
pub(in crate::session) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    session: &Session,
    options: &RunOptions,
) -> Result<Body, StepError> {
    let source = options
        .body_override
        .clone()
        .map_or_else(|| session.scene.body.clone(), BodySource::File);
    let mut landmark_options = options.landmarks.clone();
    landmark_options.overrides = session.scene.landmarks.clone();
    let limit = match options.max_input_bytes {
        0 => crate::input::DEFAULT_MAX_INPUT_BYTES,
        n => n,
    };
    let mesh = scope.timed("body.load", || {
        BodyMesh::load_bounded(&source, session.scene.units.scale(), limit).map(|m| m.reoriented(options.body_frame))
    })?;
    scope.record(&MeshFigures {
        body: &mesh.name,
        vertices: mesh.mesh.positions.len(),
        triangles: mesh.mesh.triangles.len(),
        height_m: mesh.height(),
        repairs: mesh.report.notes(),
        mesh_report: &mesh.report,
    });
    scope.emit("body.load", Stage::Body(BodyStage::Mesh(&mesh)));
    let landmarks = scope.timed("body.landmarks", || body::find_landmarks(&mesh, &landmark_options))?;
    scope.record(&LandmarkFigures {
        landmarks: &landmarks.items,
        neck_plane_tilt_deg: landmarks.neck_plane().map(|p| p.tilt().to_degrees()),
    });
    scope.record(&ArmsFigures {
        arms: [Side::Left, Side::Right]
            .into_iter()
            .zip(&landmarks.arm_axis)
            .filter(|(_, a)| a.points.len() > 2)
            .map(|(side, a)| arm_figures(&mesh, side, a))
            .collect(),
    });
    scope.emit("body.landmarks", Stage::Body(BodyStage::Landmarks(&mesh, &landmarks)));
    let rings = scope.timed("body.rings", || body::cut_rings(&mesh, &landmarks))?;
    scope.record(&RingFigures { rings: &rings });
    scope.emit("body.rings", Stage::Body(BodyStage::Rings(&rings)));
    let partitions = scope.timed("body.partitions", || {
        body::build_partitions(&mesh, &landmarks, &options.partitions)
    })?;
    scope.record(&PartitionFigures {
        partitions: &partitions,
    });
    scope.emit(
        "body.partitions",
        Stage::Body(BodyStage::Partitions(&mesh, &partitions)),
    );
    Ok(Body {
        mesh,
        landmarks,
        rings,
        partitions,
    })
}
