//! Step 0, the scene: the body loaded and validated, its landmarks found, its rings cut at
//! the landmarks and its partitions A-G built.

use serde::Serialize;

use crate::body::{self, Body, BodyMesh, BodyRing, BodySource, Landmark, Partition};
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
        BodyMesh::load_bounded(&source, session.scene.units.scale(), limit)
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
