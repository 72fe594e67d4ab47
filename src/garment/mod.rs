//! The garment feature-line framework (\[frame\]): ring processing, open curves, contours,
//! templates, Coons surfacing and the stitched mesh M0.
//!
//! Layers, lowest first: the data model ([`model`]); the curve algorithms (ring sub-steps
//! in [`ring`], [`convexify`](mod@convexify), [`resample`], [`ease`]; [`open_curve`], [`contour`],
//! [`adjust`]; anchors in [`anchors`]); surfacing ([`surface`], [`m0`]); the templates
//! ([`template`]), which say what a garment's curves and patches are, solved in the context
//! of [`solve`]; and the two entry points, [`build_framework`] (solve on a body) and
//! [`assemble::assemble`] (surface after an edit).

pub mod adjust;
pub mod anchors;
pub mod assemble;
pub mod bridge;
pub mod build;
pub mod contour;
pub mod convexify;
pub mod ease;
pub mod m0;
pub mod model;
pub mod open_curve;
pub mod probe;
pub mod resample;
pub mod ring;
pub mod solve;
pub mod surface;
pub mod template;
pub mod three_sided;

pub use build::{Rebuilt, build_framework, rebuild_framework};
pub use contour::{Contour, ContourKind};
pub use convexify::{ConvexRing, ConvexifyReport, convex_ring, convexify, convexify_open, extremes};
pub use ease::{Ease, EaseError, deformation_centre, ease_ring};
pub use m0::{CurveRef, M0, PatchGrid, StitchReport, stitch, weld};
pub use model::{
    Collar, DimensionValue, Dimensions, FeatureLine, Fit, Framework, FrameworkError, NamedPlane, Sleeves, Straightened,
    Style, TemplateKind,
};
pub use probe::BodyProbe;
pub use resample::{ResampleError, resample_closed, resample_open, resample_open_at};
pub use ring::{GarmentRing, RingOptions, RingStages};
pub use solve::FrameworkOptions;
pub use template::Template;
