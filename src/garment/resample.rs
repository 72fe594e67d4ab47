//! Ring resampling (\[frame\] section 2.2, step 2): the ring's anchor points (its 4
//! extremes) split it into 4 arcs, each resampled with equal chords between consecutive
//! points; an open ring is split into 2 arcs about its middle point (by length).

use glam::DVec3;

use crate::convergence::Bisection;
use thiserror::Error;

/// Why a ring cannot be resampled.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ResampleError {
    /// Anchors must be distinct indices in ring order.
    #[error("anchors {0:?} are not distinct and in ring order")]
    BadAnchors(Vec<usize>),
    /// Nothing to resample.
    #[error("a ring needs at least 2 points and 1 sample per arc")]
    TooSmall,
}

/// Marches along the polyline from its start in steps of chord `c`; returns the points
/// reached (start included) after up to `count` steps, stopping early at the end.
fn march(polyline: &[DVec3], c: f64, count: usize) -> Vec<DVec3> {
    let mut out = vec![polyline[0]];
    let (mut cur, mut segment) = (polyline[0], 0usize);
    let mut from = polyline[0];
    while out.len() <= count {
        // The first point after `cur` at distance `c` from it.
        let mut found = None;
        while segment + 1 < polyline.len() {
            let (a, b) = (from, polyline[segment + 1]);
            if b.distance(cur) >= c {
                let d = b - a;
                let (qa, qb, qc) = (d.length_squared(), (a - cur).dot(d), (a - cur).length_squared() - c * c);
                let t = if qa > 0.0 {
                    ((-qb + (qb * qb - qa * qc).max(0.0).sqrt()) / qa).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                found = Some(a + d * t);
                break;
            }
            segment += 1;
            from = polyline[segment];
        }
        let Some(next) = found else { break };
        out.push(next);
        cur = next;
        from = next;
    }
    out
}

/// `count` points from the polyline's start (included) to its end (excluded), with equal
/// chords between consecutive points and from the last to the end: the chord is found by
/// bisection (marching with it must land on the end after `count` steps).
fn arc_samples(polyline: &[DVec3], count: usize) -> Vec<DVec3> {
    let (Some(&start), Some(&end)) = (polyline.first(), polyline.last()) else {
        return Vec::new();
    };
    let total: f64 = polyline.windows(2).map(|w| w[0].distance(w[1])).sum();
    if count == 0 || total <= 0.0 {
        return vec![start; count];
    }
    // Residual: chord left from the point after count - 1 steps to the end, minus c. It is
    // positive for small c and not positive at c = total / count.
    let residual = |c: f64| {
        let points = march(polyline, c, count - 1);
        if points.len() < count {
            -1.0
        } else {
            points[count - 1].distance(end) - c
        }
    };
    let (lo, hi) = Bisection {
        name: "garment.resample.bisection",
        steps: 80,
        tolerance: 1e-12 * total,
        stop_at_tolerance: false,
    }
    .run(0.0, total / count as f64, |c| residual(c) > 0.0);
    let mut out = march(polyline, 0.5 * (lo + hi), count - 1);
    out.truncate(count);
    out
}

/// Resamples a closed ring: `per_arc` points on each arc between consecutive anchors
/// (indices into `ring`, in ring order, cyclically). The result starts at the first anchor
/// and holds every anchor exactly, at positions `0, per_arc, 2 per_arc, ...`.
pub fn resample_closed(ring: &[DVec3], anchors: &[usize], per_arc: usize) -> Result<Vec<DVec3>, ResampleError> {
    if ring.len() < 2 || per_arc == 0 || anchors.is_empty() {
        return Err(ResampleError::TooSmall);
    }
    let n = ring.len();
    // Anchors must advance around the ring exactly once.
    let steps: Vec<usize> = (0..anchors.len())
        .map(|k| (anchors[(k + 1) % anchors.len()] + n - anchors[k]) % n)
        .collect();
    let advances_once = anchors.len() == 1 || (steps.iter().all(|&s| s > 0) && steps.iter().sum::<usize>() == n);
    if anchors.iter().any(|&a| a >= n) || !advances_once {
        return Err(ResampleError::BadAnchors(anchors.to_vec()));
    }
    let mut out = Vec::with_capacity(anchors.len() * per_arc);
    for (k, &start) in anchors.iter().enumerate() {
        let step = if anchors.len() == 1 { n } else { steps[k] };
        let arc: Vec<DVec3> = (0..=step).map(|j| ring[(start + j) % n]).collect();
        out.extend(arc_samples(&arc, per_arc));
    }
    Ok(out)
}

/// Resamples an open curve: its middle point (half its length) splits it into two arcs of
/// `per_half` samples each; both ends and the middle are kept (`2 per_half + 1` points).
pub fn resample_open(curve: &[DVec3], per_half: usize) -> Result<Vec<DVec3>, ResampleError> {
    if curve.len() < 2 || per_half == 0 {
        return Err(ResampleError::TooSmall);
    }
    let lengths: Vec<f64> = curve.windows(2).map(|w| w[0].distance(w[1])).collect();
    let half = 0.5 * lengths.iter().sum::<f64>();
    // Split the polyline at its middle point.
    let (mut walked, mut first) = (0.0, vec![curve[0]]);
    let mut second = Vec::new();
    for (i, len) in lengths.iter().enumerate() {
        if second.is_empty() && walked + len >= half {
            let t = if *len > 0.0 { (half - walked) / len } else { 0.0 };
            let middle = curve[i].lerp(curve[i + 1], t);
            first.push(middle);
            second.push(middle);
        } else if second.is_empty() {
            first.push(curve[i + 1]);
        }
        if !second.is_empty() {
            second.push(curve[i + 1]);
        }
        walked += len;
    }
    Ok(two_arcs(&first, &second, per_half))
}

fn two_arcs(first: &[DVec3], second: &[DVec3], per_half: usize) -> Vec<DVec3> {
    let mut out = arc_samples(first, per_half);
    out.extend(arc_samples(second, per_half));
    out.extend(second.last().copied());
    out
}

/// Resamples an open curve split at the given point (its apex: the crotch curve's lowest
/// point, a strap's highest) rather than at half its length; `2 per_half + 1` points, the
/// apex at position `per_half`.
pub fn resample_open_at(curve: &[DVec3], apex: usize, per_half: usize) -> Result<Vec<DVec3>, ResampleError> {
    if curve.len() < 3 || per_half == 0 {
        return Err(ResampleError::TooSmall);
    }
    if apex == 0 || apex + 1 >= curve.len() {
        return Err(ResampleError::BadAnchors(vec![apex]));
    }
    Ok(two_arcs(&curve[..=apex], &curve[apex..], per_half))
}
