//! Garments made elsewhere: a garment mesh from another tool (exported from garment CAD,
//! draped by a simulator, made by a dataset generator) read with everything its tool needs
//! kept ([`crate::mesh::MeshDocument`]), made ready for the collision layers
//! ([`ImportedGarment`]: welded, oriented away from the body, its size checked), counted
//! exactly, repaired by the same layers as drape's own garments, counted again
//! ([`check`]), and written back with only the moved vertices changed.

pub mod check;
pub mod garment;
pub mod regions;

pub use check::{CheckOptions, CheckReport, CheckTimings, Checked, Counts, RegionCounts, Status, check};
pub use garment::{ImportError, ImportNotes, ImportedGarment};
pub use regions::face_regions;
