//! One sculpt: the drag, then the adaptive refinement of the region it stretched.

use glam::DVec3;

use super::adaptive::{self, Refined, refine};
use super::drag::{Displacement, Drag, displace_clear_of};
use super::options::{SculptError, SculptOptions};
use crate::mesh::TriMesh;

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
pub(super) fn prepare(
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
