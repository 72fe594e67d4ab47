//! The torso rules: the torso tracked up from the crotch with the arms beside it (the
//! armpit, where the last arm joins it, refined by bisection; the neck, the first girth
//! minimum above the armpit followed by a 10% rise), then the waist, hip and bust from its
//! girth and back profiles.

use glam::DVec2;

use super::LandmarkError;
use super::scan::{Scan, arg_extreme};
use crate::body::profile::{MeasuredLoop, loop_at};

/// The torso as scanned: one `(y, loop)` per level from where the legs join to the head,
/// the last level each arm (left, right) was seen beside it with the arm's centroid, and
/// the levels (indices into `torso`) of the armpit and the neck.
pub(super) struct TorsoScan {
    pub(super) torso: Vec<(f64, MeasuredLoop)>,
    pub(super) last_arms: [Option<(usize, DVec2)>; 2],
    pub(super) armpit_index: usize,
    pub(super) neck_index: usize,
}

impl TorsoScan {
    /// The tape girth per level, `(y, girth)`, m.
    pub(super) fn girths(&self) -> Vec<(f64, f64)> {
        self.torso.iter().map(|(y, l)| (*y, l.tape_girth)).collect()
    }
}

/// Tracks the torso up from the joined legs' loop. A loop beside the torso of at least 2%
/// of its area is an arm; the **armpit** level is the last one an arm was seen once none has
/// been for 1/40 of the levels; the **neck** level is the running girth minimum above it,
/// fixed when the girth rises 10% past it (the head).
pub(super) fn scan_torso(
    scan: &Scan<'_>,
    levels: usize,
    joined: (f64, &MeasuredLoop),
) -> Result<TorsoScan, LandmarkError> {
    let (joined_y, joined_loop) = joined;
    let mut torso: Vec<(f64, MeasuredLoop)> = vec![(joined_y, joined_loop.clone())];
    let mut last_arms: [Option<(usize, DVec2)>; 2] = [None, None];
    let mut k = ((joined_y - scan.floor) / scan.height * levels as f64).floor() as usize + 1;
    let mut neck: Option<usize> = None;
    let mut armpit_level: Option<usize> = None;
    let mut running_min: Option<(usize, f64)> = None;
    while k < levels {
        let y = scan.level(k, levels);
        let loops = scan.loops(y);
        let Some((_, prev)) = torso.last() else { break };
        let Some(ti) = loop_at(&loops, prev.centroid) else {
            break;
        };
        let body = loops[ti].clone();
        for (side, slot) in last_arms.iter_mut().enumerate() {
            let arm = loops.iter().enumerate().filter(|(i, l)| {
                *i != ti
                    && l.area >= 0.02 * body.area
                    && if side == 0 {
                        l.centroid.x > body.max.x
                    } else {
                        l.centroid.x < body.min.x
                    }
            });
            if let Some((_, l)) = arm.max_by(|a, b| a.1.area.total_cmp(&b.1.area)) {
                *slot = Some((torso.len(), l.centroid));
            }
        }
        torso.push((y, body));
        let index = torso.len() - 1;
        // The armpit is fixed once no arm has been seen beside the torso for a while.
        let last_seen = last_arms.iter().flatten().map(|a| a.0).max();
        if let Some(seen) = last_seen
            && index > seen
            && armpit_level.is_none()
            && index - seen > levels / 40
        {
            armpit_level = Some(seen);
        }
        if armpit_level.is_some() {
            let g = torso[index].1.tape_girth;
            match running_min {
                Some((_, m)) if g >= m => {
                    if g > 1.1 * m {
                        neck = running_min.map(|r| r.0);
                        break;
                    }
                }
                _ => running_min = Some((index, g)),
            }
        }
        k += 1;
    }
    let armpit_index = armpit_level.ok_or(LandmarkError::NoArms)?;
    let neck_index = neck.ok_or(LandmarkError::NoNeck)?;
    Ok(TorsoScan {
        torso,
        last_arms,
        armpit_index,
        neck_index,
    })
}

/// **Armpit** height: per arm last seen at the armpit level, bisection between that level
/// and the next for where the arm's loop joins the torso's; the lower of the two.
pub(super) fn armpit(scan: &Scan<'_>, t: &TorsoScan, levels: usize, steps: usize) -> f64 {
    let (below_y, below_loop) = (t.torso[t.armpit_index].0, &t.torso[t.armpit_index].1);
    let above_y = t
        .torso
        .get(t.armpit_index + 1)
        .map_or(below_y + scan.height / levels as f64, |x| x.0);
    let mut armpit_y = above_y;
    for (seen, arm_centroid) in t.last_arms.iter().flatten() {
        if *seen != t.armpit_index {
            continue;
        }
        let torso_point = below_loop.centroid;
        let arm_point = *arm_centroid;
        let y = scan.bisect(below_y, above_y, steps, |loops| {
            let t = loops.iter().position(|l| l.contains(torso_point));
            t.is_none() || t != loops.iter().position(|l| l.contains(arm_point))
        });
        armpit_y = armpit_y.min(y);
    }
    armpit_y
}

/// The first torso level at or above `y`.
fn index_of(girths: &[(f64, f64)], y: f64) -> usize {
    girths.partition_point(|g| g.0 < y)
}

/// **Waist**: the level of the smallest torso tape girth in the middle half between the
/// crotch and the armpit.
pub(super) fn waist(girths: &[(f64, f64)], crotch_y: f64, armpit_y: f64) -> Result<usize, LandmarkError> {
    let span = armpit_y - crotch_y;
    arg_extreme(
        girths,
        index_of(girths, crotch_y + 0.25 * span)..index_of(girths, armpit_y - 0.25 * span),
        false,
    )
    .ok_or(LandmarkError::NoWaist)
}

/// **Hip**: the level of the greatest buttock protrusion (the torso's rearmost point) below
/// the waist. The widest hull is not used: with the legs apart it sits just above the crotch.
pub(super) fn hip(torso: &[(f64, MeasuredLoop)], waist_i: usize) -> usize {
    let back: Vec<(f64, f64)> = torso.iter().map(|(y, l)| (*y, -l.min.y)).collect();
    arg_extreme(&back, 1..waist_i, true).unwrap_or(waist_i)
}

/// **Bust**: the level of the largest tape girth between the waist and the armpit.
pub(super) fn bust(girths: &[(f64, f64)], waist_i: usize, armpit_y: f64) -> usize {
    arg_extreme(girths, waist_i..index_of(girths, armpit_y), true).unwrap_or(waist_i)
}
