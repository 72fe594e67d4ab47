//! Closest point on a triangle, with the feature it lies on (Ericson, *Real-Time Collision
//! Detection*, 5.1.5: Voronoi regions of the corners, then of the edges, then the face).
//! Zero-area triangles are handled as their three edges, so no division by zero occurs.

use glam::DVec3;

/// Which part of a triangle a closest point lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Feature {
    /// Strictly inside the face.
    Face,
    /// On edge `k` (corner `k` to corner `k + 1`).
    Edge(u8),
    /// At corner `k`.
    Vertex(u8),
}

/// The closest point of the segment `ab` to `p` and its parameter in `[0, 1]`.
pub fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> (DVec3, f64) {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 <= 0.0 {
        return (a, 0.0);
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    (a + ab * t, t)
}

fn on_edge(t: f64, k: u8) -> Feature {
    if t <= 0.0 {
        Feature::Vertex(k)
    } else if t >= 1.0 {
        Feature::Vertex((k + 1) % 3)
    } else {
        Feature::Edge(k)
    }
}

/// The point of triangle `[a, b, c]` nearest to `p`, and its feature.
pub fn closest_on_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> (DVec3, Feature) {
    let ab = b - a;
    let ac = c - a;
    let n = ab.cross(ac);
    let scale = ab.length_squared().max(ac.length_squared());
    if n.length_squared() <= 1e-24 * scale * scale {
        // Degenerate: the nearest of the three edges.
        let corners = [a, b, c];
        let mut best = (a, Feature::Vertex(0), f64::INFINITY);
        for k in 0..3u8 {
            let (q, t) = closest_on_segment(p, corners[k as usize], corners[(k as usize + 1) % 3]);
            let d = q.distance_squared(p);
            if d < best.2 {
                best = (q, on_edge(t, k), d);
            }
        }
        return (best.0, best.1);
    }
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, Feature::Vertex(0));
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, Feature::Vertex(1));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, Feature::Edge(0));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, Feature::Vertex(2));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, Feature::Edge(2));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, Feature::Edge(1));
    }
    let denom = 1.0 / (va + vb + vc);
    let v = vb * denom;
    let w = vc * denom;
    (a + ab * v + ac * w, Feature::Face)
}

/// The distance between the segments `p1 q1` and `p2 q2` (Ericson, *Real-Time Collision
/// Detection*, 5.1.9: the closest points of the two lines, clamped to the segments in turn);
/// a segment of zero length is its point.
pub fn segments_distance(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> f64 {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    let (s, t) = if a <= f64::MIN_POSITIVE && e <= f64::MIN_POSITIVE {
        (0.0, 0.0)
    } else if a <= f64::MIN_POSITIVE {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e <= f64::MIN_POSITIVE {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let s = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t = (b * s + f) / e;
            if t < 0.0 {
                ((-c / a).clamp(0.0, 1.0), 0.0)
            } else if t > 1.0 {
                (((b - c) / a).clamp(0.0, 1.0), 1.0)
            } else {
                (s, t)
            }
        }
    };
    (p1 + d1 * s).distance(p2 + d2 * t)
}

/// The distance between two triangles that do not intersect: the least of each one's
/// corners to the other and of their edges to each other (two disjoint triangles are
/// nearest at a corner of one or on an edge of each).
pub fn triangles_distance(a: [DVec3; 3], b: [DVec3; 3]) -> f64 {
    let mut best = f64::INFINITY;
    for (from, to) in [(a, b), (b, a)] {
        for &p in &from {
            best = best.min(closest_on_triangle(p, to).0.distance(p));
        }
    }
    for i in 0..3 {
        for j in 0..3 {
            best = best.min(segments_distance(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: [DVec3; 3] = [DVec3::ZERO, DVec3::X, DVec3::Y];

    #[test]
    fn regions_of_a_right_triangle() {
        let (q, f) = closest_on_triangle(DVec3::new(0.2, 0.2, 1.0), T);
        assert!(q.distance(DVec3::new(0.2, 0.2, 0.0)) < 1e-15);
        assert_eq!(f, Feature::Face);
        let (q, f) = closest_on_triangle(DVec3::new(-1.0, -1.0, 0.5), T);
        assert_eq!((q, f), (DVec3::ZERO, Feature::Vertex(0)));
        let (q, f) = closest_on_triangle(DVec3::new(0.5, -1.0, 0.0), T);
        assert_eq!((q, f), (DVec3::new(0.5, 0.0, 0.0), Feature::Edge(0)));
        let (q, f) = closest_on_triangle(DVec3::new(1.0, 1.0, 0.0), T);
        assert!(q.distance(DVec3::new(0.5, 0.5, 0.0)) < 1e-15);
        assert_eq!(f, Feature::Edge(1));
        let (_, f) = closest_on_triangle(DVec3::new(-1.0, 0.5, 0.0), T);
        assert_eq!(f, Feature::Edge(2));
    }

    #[test]
    fn brute_force_agrees_on_random_points() {
        // Dense barycentric sampling as an independent nearest point.
        let tri = [
            DVec3::new(0.1, -0.3, 0.2),
            DVec3::new(1.2, 0.4, -0.1),
            DVec3::new(-0.2, 0.9, 0.5),
        ];
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 3.0 - 1.5
        };
        for _ in 0..50 {
            let p = DVec3::new(rnd(), rnd(), rnd());
            let (q, _) = closest_on_triangle(p, tri);
            let n = 200;
            let mut best = f64::INFINITY;
            for i in 0..=n {
                for j in 0..=(n - i) {
                    let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                    let s = tri[0] + (tri[1] - tri[0]) * u + (tri[2] - tri[0]) * v;
                    best = best.min(s.distance(p));
                }
            }
            assert!(q.distance(p) <= best + 1e-12);
            assert!(q.distance(p) > best - 1e-2);
        }
    }

    #[test]
    fn zero_area_triangles_give_the_nearest_edge_point() {
        let flat = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        let (q, f) = closest_on_triangle(DVec3::new(1.5, 1.0, 0.0), flat);
        assert!(q.distance(DVec3::new(1.5, 0.0, 0.0)) < 1e-15);
        assert!(matches!(f, Feature::Edge(_)));
        let point = [DVec3::ONE; 3];
        let (q, _) = closest_on_triangle(DVec3::ZERO, point);
        assert_eq!(q, DVec3::ONE);
    }
}
