//! Loading a body (the OBJ read, validated and repaired) and analysing it: landmarks,
//! rings, partitions.

use std::path::Path;

use thiserror::Error;

use super::landmarks::{self, LandmarkError, LandmarkOptions, Landmarks};
use super::mesh::{BUILTIN_BODY_OBJ, BodyMesh, BodySource};
use super::partition::{self, Partition, PartitionOptions};
use super::rings::{self, BodyRing, RingError};
use crate::geom::HeightBands;
use crate::mesh::validate::validate_and_repair_at;
use crate::mesh::{MeshError, MeshFileError, obj};

/// Why a body could not be used.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BodyError {
    /// The OBJ is unreadable or malformed.
    #[error(transparent)]
    File(#[from] MeshFileError),
    /// The mesh is broken beyond repair.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// Landmarks could not be found.
    #[error("{body}: {source}")]
    Landmarks {
        /// Body name.
        body: String,
        /// Cause.
        source: LandmarkError,
    },
    /// The body does not stand in drape's frame (y up, facing +z).
    #[error("{body}: {cause}")]
    Pose {
        /// Body name.
        body: String,
        /// How it stands.
        cause: super::orient::PoseError,
    },
    /// A ring could not be cut.
    #[error("{body}: {source}")]
    Ring {
        /// Body name.
        body: String,
        /// Cause.
        source: RingError,
    },
}

impl BodyMesh {
    /// Loads and validates a body; `scale` converts file units to metres. A file is read
    /// within [`crate::input::DEFAULT_MAX_INPUT_BYTES`].
    pub fn load(source: &BodySource, scale: f64) -> Result<Self, BodyError> {
        Self::load_bounded(source, scale, crate::input::DEFAULT_MAX_INPUT_BYTES)
    }

    /// Loads and validates a body, a file of at most `max_bytes`.
    pub fn load_bounded(source: &BodySource, scale: f64, max_bytes: u64) -> Result<Self, BodyError> {
        let name = source.name();
        let parsed = match source {
            BodySource::Builtin => obj::parse_obj(BUILTIN_BODY_OBJ, &name, scale)?,
            BodySource::File(path) => crate::mesh::document::read_mesh(path, scale, max_bytes)?,
        };
        Self::from_obj(name, parsed)
    }

    /// Validates OBJ text (for tests and tools).
    pub fn from_obj_text(text: &str, name: &str, scale: f64) -> Result<Self, BodyError> {
        Self::from_obj(name.to_string(), obj::parse_obj(text, name, scale)?)
    }

    fn from_obj(name: String, parsed: obj::ObjMesh) -> Result<Self, BodyError> {
        let mut mesh = parsed.mesh;
        let (report, adjacency) =
            validate_and_repair_at(&mut mesh, &name, (&parsed.triangle_lines, parsed.place_word))?;
        let bands = HeightBands::new(&mesh);
        Ok(Self {
            name,
            mesh,
            adjacency,
            report,
            polygons_triangulated: parsed.polygons_triangulated,
            bands,
        })
    }
}

/// A body ready for garments: mesh, landmarks, rings and partitions.
#[derive(Clone, Debug)]
pub struct Body {
    /// The mesh.
    pub mesh: BodyMesh,
    /// Landmarks.
    pub landmarks: Landmarks,
    /// Rings at the landmarks.
    pub rings: Vec<BodyRing>,
    /// Partitions A-G.
    pub partitions: Vec<Partition>,
}

impl Body {
    /// Analyses a loaded mesh: landmarks, rings, partitions.
    pub fn analyse(
        mesh: BodyMesh,
        landmark_options: &LandmarkOptions,
        partition_options: &PartitionOptions,
    ) -> Result<Self, BodyError> {
        let landmarks = find_landmarks(&mesh, landmark_options)?;
        let rings = cut_rings(&mesh, &landmarks)?;
        let partitions = build_partitions(&mesh, &landmarks, partition_options)?;
        Ok(Self {
            mesh,
            landmarks,
            rings,
            partitions,
        })
    }

    /// Loads and analyses with default options.
    pub fn load_default(path: Option<&Path>) -> Result<Self, BodyError> {
        let source = path.map_or(BodySource::Builtin, |p| BodySource::File(p.to_path_buf()));
        Self::analyse(
            BodyMesh::load(&source, 1.0)?,
            &LandmarkOptions::default(),
            &PartitionOptions::default(),
        )
    }
}

/// Landmark detection on a body mesh, once it stands in drape's frame ([`check_pose`](super::orient::check_pose)); errors carry the body name.
pub fn find_landmarks(mesh: &BodyMesh, options: &LandmarkOptions) -> Result<Landmarks, BodyError> {
    super::orient::check_pose(&mesh.mesh).map_err(|cause| BodyError::Pose {
        body: mesh.name.clone(),
        cause,
    })?;
    landmarks::detect_landmarks(mesh, options).map_err(|source| BodyError::Landmarks {
        body: mesh.name.clone(),
        source,
    })
}

/// The landmark rings of a body.
pub fn cut_rings(mesh: &BodyMesh, landmarks: &Landmarks) -> Result<Vec<BodyRing>, BodyError> {
    rings::landmark_rings(mesh, landmarks).map_err(|source| BodyError::Ring {
        body: mesh.name.clone(),
        source,
    })
}

/// The partitions of a body.
pub fn build_partitions(
    mesh: &BodyMesh,
    landmarks: &Landmarks,
    options: &PartitionOptions,
) -> Result<Vec<Partition>, BodyError> {
    partition::partitions(mesh, landmarks, options).map_err(|source| BodyError::Ring {
        body: mesh.name.clone(),
        source,
    })
}
