//! The body's mesh: where it comes from and the validated mesh with its adjacency and
//! height bands. Loading it is in [`super::load`].

use std::path::PathBuf;

use crate::geom::{HeightBands, Plane, SectionLoop, section_mesh_banded};
use crate::mesh::{Adjacency, MeshReport, TriMesh};

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
    pub(super) bands: HeightBands,
}

impl BodyMesh {
    /// Sorts the triangles by height again, after [`Self::mesh`] was changed.
    pub fn reindex(&mut self) {
        self.bands = HeightBands::new(&self.mesh);
    }

    /// The body's section by `plane` ([`section_mesh_banded`]: a horizontal plane looks only
    /// at the triangles at its height).
    pub fn section(&self, plane: &Plane) -> Vec<SectionLoop> {
        section_mesh_banded(&self.mesh, &self.adjacency, &self.bands, plane)
    }

    /// The body turned from its file's `frame` into drape's (y up, facing +z): a rotation,
    /// so the triangles keep their orientation and adjacency.
    pub fn reoriented(mut self, frame: super::orient::Frame) -> Self {
        if !frame.is_identity() {
            let m = frame.to_drape();
            for p in &mut self.mesh.positions {
                *p = m * *p;
            }
            self.reindex();
        }
        self
    }

    /// Height (top minus floor), m.
    pub fn height(&self) -> f64 {
        self.mesh.bounds().map_or(0.0, |(lo, hi)| hi.y - lo.y)
    }
}
