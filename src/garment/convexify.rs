//! Ring convexification (\[frame\] section 2.2, step 1).
//!
//! The paper: find the ring's 4 extreme points (front, left, back, right in the plane's
//! frame), take the ring's orientation from three of them, then delete every point whose
//! turn disagrees with that orientation, and repeat until nothing changes. The extremes are
//! never deleted. That scan (Sklansky's) is fast but can fail on some rings that are not
//! star-shaped; the result is therefore checked against the convex hull, and where they
//! differ the hull's points, in ring order, are used instead ([`ConvexifyReport::fallback`]).

use glam::DVec2;

use crate::geom::polygon;

/// What convexification did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct ConvexifyReport {
    /// Points deleted.
    pub removed: usize,
    /// Deletion passes (the last one deletes nothing).
    pub passes: usize,
    /// The turn-sign scan did not reach the convex hull; the hull was used.
    pub fallback: bool,
}

/// Indices of the extreme points `[max u, max v, min u, min v]` (front, left, back, right
/// for a horizontal ring in [`crate::geom::Plane::frame`] coordinates); the first index wins ties.
pub fn extremes(points: &[DVec2]) -> [usize; 4] {
    let pick = |key: &dyn Fn(DVec2) -> f64| {
        (0..points.len()).fold(0, |best, i| if key(points[i]) > key(points[best]) { i } else { best })
    };
    [pick(&|p| p.x), pick(&|p| p.y), pick(&|p| -p.x), pick(&|p| -p.y)]
}

fn turn(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - b)
}

/// Convexifies a closed ring; returns the indices kept and a report. For a simple ring the
/// indices are in ring order; a self-crossing ring gets its hull in hull order. Rings of
/// fewer than 4 points are returned whole.
pub fn convexify(points: &[DVec2]) -> (Vec<usize>, ConvexifyReport) {
    let n = points.len();
    let mut report = ConvexifyReport::default();
    if n < 4 {
        return ((0..n).collect(), report);
    }
    let ext = extremes(points);
    let mut ordered = ext;
    ordered.sort_unstable();
    // Two extremes can be one point (the rightmost is also the lowest): the scan may go on
    // until only the distinct extremes are left.
    let distinct = 1 + ordered.windows(2).filter(|w| w[0] != w[1]).count();
    // Orientation from three extremes, taken in ring order.
    let [a, b, c] = [ordered[0], ordered[1], ordered[2]].map(|i| points[i]);
    let orientation = match turn(a, b, c) {
        t if t > 0.0 => 1.0,
        t if t < 0.0 => -1.0,
        _ => polygon::signed_area(points).signum(),
    };
    let mut kept: Vec<usize> = (0..n).collect();
    loop {
        report.passes += 1;
        let m = kept.len();
        let mut next = Vec::with_capacity(m);
        for k in 0..m {
            let i = kept[k];
            // The previous neighbour is the last point kept in this pass.
            let prev = if let Some(&p) = next.last() {
                p
            } else {
                kept[(k + m - 1) % m]
            };
            let after = kept[(k + 1) % m];
            let agrees = turn(points[prev], points[i], points[after]) * orientation > 0.0;
            if agrees || ext.contains(&i) {
                next.push(i);
            }
        }
        let removed = m - next.len();
        report.removed += removed;
        kept = next;
        if removed == 0 || kept.len() <= distinct {
            break;
        }
    }
    // Check against the hull: the kept points must be exactly its vertices (or the extremes).
    let hull = polygon::convex_hull(points);
    let on_hull = |i: usize| hull.contains(&points[i]) || ext.contains(&i);
    let expected: Vec<usize> = (0..n).filter(|&i| on_hull(i)).collect();
    let mut sorted = kept.clone();
    sorted.sort_unstable();
    if sorted != expected || !turns_once_convexly(points, &kept, orientation) {
        // The hull's own cyclic order, turned like the ring and starting at its lowest
        // index: for a simple ring that is ring order; a self-crossing ring has none.
        let mut ordered: Vec<usize> = hull.iter().filter_map(|h| (0..n).find(|&i| points[i] == *h)).collect();
        if orientation < 0.0 {
            ordered.reverse();
        }
        if let Some(first) = (0..ordered.len()).min_by_key(|&k| ordered[k]) {
            ordered.rotate_left(first);
        }
        report.fallback = true;
        report.removed = n - ordered.len();
        kept = ordered;
    }
    (kept, report)
}

/// Whether the closed polygon `points[kept]` turns one way only (with `orientation`'s sign,
/// or not at all) and goes round once: its turning angles sum to one full turn. Turning one
/// way alone is not enough: a ring that winds twice round its middle (a pentagram-like ring)
/// turns one way at every point and still crosses itself.
fn turns_once_convexly(points: &[DVec2], kept: &[usize], orientation: f64) -> bool {
    let m = kept.len();
    let mut total = 0.0;
    for k in 0..m {
        let (a, b, c) = (
            points[kept[(k + m - 1) % m]],
            points[kept[k]],
            points[kept[(k + 1) % m]],
        );
        let (u, v) = (b - a, c - b);
        if u.perp_dot(v) * orientation < 0.0 {
            return false;
        }
        total += u.perp_dot(v).atan2(u.dot(v));
    }
    // One turn is 2 pi; a ring that goes round twice turns 4 pi.
    total.abs() < 3.0 * std::f64::consts::PI
}

/// A convexified ring with its extremes located in it.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexRing {
    /// The kept points, in order.
    pub points: Vec<glam::DVec3>,
    /// Positions of the extremes within `points`, in ring order, duplicates removed.
    pub anchors: Vec<usize>,
    /// What convexification did.
    pub report: ConvexifyReport,
}

/// Convexifies a 3D ring lying in `plane` and locates its extremes: the input of resampling.
pub fn convex_ring(points: &[glam::DVec3], plane: &crate::geom::Plane) -> ConvexRing {
    let flat: Vec<DVec2> = points.iter().map(|p| plane.project(*p)).collect();
    let (kept, report) = convexify(&flat);
    let mut anchors: Vec<usize> = extremes(&flat)
        .iter()
        .filter_map(|e| kept.iter().position(|k| k == e))
        .collect();
    anchors.sort_unstable();
    anchors.dedup();
    ConvexRing {
        points: kept.iter().map(|&i| points[i]).collect(),
        anchors,
        report,
    }
}

/// Convexifies an open arc (a strap over the shoulder, the crotch curve): the same
/// turn-sign deletion, repeated until nothing changes, with both ends and the `apex` kept;
/// the orientation is the turn at the apex seen from the ends. Returns the indices kept,
/// in order, and the apex's position among them.
pub fn convexify_open(points: &[DVec2], apex: usize) -> (Vec<usize>, usize) {
    let n = points.len();
    if n < 3 || apex == 0 || apex + 1 >= n {
        return ((0..n).collect(), apex.min(n.saturating_sub(1)));
    }
    let orientation = turn(points[0], points[apex], points[n - 1]).signum();
    let fixed = [0, apex, n - 1];
    let mut kept: Vec<usize> = (0..n).collect();
    loop {
        let mut next: Vec<usize> = Vec::with_capacity(kept.len());
        for k in 0..kept.len() {
            let i = kept[k];
            let keep = fixed.contains(&i) || {
                let prev = *next.last().unwrap_or(&kept[0]);
                turn(points[prev], points[i], points[kept[k + 1]]) * orientation > 0.0
            };
            if keep {
                next.push(i);
            }
        }
        let removed = kept.len() - next.len();
        kept = next;
        if removed == 0 {
            break;
        }
    }
    let at = kept.iter().position(|&i| i == apex).unwrap_or(0);
    (kept, at)
}
