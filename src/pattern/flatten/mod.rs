//! Flattening one panel (a disc-shaped triangle mesh) into the plane: least squares
//! conformal maps ([`lscm`]) for the start, then as-rigid-as-possible local/global
//! iterations ([`arap`], Liu et al. 2008) with springs on the boundary edges that hold the
//! cut lines at their 3D lengths, so that the two sides of a seam sew.

pub(crate) mod arap;
pub(crate) mod lscm;
mod sparse;
mod types;

use glam::DVec3;

pub use types::{FlattenError, FlattenOptions, Flattening, Frames, Method, boundary_half_edges, signed_area};

/// Flattens a disc-shaped panel (`triangles` counter-clockwise seen from the side that is
/// to face up in the plane).
///
/// `runs` are boundary polylines (the panel's sides of its seams, as vertex lists) whose 2D
/// lengths are held at their 3D lengths, so that two panels sewn along a seam meet; ARAP
/// keeps them (LSCM alone does not).
pub fn flatten(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    runs: &[Vec<u32>],
    options: &FlattenOptions,
) -> Result<Flattening, FlattenError> {
    let frames = Frames::new(positions, triangles)?;
    let start = lscm::lscm(positions, triangles, &frames)?;
    match options.method {
        Method::Lscm => Ok(Flattening {
            uv: start,
            iterations: 0,
            energy: f64::NAN,
        }),
        Method::Arap => arap::arap(positions, triangles, &frames, start, runs, options),
    }
}
