//! How far a flattened panel is from its 3D shape: edge-length strain, area ratio and angle
//! change per triangle, flipped triangles, and the boundary crossing itself.

use glam::{DVec2, DVec3};
use serde::Serialize;

use super::flatten::signed_area;

/// The distortion of one flattened panel.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Distortion {
    /// Largest `|l_2d - l_3d| / l_3d` over the panel's edges (a fraction: 0.01 is 1%).
    pub max_strain: f64,
    /// Mean of the same over the edges.
    pub mean_strain: f64,
    /// Smallest and largest triangle area ratio 2D / 3D.
    pub area_ratio: [f64; 2],
    /// Largest change of a triangle's angle, degrees.
    pub max_angle_deg: f64,
    /// Mean change of the triangles' angles, degrees.
    pub mean_angle_deg: f64,
    /// Triangles whose 2D image is not counter-clockwise (area <= 0).
    pub flipped: usize,
    /// Pairs of boundary segments that cross (the panel overlapping itself).
    pub overlaps: usize,
}

/// Strain of every edge of a panel: `(edge, |l_2d - l_3d| / l_3d)`, edges `a < b` sorted.
pub fn edge_strains(positions: &[DVec3], triangles: &[[u32; 3]], uv: &[DVec2]) -> Vec<([u32; 2], f64)> {
    let mut edges: Vec<[u32; 2]> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])]))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
        .into_iter()
        .map(|[a, b]| {
            let l3 = positions[a as usize].distance(positions[b as usize]);
            let l2 = uv[a as usize].distance(uv[b as usize]);
            ([a, b], (l2 - l3).abs() / l3)
        })
        .collect()
}

/// Measures a flattened panel whose boundary loop is `boundary`.
pub fn measure(positions: &[DVec3], triangles: &[[u32; 3]], uv: &[DVec2], boundary: &[u32]) -> Distortion {
    let strains = edge_strains(positions, triangles, uv);
    let max_strain = strains.iter().map(|s| s.1).fold(0.0, f64::max);
    let mean_strain = strains.iter().map(|s| s.1).sum::<f64>() / strains.len().max(1) as f64;
    let mut area_ratio = [f64::INFINITY, f64::NEG_INFINITY];
    let (mut max_angle, mut sum_angle) = (0.0_f64, 0.0);
    let mut flipped = 0;
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let [p, q, r] = t.map(|i| uv[i as usize]);
        let a2 = signed_area(p, q, r);
        if a2.is_nan() || a2 <= 0.0 {
            flipped += 1;
        }
        let a3 = 0.5 * (b - a).cross(c - a).length();
        let ratio = a2 / a3;
        area_ratio = [area_ratio[0].min(ratio), area_ratio[1].max(ratio)];
        let angles3 = [
            (b - a).angle_between(c - a),
            (c - b).angle_between(a - b),
            (a - c).angle_between(b - c),
        ];
        let angles2 = [
            (q - p).angle_to(r - p).abs(),
            (r - q).angle_to(p - q).abs(),
            (p - r).angle_to(q - r).abs(),
        ];
        for (x, y) in angles3.iter().zip(&angles2) {
            let d = (x - y).abs().to_degrees();
            max_angle = max_angle.max(d);
            sum_angle += d;
        }
    }
    Distortion {
        max_strain,
        mean_strain,
        area_ratio,
        max_angle_deg: max_angle,
        mean_angle_deg: sum_angle / (3 * triangles.len()).max(1) as f64,
        flipped,
        overlaps: boundary_crossings(uv, boundary),
    }
}

/// Pairs of non-adjacent segments of a closed loop that cross or touch (boxes swept along
/// `x`, the exact orientation test deciding).
pub fn boundary_crossings(uv: &[DVec2], boundary: &[u32]) -> usize {
    let n = boundary.len();
    if n < 4 {
        return 0;
    }
    let seg = |k: usize| (uv[boundary[k] as usize], uv[boundary[(k + 1) % n] as usize]);
    let mut order: Vec<usize> = (0..n).collect();
    let lo = |k: usize| {
        let (a, b) = seg(k);
        a.x.min(b.x)
    };
    order.sort_by(|&i, &j| lo(i).total_cmp(&lo(j)).then(i.cmp(&j)));
    let mut count = 0;
    for (x, &i) in order.iter().enumerate() {
        let (a, b) = seg(i);
        let hi = a.x.max(b.x);
        for &j in &order[x + 1..] {
            if lo(j) > hi {
                break;
            }
            let adjacent = (i + 1) % n == j || (j + 1) % n == i;
            if !adjacent && segments_cross(a, b, seg(j).0, seg(j).1) {
                count += 1;
            }
        }
    }
    count
}

/// Whether two segments share a point (exact orientation predicates).
fn segments_cross(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let o = |p: DVec2, q: DVec2, r: DVec2| {
        robust::orient2d(
            robust::Coord { x: p.x, y: p.y },
            robust::Coord { x: q.x, y: q.y },
            robust::Coord { x: r.x, y: r.y },
        )
    };
    let (d1, d2, d3, d4) = (o(c, d, a), o(c, d, b), o(a, b, c), o(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    let on = |p: DVec2, q: DVec2, r: DVec2| {
        r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
    };
    (d1 == 0.0 && on(c, d, a)) || (d2 == 0.0 && on(c, d, b)) || (d3 == 0.0 && on(a, b, c)) || (d4 == 0.0 && on(a, b, d))
}
