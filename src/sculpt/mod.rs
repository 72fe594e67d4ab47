//! Sculpting (\[sculpt\], docs/design.md section 8): free-form pushes and pulls on a mesh, refined
//! only where the drag stretched it.
//!
//! Data flow of one sculpt: [`displace`] (pick the nearest point of the mesh, move the
//! vertices within the radius by the peak times the [`Falloff`]; the faces with a moved
//! corner are the region) -> [`refine`] (adaptive Loop subdivision with red-green closure
//! of the region, until no region face has an edge longer than epsilon) -> (in a session)
//! the collision of what changed with the body, by M1's machinery
//! ([`crate::m1::collide_refined`]). [`compare()`] runs the same drag with no subdivision,
//! with uniform Loop to the same epsilon, and adaptively, and measures all three.
//!
//! Nothing here logs: [`crate::viz`] draws the results.

pub mod adaptive;
pub mod compare;
pub mod drag;
pub mod falloff;
pub mod loop_rules;
pub mod measure;

pub use adaptive::{AdaptiveOptions, Level, Refined, refine};
pub use compare::{Comparison, Variant, compare};
pub use drag::{Displacement, Drag, Pick, STOP_TOLERANCE_M, displace, displace_clear_of, pick};
pub use falloff::Falloff;
pub use loop_rules::{UniformStep, boundary_vertex, edge_point, interior_vertex, loop_beta, uniform_step};
pub use measure::{Measures, measure};

use glam::DVec3;
use thiserror::Error;

use crate::mesh::TriMesh;

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

    fn check(&self) -> Result<(), SculptError> {
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

/// A drag and its adaptive refinement.
#[derive(Clone, Debug, PartialEq)]
pub struct Sculpt {
    /// The drag on the input mesh.
    pub displacement: Displacement,
    /// The epsilon used, m.
    pub epsilon: f64,
    /// The refined mesh.
    pub refined: Refined,
}

/// The longest edge of the faces `faces` of `mesh` (0 for none).
pub fn longest_edge(mesh: &TriMesh, faces: impl IntoIterator<Item = usize>) -> f64 {
    faces
        .into_iter()
        .map(|t| adaptive::face_longest_edge(&mesh.positions, mesh.triangles[t]))
        .fold(0.0, f64::max)
}

/// The drag, its region flags and epsilon, shared by [`sculpt`] and [`compare()`].
fn prepare(
    mesh: &TriMesh,
    drag: &Drag,
    options: &SculptOptions,
    keep_out: Option<&(dyn Fn(DVec3) -> bool + Sync)>,
) -> Result<(Displacement, Vec<bool>, f64), SculptError> {
    options.check()?;
    let displacement = displace_clear_of(mesh, &mesh.vertex_normals(), drag, keep_out)?;
    let mut region = vec![false; mesh.triangles.len()];
    for &t in &displacement.region {
        region[t as usize] = true;
    }
    let epsilon = options.epsilon.unwrap_or_else(|| {
        let before = longest_edge(mesh, displacement.region.iter().map(|&t| t as usize));
        (drag.radius / 4.0).min(before)
    });
    Ok((displacement, region, epsilon))
}

/// Applies `drag` to `mesh` and refines the region adaptively.
///
/// # Errors
/// Bad drag values or options, or a pick farther from the mesh than the radius.
pub fn sculpt(mesh: &TriMesh, drag: &Drag, options: &SculptOptions) -> Result<Sculpt, SculptError> {
    sculpt_clear_of(mesh, drag, options, None)
}

/// [`sculpt`] with the drag stopped where it would end in `keep_out` (see
/// [`displace_clear_of`]).
///
/// # Errors
/// As [`sculpt`].
pub fn sculpt_clear_of(
    mesh: &TriMesh,
    drag: &Drag,
    options: &SculptOptions,
    keep_out: Option<&(dyn Fn(DVec3) -> bool + Sync)>,
) -> Result<Sculpt, SculptError> {
    let (displacement, region, epsilon) = prepare(mesh, drag, options, keep_out)?;
    let dragged = TriMesh {
        positions: displacement.positions.clone(),
        triangles: mesh.triangles.clone(),
    };
    let refined = refine(&dragged, &region, &options.adaptive(epsilon));
    Ok(Sculpt {
        displacement,
        epsilon,
        refined,
    })
}
