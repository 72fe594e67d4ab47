//! The garment feature-line framework ([frame]): ring processing, contours, templates,
//! Coons surfacing to M0. This is being built step by step; so far: ring convexification and resampling.

pub mod convexify;
pub mod resample;

pub use convexify::{ConvexifyReport, convexify, extremes};
pub use resample::{ResampleError, resample_closed, resample_open};
