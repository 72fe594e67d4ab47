//! Oriented planes and their 2D frames.

use glam::{DVec2, DVec3};

/// The plane `normal . p = offset` (`normal` of unit length).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal.
    pub normal: DVec3,
    /// Signed distance of the plane from the origin along `normal` (input units, m in drape).
    pub offset: f64,
}

impl Plane {
    /// The horizontal plane at height `y` (normal `+y`).
    pub fn horizontal(y: f64) -> Self {
        Self {
            normal: DVec3::Y,
            offset: y,
        }
    }

    /// The plane through `point` with the given normal (normalized here).
    pub fn from_point_normal(point: DVec3, normal: DVec3) -> Self {
        let normal = normal.normalize();
        Self {
            normal,
            offset: normal.dot(point),
        }
    }

    /// Signed distance of `p`, `normal . p - offset` (positive on the normal's side; input
    /// units).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }

    /// An orthonormal frame `(u, v)` of the plane with `u x v = normal`. For the
    /// horizontal plane `u = +z`, `v = +x`, so counter-clockwise in `(u, v)` is
    /// counter-clockwise seen from above.
    pub fn frame(&self) -> (DVec3, DVec3) {
        let n = self.normal;
        let helper = if n.y.abs() > 0.9 { DVec3::Z } else { DVec3::Y };
        let u = (helper - n * n.dot(helper)).normalize();
        (u, n.cross(u))
    }

    /// The least-squares plane through `points`: their centroid and the eigenvector of the
    /// smallest eigenvalue of their covariance (nalgebra's symmetric eigen-decomposition).
    /// The normal is oriented to have a non-negative `y`. `None` for fewer than 3 points,
    /// non-finite input or points on a line (no unique plane).
    pub fn fit(points: &[DVec3]) -> Option<Self> {
        if points.len() < 3 || points.iter().any(|p| !p.is_finite()) {
            return None;
        }
        let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
        let mut covariance = nalgebra::Matrix3::<f64>::zeros();
        for p in points {
            let d = nalgebra::Vector3::new(p.x - centroid.x, p.y - centroid.y, p.z - centroid.z);
            covariance += d * d.transpose();
        }
        let eigen = covariance.symmetric_eigen();
        let mut order = [0usize, 1, 2];
        order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
        // A line has two (near) zero eigenvalues: the plane is not determined.
        let scale = eigen.eigenvalues[order[2]].abs().max(f64::MIN_POSITIVE);
        if eigen.eigenvalues[order[1]].abs() <= 1e-12 * scale {
            return None;
        }
        let n = eigen.eigenvectors.column(order[0]);
        let mut normal = DVec3::new(n[0], n[1], n[2]).normalize();
        if normal.y < 0.0 {
            normal = -normal;
        }
        Some(Self::from_point_normal(centroid, normal))
    }

    /// Angle between the normal and `+y`, radians (0 for a horizontal plane).
    pub fn tilt(&self) -> f64 {
        self.normal.dot(DVec3::Y).clamp(-1.0, 1.0).acos()
    }

    /// `p` in the plane's 2D frame.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let (u, v) = self.frame();
        DVec2::new(p.dot(u), p.dot(v))
    }

    /// The point of the plane with in-plane coordinates `q` (the inverse of [`Self::project`]
    /// on the plane; input units).
    pub fn lift(&self, q: DVec2) -> DVec3 {
        let (u, v) = self.frame();
        self.normal * self.offset + u * q.x + v * q.y
    }

    /// `p` moved along the normal onto the plane: `p - (normal . p - offset) normal`.
    pub fn snap(&self, p: DVec3) -> DVec3 {
        p - self.normal * self.signed_distance(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_recovers_a_known_plane_and_refuses_a_line() {
        let plane = Plane::from_point_normal(DVec3::new(0.1, 1.3, 0.05), DVec3::new(0.0, 1.0, 0.3));
        let (u, v) = plane.frame();
        let origin = plane.normal * plane.offset;
        let pts: Vec<DVec3> = (0..20)
            .map(|i| origin + u * (i as f64 * 0.37).sin() + v * (i as f64 * 0.11))
            .collect();
        let fit = Plane::fit(&pts).unwrap();
        assert!(fit.normal.distance(plane.normal) < 1e-12 && (fit.offset - plane.offset).abs() < 1e-12);
        assert!((fit.tilt() - 0.3f64.atan()).abs() < 1e-12);
        let line: Vec<DVec3> = (0..5).map(|i| DVec3::X * i as f64).collect();
        assert_eq!(Plane::fit(&line), None);
    }
}
