//! The garment feature-line framework ([frame]): ring processing, contours, templates,
//! Coons surfacing to M0. This is being built step by step; so far: ring convexification, resampling and easing.

pub mod convexify;
pub mod ease;
pub mod resample;

pub use convexify::{ConvexRing, ConvexifyReport, convex_ring, convexify, extremes};
pub use ease::{Ease, EaseError, deformation_centre, ease_ring};
pub use resample::{ResampleError, resample_closed, resample_open};
