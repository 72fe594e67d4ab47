//! Pattern pieces: the garment cut into panels along its seams, each panel flattened with
//! its distortion measured, the two sides of every seam matched, the pieces laid out for
//! cutting (`docs/design.md` section 9; \[frame\] section 6, the paper's last stage).
//!
//! The data flow: the mesh's edges between patches are labelled with the feature curves
//! they lie on ([`labels`]); the edges on the chosen seam curves cut the faces into panels
//! ([`panels`]), each checked to be a disc; each panel is flattened ([`flatten`]: LSCM,
//! then ARAP with the boundary held at its 3D lengths) and measured ([`distortion`]); the
//! seams are chained and their sides' 2D lengths compared ([`seams`]); each piece is
//! turned to its grain and the pieces are laid out ([`layout`]). A panel whose triangles
//! and positions are the previous pattern's, bit for bit, keeps its flattening.
//! [`export`] writes DXF, SVG, JSON and OBJ. Nothing here knows Rerun.

mod build;
pub mod cut_lines;
pub mod distortion;
pub mod export;
pub mod flatten;
pub mod labels;
pub mod layout;
mod names;
pub mod panels;
pub mod seams;
mod types;

pub use build::build;
pub use cut_lines::{CutLine, CutShape};
pub use distortion::Distortion;
pub use flatten::{FlattenError, FlattenOptions, Flattening, Method};
pub use labels::EdgeCurves;
pub use panels::{NotADisc, Panel};
pub use seams::{DEFAULT_SEAMS, Seam, seam_tolerance};
pub use types::{Pattern, PatternError, PatternInput, PatternOptions, Piece, Source};
