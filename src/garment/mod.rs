//! The garment feature-line framework ([frame]): ring processing, open curves, contours,
//! templates, Coons surfacing and the stitched mesh M0.

pub mod adjust;
pub mod assemble;
pub mod contour;
pub mod convexify;
pub mod ease;
pub mod framework;
pub mod m0;
pub mod open_curve;
pub mod probe;
pub mod resample;
pub mod ring;
pub mod template;

pub use convexify::{ConvexRing, ConvexifyReport, convex_ring, convexify, convexify_open, extremes};
pub use ease::{Ease, EaseError, deformation_centre, ease_ring};
pub use framework::{Framework, FrameworkError, FrameworkOptions, build_framework};
pub use m0::{CurveRef, M0, PatchGrid, StitchReport, stitch, weld};
pub use probe::BodyProbe;
pub use resample::{ResampleError, resample_closed, resample_open, resample_open_at};
pub use ring::{GarmentRing, RingOptions, RingStages};
pub use template::{Dimensions, Fit, TemplateKind};
