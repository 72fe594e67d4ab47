//! The body: mesh loading and validation, landmarks, section rings, partitions A-G.

pub mod index;
pub mod index_cache;
pub mod landmarks;
pub mod near_tree;
pub mod nearby;
pub mod partition;
pub mod profile;
pub mod rings;
pub mod shell;
pub mod slices;

use std::path::{Path, PathBuf};

use thiserror::Error;

pub use landmarks::{Landmark, LandmarkError, LandmarkKind, LandmarkOptions, LandmarkOverride, Landmarks, Side};
pub use partition::{DetectionMethod, Partition, PartitionId, PartitionOptions, ResponseRule};
pub use rings::{BodyRing, RingError};

use crate::geom::{HeightBands, Plane, SectionLoop, section_mesh_banded};
use crate::mesh::{Adjacency, MeshError, MeshReport, ObjError, TriMesh, obj, validate_and_repair};

/// The body shipped with drape (MakeHuman, CC0), used by `body builtin`.
pub const BUILTIN_BODY_OBJ: &str = include_str!("../../assets/bodies/female-young-average.obj");

/// Name of the built-in body.
pub const BUILTIN_BODY_NAME: &str = "builtin:female-young-average";

/// Where a body comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BodySource {
    /// The shipped body.
    Builtin,
    /// An OBJ file.
    File(PathBuf),
}

impl BodySource {
    /// A name for messages.
    pub fn name(&self) -> String {
        match self {
            Self::Builtin => BUILTIN_BODY_NAME.to_string(),
            Self::File(p) => p.display().to_string(),
        }
    }
}

/// Why a body could not be used.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BodyError {
    /// The OBJ is unreadable or malformed.
    #[error(transparent)]
    Obj(#[from] ObjError),
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
    /// A ring could not be cut.
    #[error("{body}: {source}")]
    Ring {
        /// Body name.
        body: String,
        /// Cause.
        source: RingError,
    },
}

/// A loaded, validated body mesh with its adjacency.
#[derive(Clone, Debug)]
pub struct BodyMesh {
    /// Name for messages.
    pub name: String,
    /// The repaired mesh, outward-facing. Code that changes it afterwards calls
    /// [`Self::reindex`] (sections of a mesh changed without it are cut the slow way).
    pub mesh: TriMesh,
    /// Triangle adjacency.
    pub adjacency: Adjacency,
    /// What validation found.
    pub report: MeshReport,
    /// Polygons with more than 3 corners triangulated on load.
    pub polygons_triangulated: usize,
    /// The triangles by height, for horizontal sections (made on load, from `mesh`).
    bands: HeightBands,
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
            BodySource::File(path) => obj::read_obj(path, scale, max_bytes)?,
        };
        Self::from_obj(name, parsed)
    }

    /// Validates OBJ text (for tests and tools).
    pub fn from_obj_text(text: &str, name: &str, scale: f64) -> Result<Self, BodyError> {
        Self::from_obj(name.to_string(), obj::parse_obj(text, name, scale)?)
    }

    fn from_obj(name: String, parsed: obj::ObjMesh) -> Result<Self, BodyError> {
        let mut mesh = parsed.mesh;
        let (report, adjacency) = validate_and_repair(&mut mesh, &name, &parsed.triangle_lines)?;
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

    /// Sorts the triangles by height again, after [`Self::mesh`] was changed.
    pub fn reindex(&mut self) {
        self.bands = HeightBands::new(&self.mesh);
    }

    /// The body's section by `plane` ([`section_mesh_banded`]: a horizontal plane looks only
    /// at the triangles at its height).
    pub fn section(&self, plane: &Plane) -> Vec<SectionLoop> {
        section_mesh_banded(&self.mesh, &self.adjacency, &self.bands, plane)
    }

    /// Height (top minus floor), m.
    pub fn height(&self) -> f64 {
        self.mesh.bounds().map_or(0.0, |(lo, hi)| hi.y - lo.y)
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

/// Landmark detection on a body mesh (errors carry the body name).
pub fn find_landmarks(mesh: &BodyMesh, options: &LandmarkOptions) -> Result<Landmarks, BodyError> {
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
