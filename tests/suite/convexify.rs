//! Ring convexification: a convex ring that keeps the 4 extremes and is exactly the convex
//! hull's vertices in ring order, for star-shaped and non-star-shaped rings; on star-shaped
//! rings the paper's turn-sign scan alone reaches it (no fallback to the library's hull).

use drape::garment::{convexify, extremes};
use glam::DVec2;
use proptest::prelude::*;

/// The convex hull's vertices by gift wrapping (Jarvis 1973), written here independently
/// of the library's monotone chain: from the lowest-leftmost point, each next vertex is the
/// point with every other point on its left (the farthest one among collinear candidates).
fn gift_wrap(points: &[DVec2]) -> Vec<DVec2> {
    let start = (0..points.len())
        .min_by(|&a, &b| {
            points[a]
                .x
                .total_cmp(&points[b].x)
                .then(points[a].y.total_cmp(&points[b].y))
        })
        .expect("points");
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull = vec![points[start]];
    let mut current = start;
    loop {
        let mut next = (current + 1) % points.len();
        for k in 0..points.len() {
            let turn = cross(points[current], points[next], points[k]);
            let farther = points[current].distance(points[k]) > points[current].distance(points[next]);
            if turn < 0.0 || (turn == 0.0 && farther) {
                next = k;
            }
        }
        if next == start || hull.len() > points.len() {
            break;
        }
        hull.push(points[next]);
        current = next;
    }
    hull
}

/// The shoelace area of a closed polygon, here.
fn area(p: &[DVec2]) -> f64 {
    0.5 * (0..p.len()).map(|k| p[k].perp_dot(p[(k + 1) % p.len()])).sum::<f64>()
}

/// A star-shaped ring around the origin: points in increasing angle with every angular gap
/// under a half turn (so the origin is inside and sees the whole ring), radii 0.4-1.6.
fn star_ring() -> impl Strategy<Value = Vec<DVec2>> {
    (8usize..80).prop_flat_map(|n| {
        prop::collection::vec((0.0f64..0.9, 0.4f64..1.6), n).prop_map(move |raw| {
            raw.iter()
                .enumerate()
                .map(|(k, (jitter, r))| {
                    let a = (k as f64 + jitter) / n as f64 * std::f64::consts::TAU;
                    DVec2::new(r * a.cos(), r * a.sin())
                })
                .collect()
        })
    })
}

/// A star-shaped ring (radius against sorted angles), then bent by `y += bend * x^2`,
/// which for large `bend` makes it banana-shaped and not star-shaped.
fn ring() -> impl Strategy<Value = Vec<DVec2>> {
    (8usize..80, 0.0f64..3.0).prop_flat_map(|(n, bend)| {
        (prop::collection::vec((0.0f64..1.0, 0.4f64..1.6), n), Just(bend)).prop_map(move |(raw, bend)| {
            let mut samples: Vec<(f64, f64)> = raw.into_iter().map(|(a, r)| (a * std::f64::consts::TAU, r)).collect();
            samples.sort_by(|a, b| a.0.total_cmp(&b.0));
            samples.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-6);
            samples
                .into_iter()
                .map(|(a, r)| {
                    let (x, y) = (r * a.cos(), r * a.sin());
                    DVec2::new(x, y + bend * x * x)
                })
                .collect()
        })
    })
}

/// Whether the closed polygon has no two non-adjacent edges that touch (brute force).
fn is_simple(p: &[DVec2]) -> bool {
    let n = p.len();
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    for i in 0..n {
        for j in i + 1..n {
            if j == i + 1 || (i == 0 && j == n - 1) {
                continue;
            }
            let (a, b, c, d) = (p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]);
            let (d1, d2) = (cross(a, b, c), cross(a, b, d));
            let (d3, d4) = (cross(c, d, a), cross(c, d, b));
            if d1 * d2 <= 0.0 && d3 * d4 <= 0.0 {
                return false;
            }
        }
    }
    true
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(super::common::proptest_cases(400)))]

    #[test]
    fn convexify_gives_the_hull_in_ring_order_keeping_the_extremes(points in ring()) {
        prop_assume!(points.len() >= 4);
        let (kept, _report) = convexify(&points);
        // A simple ring keeps its order (a self-crossing one has none to keep).
        if is_simple(&points) {
            prop_assert!(kept.windows(2).all(|w| w[0] < w[1]), "ring order lost: {:?}", kept);
        }
        // The 4 extremes survive.
        for e in extremes(&points) {
            prop_assert!(kept.contains(&e), "extreme {} lost", e);
        }
        // Convex: every turn has the orientation's sign (or is zero at a tied extreme).
        let m = kept.len();
        let pts: Vec<DVec2> = kept.iter().map(|&i| points[i]).collect();
        let orientation = area(&pts).signum();
        for k in 0..m {
            let (a, b, c) = (pts[(k + m - 1) % m], pts[k], pts[(k + 1) % m]);
            prop_assert!((b - a).perp_dot(c - b) * orientation >= -1e-12, "reflex turn at kept point {}", kept[k]);
        }
        // Exactly the convex hull's vertices (the test's own gift-wrapping hull).
        let hull = gift_wrap(&points);
        prop_assert!(hull.iter().all(|h| pts.contains(h)), "a hull vertex was deleted");
        prop_assert!(pts.iter().all(|p| hull.contains(p) || extremes(&points).iter().any(|&e| points[e] == *p)), "a point off the hull was kept");
        prop_assert!((area(&pts).abs() - area(&hull).abs()).abs() < 1e-12);
    }

    /// On a star-shaped ring seen from inside, deleting the points whose turn disagrees is
    /// Graham's scan in angular order: the paper's scan alone must reach the hull, without
    /// the fallback to the library's hull.
    #[test]
    fn the_scan_alone_convexifies_star_shaped_rings(points in star_ring()) {
        let (kept, report) = convexify(&points);
        prop_assert!(!report.fallback, "fell back on a star-shaped ring: {report:?}");
        let pts: Vec<DVec2> = kept.iter().map(|&i| points[i]).collect();
        let hull = gift_wrap(&points);
        prop_assert_eq!(pts.len(), hull.len());
        prop_assert!(hull.iter().all(|h| pts.contains(h)));
        prop_assert!(kept.windows(2).all(|w| w[0] < w[1]), "ring order lost");
    }
}

#[test]
fn a_star_shaped_notch_is_removed_by_the_scan_itself() {
    // A square with a notch in its top edge: one pass deletes the notch, no fallback.
    let pts = [
        (0.0, 0.0),
        (1.0, 0.0),
        (1.0, 1.0),
        (0.6, 1.0),
        (0.5, 0.7),
        (0.4, 1.0),
        (0.0, 1.0),
    ]
    .map(|(x, y)| DVec2::new(x, y));
    let (kept, report) = convexify(&pts);
    assert_eq!(kept, vec![0, 1, 2, 6]);
    assert!(!report.fallback);
    assert_eq!(report.removed, 3);
}

#[test]
fn a_ring_that_winds_twice_round_its_middle_gets_its_hull() {
    // Six points all on their hull, in a ring order that goes round twice: every turn has
    // the same sign, yet the ring crosses itself. Its convexification is the hull, whose
    // area the test's own gift wrapping gives.
    let pts = [
        (0.4, 0.45049457771160073),
        (-1.2343235602669267, 3.5377749165655707),
        (-0.9612376693028273, 2.002217057951647),
        (-1.289522422278717, 3.8679419074008865),
        (-1.0161705728142916, 2.2559538251649336),
        (-0.022563322595030185, -0.9780581135894246),
    ]
    .map(|(x, y)| DVec2::new(x, y));
    assert!(!is_simple(&pts));
    let (kept, report) = convexify(&pts);
    let kept: Vec<DVec2> = kept.iter().map(|&i| pts[i]).collect();
    assert!(is_simple(&kept), "the result crosses itself: {kept:?}");
    assert!(report.fallback);
    let hull = gift_wrap(&pts);
    assert!((area(&kept).abs() - area(&hull).abs()).abs() < 1e-12);
}

#[test]
fn a_star_shaped_ring_whose_lowest_point_is_also_its_rightmost_is_scanned_down_to_a_triangle() {
    // Point 6 is both the rightmost and the lowest: three distinct extremes, and a hull of
    // three points. The scan must go below four points to reach it.
    let pts = [
        (0.4, 0.0),
        (0.40719119050670044, 1.249102073487793),
        (2.4492935982947065e-17, 0.4),
        (-0.282842712474619, 0.28284271247461906),
        (-1.2704941506310674, -0.6121319417585702),
        (-0.28284271247461906, -0.282842712474619),
        (0.8963471374102787, -1.159117626274666),
        (0.3073867594776446, -0.25595581669075756),
    ]
    .map(|(x, y)| DVec2::new(x, y));
    let (kept, report) = convexify(&pts);
    assert!(!report.fallback, "{report:?}");
    let hull = gift_wrap(&pts);
    assert_eq!(hull.len(), 3);
    assert_eq!(kept.len(), 3);
    assert!(kept.iter().all(|&i| hull.contains(&pts[i])));
}
