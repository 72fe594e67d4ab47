//! Least squares conformal maps (Lévy et al. 2002) in the form of Mullen et al. (2008):
//! the conformal energy `E_C = E_D - A`, the Dirichlet energy of the map less its signed
//! area, is a quadratic form `x^T (L_D - A) x / 2` over the `2n` coordinates; two boundary
//! vertices far apart are pinned and the rest solved for. A map that can be isometric (a
//! developable panel) is found exactly up to a similarity; scaling the result to the 3D
//! area makes it the isometry.

use glam::{DVec2, DVec3};

use super::sparse::PinnedSystem;
use super::types::{FlattenError, Frames, boundary_half_edges, signed_area};

/// The conformal start of a panel, scaled so that its 2D area equals its 3D area.
pub(crate) fn lscm(positions: &[DVec3], triangles: &[[u32; 3]], frames: &Frames) -> Result<Vec<DVec2>, FlattenError> {
    let n = positions.len();
    let boundary = boundary_half_edges(triangles);
    let Some(&[first, _]) = boundary.first() else {
        return Err(FlattenError::NoBoundary);
    };
    // Two boundary vertices far apart: the farthest from the first, then the farthest
    // from that one.
    let farthest = |from: u32| {
        boundary
            .iter()
            .map(|e| e[0])
            .max_by(|&a, &b| {
                let (da, db) = (
                    positions[a as usize].distance_squared(positions[from as usize]),
                    positions[b as usize].distance_squared(positions[from as usize]),
                );
                da.total_cmp(&db).then(b.cmp(&a))
            })
            .unwrap_or(from)
    };
    let p = farthest(first);
    let q = farthest(p);
    if p == q {
        return Err(FlattenError::Empty);
    }
    let mut triplets = Vec::with_capacity(triangles.len() * 24 + boundary.len() * 4);
    for (t, cot) in triangles.iter().zip(&frames.cot) {
        for k in 0..3 {
            let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
            let w = 0.5 * cot[k];
            for off in [0, n] {
                triplets.extend([
                    (i + off, i + off, w),
                    (j + off, j + off, w),
                    (i + off, j + off, -w),
                    (j + off, i + off, -w),
                ]);
            }
        }
    }
    for &[i, j] in &boundary {
        let (i, j) = (i as usize, j as usize);
        triplets.extend([(i, n + j, -0.5), (n + j, i, -0.5), (j, n + i, 0.5), (n + i, j, 0.5)]);
    }
    let (p, q) = (p as usize, q as usize);
    let pins = [p, n + p, q, n + q];
    let system = PinnedSystem::factor(2 * n, &triplets, &pins)?;
    let mut x = vec![0.0; 2 * n];
    x[q] = positions[p].distance(positions[q]);
    system.solve(&vec![0.0; 2 * n], &mut x);
    let mut uv: Vec<DVec2> = (0..n).map(|i| DVec2::new(x[i], x[n + i])).collect();
    // Scale (and, were it mirrored, reflect) to the 3D area.
    let area_2d: f64 = triangles
        .iter()
        .map(|t| signed_area(uv[t[0] as usize], uv[t[1] as usize], uv[t[2] as usize]))
        .sum();
    let area_3d: f64 = frames.area.iter().sum();
    if area_2d == 0.0 || !area_2d.is_finite() {
        return Err(FlattenError::NotPositiveDefinite { unknowns: 2 * n - 4 });
    }
    let s = (area_3d / area_2d.abs()).sqrt();
    let mirror = if area_2d < 0.0 { -1.0 } else { 1.0 };
    for w in &mut uv {
        *w = DVec2::new(w.x * s, w.y * s * mirror);
    }
    Ok(uv)
}
