//! Exact orientation predicates (Shewchuk's adaptive `orient3d`, from the `robust` crate):
//! the side of a plane a point lies on, and whether a segment crosses a triangle, decided
//! without rounding error whatever the inputs, so that a verdict never flips on a point a
//! hair off the skin or an edge through a body edge.

use std::cmp::Ordering;

use glam::DVec3;
use robust::{Coord3D, orient3d};

fn coord(p: DVec3) -> Coord3D<f64> {
    Coord3D { x: p.x, y: p.y, z: p.z }
}

/// Which side of the plane through `a`, `b`, `c` the point `d` lies on, exactly: `Greater`
/// on the side `(b - a) x (c - a)` points to (outside, for an outward-facing body
/// triangle), `Less` on the other, `Equal` in the plane (or for a degenerate triangle).
pub fn side(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Ordering {
    // Shewchuk's orient3d is positive when `d` lies below the plane, `a b c` seen
    // counter-clockwise from above.
    0.0.partial_cmp(&orient3d(coord(a), coord(b), coord(c), coord(d)))
        .unwrap_or(Ordering::Equal)
}

/// Whether the segment `p..q` passes through triangle `[a, b, c]`: its ends strictly on
/// opposite sides of the triangle's plane and the crossing point in the closed triangle (so
/// a segment through an edge shared by two triangles crosses both, and one that only
/// touches the plane at an end crosses neither). Exact. A degenerate triangle is never
/// crossed (its neighbours cover the surface).
pub fn segment_crosses_triangle(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let (sp, sq) = (side(a, b, c, p), side(a, b, c, q));
    strictly_apart(sp, sq) && line_through_triangle(p, q, [a, b, c])
}

/// Whether two sides of a plane ([`side`]) are strictly opposite: neither in the plane.
pub fn strictly_apart(sp: Ordering, sq: Ordering) -> bool {
    sp != Ordering::Equal && sq != Ordering::Equal && sp != sq
}

/// Whether the line through `p` and `q` passes through the closed triangle `[a, b, c]`: it
/// turns the same way (or not at all) about each of the three edges. Exact. With `p` and
/// `q` strictly on either side of the triangle's plane, this is
/// [`segment_crosses_triangle`].
pub fn line_through_triangle(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let turns = [side(p, q, a, b), side(p, q, b, c), side(p, q, c, a)];
    let positive = turns.iter().all(|&s| s != Ordering::Less);
    let negative = turns.iter().all(|&s| s != Ordering::Greater);
    positive || negative
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_of_the_unit_triangle() {
        let [a, b, c] = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert_eq!(side(a, b, c, DVec3::Z), Ordering::Greater);
        assert_eq!(side(a, b, c, -DVec3::Z), Ordering::Less);
        assert_eq!(side(a, b, c, DVec3::new(5.0, 7.0, 0.0)), Ordering::Equal);
        // 1e-300 off the plane is still off it.
        assert_eq!(side(a, b, c, DVec3::new(0.3, 0.3, 1e-300)), Ordering::Greater);
    }

    #[test]
    fn segments_through_the_inside_an_edge_and_past_the_triangle() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let through = |x: f64, y: f64| segment_crosses_triangle(DVec3::new(x, y, 1.0), DVec3::new(x, y, -1.0), t);
        assert!(through(0.25, 0.25));
        assert!(through(0.5, 0.5)); // on the hypotenuse
        assert!(through(0.0, 0.0)); // through a corner
        assert!(!through(0.75, 0.75));
        // Touching the plane at an end is not crossing it.
        assert!(!segment_crosses_triangle(
            DVec3::new(0.2, 0.2, 0.0),
            DVec3::new(0.2, 0.2, 1.0),
            t
        ));
        // Zero-area triangles are never crossed.
        let flat = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert!(!segment_crosses_triangle(
            DVec3::new(0.5, 0.0, 1.0),
            DVec3::new(0.5, 0.0, -1.0),
            flat
        ));
    }
}
