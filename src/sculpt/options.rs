//! A sculpt's settings and why one cannot be made.

use glam::DVec3;
use thiserror::Error;

use super::adaptive::AdaptiveOptions;

/// A sculpt that cannot be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SculptError {
    /// The mesh has no faces.
    #[error("the mesh has no faces to sculpt")]
    EmptyMesh,
    /// The radius is not a positive length.
    #[error("the radius must be a positive length in m, got {0}")]
    Radius(f64),
    /// A drag or option value is NaN or infinite.
    #[error("the pick point and the peak must be finite numbers")]
    NotFinite,
    /// The direction given is zero.
    #[error("the drag direction is zero")]
    ZeroDirection,
    /// The pick point is farther from the mesh than the radius.
    #[error(
        "the pick point is {distance:.4} m from the garment, farther than the radius {radius} m (the nearest \
         point of the garment is {:.3},{:.3},{:.3})",
        nearest.x, nearest.y, nearest.z
    )]
    FarPick {
        /// Distance from the pick to the mesh, m.
        distance: f64,
        /// The radius, m.
        radius: f64,
        /// The mesh's nearest point.
        nearest: DVec3,
    },
    /// Epsilon is not a positive length.
    #[error("eps must be a positive length in m, got {0}")]
    Epsilon(f64),
    /// The weight is outside `[0, 1]`.
    #[error("the Loop weight must be from 0 to 1, got {0}")]
    Weight(f64),
}

/// Sculpt settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SculptOptions {
    /// Faces are refined while their longest edge exceeds this, m. `None` (the default):
    /// the smaller of a quarter of the radius (eight edges across the bump, enough to draw
    /// it smoothly whatever the mesh) and the region's longest edge before the drag (never
    /// coarser than the mesh was there, so a stretch is always refined away).
    pub epsilon: Option<f64>,
    /// Level limit (default [`AdaptiveOptions::MAX_LEVELS`]).
    pub max_levels: usize,
    /// Loop's vertex-rule weight, 0 to 1 (default 1).
    pub weight: f64,
}

impl Default for SculptOptions {
    fn default() -> Self {
        Self {
            epsilon: None,
            max_levels: AdaptiveOptions::MAX_LEVELS,
            weight: 1.0,
        }
    }
}

impl SculptOptions {
    /// The adaptive refinement these settings ask for, to `epsilon`.
    pub fn adaptive(&self, epsilon: f64) -> AdaptiveOptions {
        AdaptiveOptions {
            epsilon,
            max_levels: self.max_levels,
            weight: self.weight,
        }
    }

    pub(super) fn check(&self) -> Result<(), SculptError> {
        if let Some(e) = self.epsilon
            && !(e.is_finite() && e > 0.0)
        {
            return Err(SculptError::Epsilon(e));
        }
        if !(0.0..=1.0).contains(&self.weight) {
            return Err(SculptError::Weight(self.weight));
        }
        Ok(())
    }
}
