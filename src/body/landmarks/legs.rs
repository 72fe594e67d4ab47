//! The leg rules: the two legs tracked up from the feet until one section holds both (the
//! crotch, refined by bisection), and the ankle and knee from the legs' girth profile.

use super::LandmarkError;
use super::scan::{Scan, arg_extreme};
use crate::body::profile::{MeasuredLoop, loop_at};

/// The legs as scanned: one `(y, left loop, right loop)` per level from the feet, and the
/// first level where one loop holds both legs `(y, index of that loop, all loops there)`.
pub(super) struct LegScan {
    pub(super) legs: Vec<(f64, MeasuredLoop, MeasuredLoop)>,
    pub(super) joined: (f64, usize, Vec<MeasuredLoop>),
}

impl LegScan {
    /// The mean tape girth of the two legs per level, `(y, girth)`, m.
    pub(super) fn girths(&self) -> Vec<(f64, f64)> {
        self.legs
            .iter()
            .map(|(y, l, r)| (*y, 0.5 * (l.tape_girth + r.tape_girth)))
            .collect()
    }
}

/// Tracks the legs up from the first level (in the lowest quarter) with a loop on each side
/// of the mid-plane: each level's leg is the loop holding the previous level's centroid.
pub(super) fn scan_legs(scan: &Scan<'_>, levels: usize, mid_x: f64) -> Result<LegScan, LandmarkError> {
    let mut k = 0;
    let mut legs: Vec<(f64, MeasuredLoop, MeasuredLoop)> = Vec::new();
    while k < levels / 4 {
        let y = scan.level(k, levels);
        let loops = scan.loops(y);
        let largest = |left: bool| {
            loops
                .iter()
                .filter(|l| (l.centroid.x > mid_x) == left)
                .max_by(|a, b| a.area.total_cmp(&b.area))
                .cloned()
        };
        if let (Some(l), Some(r)) = (largest(true), largest(false)) {
            legs.push((y, l, r));
            break;
        }
        k += 1;
    }
    if legs.is_empty() {
        return Err(LandmarkError::NoLegs);
    }
    let mut joined_at = None;
    for k in k + 1..levels {
        let y = scan.level(k, levels);
        let loops = scan.loops(y);
        let Some((_, pl, pr)) = legs.last() else {
            break;
        };
        let (Some(li), Some(ri)) = (loop_at(&loops, pl.centroid), loop_at(&loops, pr.centroid)) else {
            continue;
        };
        if li == ri {
            joined_at = Some((y, li, loops));
            break;
        }
        legs.push((y, loops[li].clone(), loops[ri].clone()));
    }
    let joined = joined_at.ok_or(LandmarkError::LegsNeverJoin)?;
    Ok(LegScan { legs, joined })
}

/// **Crotch**: the height where one loop first holds both legs' last centroids, by
/// bisection between the last level with the legs apart and the first with them joined.
pub(super) fn crotch(scan: &Scan<'_>, legs: &LegScan, steps: usize) -> Result<f64, LandmarkError> {
    let (last_leg_y, last_left, last_right) = legs.legs.last().ok_or(LandmarkError::NoLegs)?;
    let (cl, cr) = (last_left.centroid, last_right.centroid);
    Ok(scan.bisect(*last_leg_y, legs.joined.0, steps, |loops| {
        let (a, b) = (
            loops.iter().position(|l| l.contains(cl)),
            loops.iter().position(|l| l.contains(cr)),
        );
        !(a.is_some() && a == b)
    }))
}

/// **Ankle**: the level of the narrowest leg above the foot's widest (the sole's slices are
/// small too), within the lower 70% of the legs.
pub(super) fn ankle(girth: &[(f64, f64)]) -> usize {
    let n_legs = girth.len();
    let foot_i = arg_extreme(girth, 0..(n_legs / 4).max(1), true).unwrap_or(0);
    arg_extreme(girth, foot_i..(n_legs * 7 / 10).max(foot_i + 1), false).unwrap_or(foot_i)
}

/// **Knee**: the level of the narrowest leg between the calf (the first local girth maximum
/// above the ankle, over a window of 1/15 of the leg) and where the thigh grows past the
/// calf. A leg without a calf bulge falls back on the usual proportion, 45% from ankle to
/// crotch.
pub(super) fn knee(girth: &[(f64, f64)], ankle_i: usize, crotch_y: f64) -> usize {
    let n_legs = girth.len();
    let g: Vec<f64> = girth.iter().map(|e| e.1).collect();
    let window = (n_legs / 15).max(2);
    let calf = (ankle_i + 1..n_legs)
        .find(|&i| i >= window && i + window < n_legs && (i - window..=i + window).all(|j| g[j] <= g[i]));
    calf.and_then(|c| {
        let end = (c + 1..n_legs).find(|&j| g[j] > g[c]).unwrap_or(n_legs);
        arg_extreme(girth, c + 1..end, false)
    })
    .unwrap_or_else(|| {
        let target = girth[ankle_i].0 + 0.45 * (crotch_y - girth[ankle_i].0);
        girth.partition_point(|e| e.0 < target).min(n_legs - 1)
    })
}
