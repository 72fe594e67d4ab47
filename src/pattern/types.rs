//! The pattern's settings, input, error and result.

use glam::{DVec2, DVec3};
use serde::Serialize;

use super::cut_lines::CutLine;
use super::distortion::Distortion;
use super::flatten::{FlattenError, FlattenOptions, Flattening};
use super::panels::{NotADisc, Panel};
use super::seams::Seam;

/// Which mesh the pattern is cut from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Source {
    /// M0 after its collision response (default).
    #[default]
    M0,
    /// M1, the refined mesh after its collision (its faces keep their patch).
    M1,
}

impl Source {
    /// The name in sessions.
    pub fn name(self) -> &'static str {
        match self {
            Self::M0 => "m0",
            Self::M1 => "m1",
        }
    }
}

/// Pattern settings (the session's `patterns` statement).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatternOptions {
    /// The seam curves; `None` is the template's default set ([`seams::default_seams`]).
    pub seams: Option<Vec<String>>,
    /// The mesh cut (default M0).
    pub source: Source,
    /// The flattening.
    pub flatten: FlattenOptions,
    /// Notches along a seam at most this far apart, m (default 0.1).
    pub notch_spacing: f64,
    /// The width of the table the pieces are laid out on, m (default 1.5, a cutting table).
    pub table_width: f64,
    /// Space between pieces on the table, m (default 0.02).
    pub gap: f64,
}

impl Default for PatternOptions {
    fn default() -> Self {
        Self {
            seams: None,
            source: Source::M0,
            flatten: FlattenOptions::default(),
            notch_spacing: 0.1,
            table_width: 1.5,
            gap: 0.02,
        }
    }
}

/// What a pattern is cut from.
#[derive(Clone, Copy, Debug)]
pub struct PatternInput<'a> {
    /// Template name (for the default seams).
    pub template: &'a str,
    /// Mesh positions, m.
    pub positions: &'a [DVec3],
    /// Mesh triangles, counter-clockwise seen from outside.
    pub triangles: &'a [[u32; 3]],
    /// The patch of each triangle.
    pub face_patch: &'a [u32],
    /// Patch names, by index.
    pub patch_names: &'a [String],
    /// Where each vertex stood before the collision moved it (the surfaced mesh, whose
    /// patch boundaries are the curves' own samples), index for index with `positions`:
    /// the edges between patches are matched with their curves there, as a response can
    /// move a boundary vertex farther off its curve than an edge is long. `None`: the
    /// positions themselves.
    pub surfaced: Option<&'a [DVec3]>,
    /// The feature curves as polylines, by name.
    pub curves: &'a [(String, Vec<DVec3>)],
    /// The user's cut lines: seams too, the mesh split along them first.
    pub cuts: &'a [CutLine],
}

/// Why a pattern cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PatternError {
    /// A named seam is not a curve of the garment.
    #[error("seam {name:?} is not a curve of this garment; its curves: {known}")]
    UnknownSeam {
        /// The name.
        name: String,
        /// The garment's curves, comma-separated.
        known: String,
    },
    /// The garment has no seam curves to cut along (a garment mesh from a file).
    #[error("garment '{0}' is a mesh from a file: it has no seam curves to cut a pattern along")]
    NoSeams(String),
    /// A panel is not a disc.
    #[error(transparent)]
    NotADisc(#[from] NotADisc),
    /// A panel could not be flattened.
    #[error("panel {panel}: {source}")]
    Flatten {
        /// The panel.
        panel: String,
        /// Why.
        source: FlattenError,
    },
}

/// One pattern piece.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// The panel it comes from.
    pub panel: Panel,
    /// Its patches' names.
    pub patches: Vec<String>,
    /// The flattening, as solved (before the layout).
    pub flat: Flattening,
    /// 2D position of every vertex on the table, m (turned to the grain, laid out).
    pub uv: Vec<DVec2>,
    /// Its distortion.
    pub distortion: Distortion,
    /// Per vertex, the largest strain of its edges (for colouring).
    pub vertex_strain: Vec<f64>,
    /// The grain line on the table (both ends), m.
    pub grain: [DVec2; 2],
    /// Notches on the table: the point on the cut line and the unit direction into the
    /// piece.
    pub notches: Vec<(DVec2, DVec2)>,
    /// 3D area and 2D area, m2.
    pub area_3d: f64,
    /// 2D area, m2.
    pub area_2d: f64,
    /// Whether its flattening was kept from the previous pattern.
    pub reused: bool,
    /// Its sides of seams (own vertices along each), held at their 3D lengths.
    pub runs: Vec<Vec<u32>>,
}

/// A garment's pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct Pattern {
    /// The mesh it was cut from.
    pub source: Source,
    /// The seam curves used.
    pub seam_curves: Vec<String>,
    /// The pieces, in the order of their first face in the mesh.
    pub pieces: Vec<Piece>,
    /// The seams, by curve and panels.
    pub seams: Vec<Seam>,
    /// The panel of each mesh face.
    pub panel_of: Vec<u32>,
}

impl Pattern {
    /// Pieces flattened again (not kept from the previous pattern).
    pub fn flattened(&self) -> usize {
        self.pieces.iter().filter(|p| !p.reused).count()
    }

    /// Every seam within its tolerance.
    pub fn sews(&self) -> bool {
        self.seams.iter().all(Seam::sews)
    }
}
