//! The sleeve's intermediate rings by the reference-plane method (\[frame\] figure 7c):
//! between the cap ring C1 and the cuff ring C2, a reference plane II is interpolated (its
//! normal the normalized blend of theirs, through the sleeve axis' point there), the ring
//! C4 interpolated into it (each point the blend of the two rings' points about their
//! planes' origins, the part along II's normal taken away). The final ring C3 that clears
//! the arm is the ring built around C4 and the arm's section eased (their convex hull).

use glam::DVec3;

use crate::geom::Plane;

/// A planar ring's reference frame: its plane's origin on the sleeve axis and its normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RingFrame {
    /// The origin (the axis point the plane passes through), m.
    pub origin: DVec3,
    /// The unit normal (up the sleeve).
    pub normal: DVec3,
}

impl RingFrame {
    /// The plane.
    pub fn plane(&self) -> Plane {
        Plane::from_point_normal(self.origin, self.normal)
    }
}

/// The reference plane II at fraction `t` (0 at C1, 1 at C2) through `origin`, and the ring
/// C4 in it: point `i` is `origin + P(lerp(c1[i] - o1, c2[i] - o2, t))`, `P` taking away the
/// part along II's normal. `c1` and `c2` are sampled alike (the same count, starting at the
/// same anchor, evenly per anchor arc).
pub fn interpolate(
    (c1, f1): (&[DVec3], RingFrame),
    (c2, f2): (&[DVec3], RingFrame),
    t: f64,
    origin: DVec3,
) -> (RingFrame, Vec<DVec3>) {
    let normal = f1.normal.lerp(f2.normal, t).normalize_or_zero();
    let normal = if normal == DVec3::ZERO { f1.normal } else { normal };
    let ring = c1
        .iter()
        .zip(c2)
        .map(|(a, b)| {
            let d = (*a - f1.origin).lerp(*b - f2.origin, t);
            origin + d - normal * d.dot(normal)
        })
        .collect();
    (RingFrame { origin, normal }, ring)
}
