//! The \[spline\] mannequin: a dress form measured as a coarse ring grid (L layers x P
//! points, the paper's 18 x 12) refined to a dense surface two ways, polar and
//! chord-length cubic splines, and both measured against the form's true surface.
//!
//! The paper only shows pictures (polar distorts neck and shoulder); here an analytic
//! dress form ([`DressForm`]) is the known truth, so the deviation of each method is a
//! number per region.

pub mod deviation;
pub mod dress_form;
pub mod refine_chord;
pub mod refine_polar;
pub mod study;

use thiserror::Error;

pub use deviation::{ErrorStats, TrueSurface};
pub use dress_form::{DressForm, Region};
pub use study::{MannequinResult, RegionErrors, run_mannequin};

use crate::geom::SplineError;
use glam::DVec3;

/// A refined surface: `layers` rings of `points` points each, row-major (ring by ring).
#[derive(Clone, Debug, PartialEq)]
pub struct RingGrid {
    /// Rings.
    pub layers: usize,
    /// Points per ring.
    pub points: usize,
    /// `layers * points` positions, m (world frame).
    pub positions: Vec<DVec3>,
}

impl RingGrid {
    /// Point `j` of ring `i`, m.
    pub fn at(&self, i: usize, j: usize) -> DVec3 {
        self.positions[i * self.points + j]
    }

    /// Triangles of the closed-around, open-ended tube (two per quad).
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        let mut tris = Vec::with_capacity(2 * (self.layers.saturating_sub(1)) * self.points);
        let id = |i: usize, j: usize| (i * self.points + j % self.points) as u32;
        for i in 0..self.layers.saturating_sub(1) {
            for j in 0..self.points {
                // Rings run counter-clockwise seen from above, so this faces outward.
                tris.push([id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
                tris.push([id(i, j), id(i + 1, j + 1), id(i + 1, j)]);
            }
        }
        tris
    }
}

/// Mannequin refinement settings.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct MannequinOptions {
    /// Measured layers (rings). Default value: 18 (the paper's).
    pub layers: usize,
    /// Measured points per layer. Default value: 12 (the paper's).
    pub points: usize,
    /// Each grid interval is split into this many (the paper: 6, so 12 points become 72
    /// and 18 layers 103 rings, 102 intervals). Default value: 6.
    pub subdivisions: usize,
}

impl Default for MannequinOptions {
    fn default() -> Self {
        Self {
            layers: 18,
            points: 12,
            subdivisions: 6,
        }
    }
}

impl MannequinOptions {
    /// A grid of `layers` x `points` with the default subdivision.
    pub fn grid(layers: usize, points: usize) -> Self {
        Self {
            layers,
            points,
            ..Self::default()
        }
    }

    /// Sets [`Self::subdivisions`].
    #[must_use]
    pub fn with_subdivisions(mut self, k: usize) -> Self {
        self.subdivisions = k;
        self
    }
}

/// Why a refinement failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MannequinError {
    /// Too coarse a grid.
    #[error("a mannequin grid needs at least 4 layers and 6 points per layer (got {layers} x {points})")]
    TooCoarse {
        /// Layers.
        layers: usize,
        /// Points.
        points: usize,
    },
    /// A spline could not be built.
    #[error("{method} refinement, {curve}: {source}")]
    Spline {
        /// Which method.
        method: &'static str,
        /// Which curve.
        curve: String,
        /// Cause.
        source: SplineError,
    },
    /// The polar method needs rings that are star-shaped about the axis.
    #[error(
        "polar refinement, layer {layer}: the ring is not star-shaped about the axis (polar angle does not increase at point {point})"
    )]
    NotStarShaped {
        /// Layer.
        layer: usize,
        /// Point.
        point: usize,
    },
    /// The polar method needs heights increasing along each meridian.
    #[error(
        "polar refinement, meridian {meridian}: heights do not increase at layer {layer}, rho(y) is not a function"
    )]
    NotMonotone {
        /// Meridian.
        meridian: usize,
        /// Layer.
        layer: usize,
    },
}
