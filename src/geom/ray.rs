//! Ray against triangle (Möller and Trumbore 1997), in `f64`. Used for the response rays
//! (from a penetrating vertex out through the skin) and for edges crossing the body.
//! Zero-area triangles and rays parallel to the plane never hit.

use glam::DVec3;

/// Where the ray `origin + t dir` meets triangle `[a, b, c]`: `t` in `(t_min, t_max]`.
/// Both sides count (the body's orientation is read from the hit triangle's normal).
pub fn ray_triangle(origin: DVec3, dir: DVec3, [a, b, c]: [DVec3; 3], t_min: f64, t_max: f64) -> Option<f64> {
    let e1 = b - a;
    let e2 = c - a;
    let pv = dir.cross(e2);
    let det = e1.dot(pv);
    let scale = e1.length() * e2.length() * dir.length();
    if det.abs() <= 1e-14 * scale || scale == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let tv = origin - a;
    let u = tv.dot(pv) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qv = tv.cross(e1);
    let v = dir.dot(qv) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(qv) * inv;
    (t > t_min && t <= t_max).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: [DVec3; 3] = [DVec3::ZERO, DVec3::X, DVec3::Y];

    #[test]
    fn hits_inside_misses_outside_and_parallel() {
        let d = DVec3::NEG_Z;
        assert_eq!(ray_triangle(DVec3::new(0.25, 0.25, 2.0), d, T, 0.0, 10.0), Some(2.0));
        assert_eq!(ray_triangle(DVec3::new(0.75, 0.75, 2.0), d, T, 0.0, 10.0), None);
        assert_eq!(ray_triangle(DVec3::new(0.25, 0.25, 2.0), d, T, 0.0, 1.0), None);
        assert_eq!(ray_triangle(DVec3::new(0.25, 0.25, 0.0), DVec3::X, T, 0.0, 10.0), None);
        let flat = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert_eq!(ray_triangle(DVec3::new(0.5, 0.0, 1.0), d, flat, 0.0, 10.0), None);
    }
}
