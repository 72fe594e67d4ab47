//! Curves, planes and sections: the geometry every stage builds on.

pub mod chord_spline;
pub mod closest;
pub mod coons;
pub mod height_bands;
pub mod inside;
pub mod local_spline;
pub mod plane;
pub mod polygon;
pub mod predicates;
pub mod ray;
pub mod section;
pub mod spline;
pub mod triangle_patch;
pub mod winding_tree;

pub use chord_spline::{ChordSpline3, CurveEnds};
pub use coons::{CoonsPatch, CornerMismatch, ParametricCurve};
pub use height_bands::HeightBands;
pub use local_spline::LocalSpline3;
pub use plane::Plane;
pub use section::{SectionLoop, section_mesh, section_mesh_banded};
pub use spline::{CubicSpline, EndCondition, SplineError};
pub use triangle_patch::{TrianglePatch, triangle_grid};
