//! The section scan the landmark rules share: sections of the body at chosen heights,
//! bisection between two heights, and the profile helpers (extremes, corners, the front
//! profile at the mid-plane).

use glam::DVec2;

use crate::body::BodyMesh;
use crate::body::profile::{MeasuredLoop, outer_loops};
use crate::convergence::Bisection;

/// The landmark heights found by bisection count as converged once known to this fraction
/// of the body's height (a micrometre per metre).
const LANDMARK_TOLERANCE: f64 = 1e-6;

/// The item whose `key` is nearest `y`.
pub(super) fn nearest<T>(items: &[T], y: f64, key: impl Fn(&T) -> f64) -> Option<&T> {
    items
        .iter()
        .min_by(|a, b| (key(a) - y).abs().total_cmp(&(key(b) - y).abs()))
}

/// Horizontal sections of the body at chosen heights.
pub(super) struct Scan<'a> {
    pub(super) body: &'a BodyMesh,
    /// The body's lowest `y`, m.
    pub(super) floor: f64,
    /// Its height, m.
    pub(super) height: f64,
}

impl Scan<'_> {
    /// The outer loops of the section at height `y`.
    pub(super) fn loops(&self, y: f64) -> Vec<MeasuredLoop> {
        outer_loops(self.body, y, self.height)
    }

    /// The height of level `k` of `levels` equal slabs (their middles).
    pub(super) fn level(&self, k: usize, levels: usize) -> f64 {
        self.floor + self.height * (k as f64 + 0.5) / levels as f64
    }

    /// Largest `t` in `[lo, hi]` where `separate(t)` still holds, given it holds at `lo`
    /// and not at `hi`.
    pub(super) fn bisect(&self, lo: f64, hi: f64, steps: usize, separate: impl Fn(&[MeasuredLoop]) -> bool) -> f64 {
        let (lo, hi) = Bisection {
            name: "landmarks.bisection",
            steps,
            tolerance: LANDMARK_TOLERANCE * self.height,
            stop_at_tolerance: false,
        }
        .run(lo, hi, |mid| separate(&self.loops(mid)));
        0.5 * (lo + hi)
    }
}

/// The `z` of the front-most crossing of a loop with the vertical plane `x = x0`.
pub(super) fn front_z_at(l: &MeasuredLoop, x0: f64) -> Option<f64> {
    let n = l.flat.len();
    (0..n)
        .filter_map(|i| {
            let (a, b) = (l.flat[i], l.flat[(i + 1) % n]);
            ((a.x - x0) * (b.x - x0) <= 0.0 && a.x != b.x).then(|| a.y + (x0 - a.x) / (b.x - a.x) * (b.y - a.y))
        })
        .max_by(f64::total_cmp)
}

/// Index of the curve point farthest from the chord between its ends on the side of `side`
/// (a direction in the curve's plane); `None` for fewer than 3 points.
pub(super) fn corner(curve: &[DVec2], side: DVec2) -> Option<usize> {
    let (first, last) = (*curve.first()?, *curve.last()?);
    let d = last - first;
    let mut normal = DVec2::new(d.y, -d.x).normalize_or_zero();
    if normal.dot(side) < 0.0 {
        normal = -normal;
    }
    (1..curve.len().saturating_sub(1)).max_by(|&a, &b| {
        (curve[a] - first)
            .dot(normal)
            .total_cmp(&(curve[b] - first).dot(normal))
    })
}

/// The index in `range` of the largest (or smallest) value of `values` (`(y, value)` pairs).
pub(super) fn arg_extreme(values: &[(f64, f64)], range: std::ops::Range<usize>, larger: bool) -> Option<usize> {
    range.filter(|&i| i < values.len()).max_by(|&a, &b| {
        let o = values[a].1.total_cmp(&values[b].1);
        if larger { o } else { o.reverse() }
    })
}
