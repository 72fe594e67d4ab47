//! Measures of closed planar polygons given in 2D: area, perimeter, convex hull (the
//! "tape measure" girth), containment, the distance to an edge.

use glam::DVec2;

/// Signed area (counter-clockwise positive), shoelace formula.
pub fn signed_area(points: &[DVec2]) -> f64 {
    let n = points.len();
    (0..n).map(|i| points[i].perp_dot(points[(i + 1) % n])).sum::<f64>() * 0.5
}

/// Area centroid; the vertex mean for a polygon of (near) zero area.
pub fn centroid(points: &[DVec2]) -> DVec2 {
    let n = points.len();
    let area = signed_area(points);
    if area.abs() <= f64::EPSILON * perimeter(points).powi(2) || n < 3 {
        return points.iter().copied().sum::<DVec2>() / n.max(1) as f64;
    }
    let mut c = DVec2::ZERO;
    for i in 0..n {
        let (p, q) = (points[i], points[(i + 1) % n]);
        c += (p + q) * p.perp_dot(q);
    }
    c / (6.0 * area)
}

/// Closed perimeter (input units, m in drape).
pub fn perimeter(points: &[DVec2]) -> f64 {
    let n = points.len();
    (0..n).map(|i| points[i].distance(points[(i + 1) % n])).sum()
}

/// Convex hull, counter-clockwise, by Andrew's monotone chain (collinear points dropped).
pub fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut pts: Vec<DVec2> = points.to_vec();
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::with_capacity(pts.len() * 2);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// Perimeter of the convex hull (input units): what a tape measure laid around the section
/// reads.
pub fn hull_perimeter(points: &[DVec2]) -> f64 {
    perimeter(&convex_hull(points))
}

/// Squared distance from `p` to the segment `a..b` (its square root is the distance, bit
/// for bit: the square root is monotone and correctly rounded).
pub fn segment_distance2(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let len2 = e.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(e) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + e * t)).length_squared()
}

/// Whether `p` lies inside the closed polygon (crossing-number rule).
pub fn contains(points: &[DVec2], p: DVec2) -> bool {
    let n = points.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if x > p.x {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_square_measures() {
        let sq = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        assert_eq!(signed_area(&sq), 1.0);
        assert_eq!(perimeter(&sq), 4.0);
        assert_eq!(centroid(&sq), DVec2::new(0.5, 0.5));
        assert!(contains(&sq, DVec2::new(0.3, 0.7)) && !contains(&sq, DVec2::new(1.3, 0.7)));
        // A notch does not change the hull.
        let notched = [sq[0], DVec2::new(0.5, 0.4), sq[1], sq[2], sq[3]];
        assert!((hull_perimeter(&notched) - 4.0).abs() < 1e-15);
    }
}
