//! Oriented planes and their 2D frames.

use glam::{DVec2, DVec3};

/// The plane `normal . p = offset` (`normal` of unit length).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal.
    pub normal: DVec3,
    /// Signed distance of the plane from the origin along `normal`.
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

    /// Signed distance of `p` (positive on the normal's side).
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

    /// `p` in the plane's 2D frame.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let (u, v) = self.frame();
        DVec2::new(p.dot(u), p.dot(v))
    }
}
