//! Landmark corrections from the session: a height re-measures the landmark on the body at
//! that height, a point is taken as given.

use glam::{DVec2, DVec3};

use super::scan::{Scan, front_z_at};
use super::{LandmarkKind, LandmarkOverride, Landmarks, Side};
use crate::body::profile::loop_at;

/// Applies session corrections: a height re-measures the landmark's point on the body at
/// that height; a point is taken as given (mirrored for the right side of a pair).
pub(super) fn apply_overrides(
    scan: &Scan<'_>,
    landmarks: &mut Landmarks,
    overrides: &[(LandmarkKind, LandmarkOverride)],
) {
    for &(kind, correction) in overrides {
        let legs = match correction {
            LandmarkOverride::Height(y) => landmarks.legs_at(y),
            LandmarkOverride::Point(p) => landmarks.legs_at(p.y),
        };
        let torso = match correction {
            LandmarkOverride::Height(y) => landmarks.torso_at(y),
            LandmarkOverride::Point(p) => landmarks.torso_at(p.y),
        };
        let mid_x = landmarks.mid_x;
        let arm_axis = landmarks.arm_axis.clone();
        for item in landmarks.items.iter_mut().filter(|l| l.kind == kind) {
            let point = match correction {
                LandmarkOverride::Point(p) => {
                    if item.side == Side::Right {
                        DVec3::new(2.0 * mid_x - p.x, p.y, p.z)
                    } else {
                        p
                    }
                }
                LandmarkOverride::Height(y) => {
                    let loops = scan.loops(y);
                    let arm = match item.side {
                        Side::Left => &arm_axis[0],
                        _ => &arm_axis[1],
                    };
                    let on_arm = arm
                        .points
                        .iter()
                        .skip(1)
                        .min_by(|a, b| (a.y - y).abs().total_cmp(&(b.y - y).abs()))
                        .map(|p| DVec2::new(p.x, p.z));
                    let anchor = match (item.side, legs, torso) {
                        _ if matches!(kind, LandmarkKind::Elbow | LandmarkKind::Wrist) => on_arm,
                        (Side::Left, Some((l, _)), _) if matches!(kind, LandmarkKind::Ankle | LandmarkKind::Knee) => {
                            Some(l)
                        }
                        (Side::Right, Some((_, r)), _) if matches!(kind, LandmarkKind::Ankle | LandmarkKind::Knee) => {
                            Some(r)
                        }
                        (_, _, t) => t,
                    };
                    let found = anchor.and_then(|a| loop_at(&loops, a)).map(|i| &loops[i]);
                    match (found, item.side) {
                        (Some(l), Side::Centre) => DVec3::new(mid_x, y, front_z_at(l, mid_x).unwrap_or(l.max.y)),
                        (Some(l), Side::Left)
                            if kind.is_paired() && !matches!(kind, LandmarkKind::Ankle | LandmarkKind::Knee) =>
                        {
                            l.extreme(|p| p.x)
                        }
                        (Some(l), Side::Right)
                            if kind.is_paired() && !matches!(kind, LandmarkKind::Ankle | LandmarkKind::Knee) =>
                        {
                            l.extreme(|p| -p.x)
                        }
                        (Some(l), _) => l.front_point(),
                        (None, _) => DVec3::new(item.point[0], y, item.point[2]),
                    }
                }
            };
            item.point = point.to_array();
            item.overridden = true;
        }
    }
}
