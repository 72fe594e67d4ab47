//! The garment feature-line framework ([frame]): ring processing, contours, templates,
//! Coons surfacing to M0. This is being built step by step; so far: ring convexification.

pub mod convexify;

pub use convexify::{ConvexifyReport, convexify, extremes};
