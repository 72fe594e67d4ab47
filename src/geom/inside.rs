//! Brute-force inside test: the generalized winding number of a closed triangle mesh at a
//! point, summed over every triangle (van Oosterom and Strackee's solid angle). It is
//! about 1 inside, 0 outside; slow (every triangle) and independent of any BVH, which makes
//! it the ground truth the fast tests are checked against.

use glam::DVec3;

use crate::mesh::TriMesh;

/// Solid angle of triangle `abc` seen from `p`, over 4 pi (signed by orientation).
pub(crate) fn solid_angle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (a, b, c) = (a - p, b - p, c - p);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let det = a.dot(b.cross(c));
    let denom = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * det.atan2(denom) / (4.0 * std::f64::consts::PI)
}

/// The generalized winding number of `mesh` (closed, outward-oriented) at `p`, unitless:
/// the sum of the solid angles of its triangles seen from `p` over `4 pi` (Van Oosterom and
/// Strackee 1983 for each triangle's solid angle; Jacobson et al. 2013): 1 inside, 0
/// outside.
pub fn winding_number(mesh: &TriMesh, p: DVec3) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            solid_angle(p, a, b, c)
        })
        .sum()
}

/// `p` is inside the closed mesh (winding number above one half).
pub fn is_inside(mesh: &TriMesh, p: DVec3) -> bool {
    winding_number(mesh, p) > 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tetrahedron_winds_once_around_inner_points_only() {
        let mesh = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        };
        assert!((winding_number(&mesh, DVec3::splat(0.1)) - 1.0).abs() < 1e-12);
        assert!(winding_number(&mesh, DVec3::splat(1.0)).abs() < 1e-12);
        assert!(winding_number(&mesh, DVec3::new(-0.1, 0.2, 0.2)).abs() < 1e-12);
    }
}
