//! The neck-base rules, from silhouettes: the **shoulder** and **side neck** points are the
//! convex and concave corners of the front silhouette (half width against height, armpit to
//! neck); the **front neck** point is the concave corner of the mid-sagittal front profile
//! between the bust and the neck.

use glam::{DVec2, DVec3};

use super::LandmarkError;
use super::scan::{Scan, corner, front_z_at};
use crate::body::profile::{MeasuredLoop, loop_at};

/// Shoulder and side-neck points, `([left, right], [left, right])`, m. The silhouette is
/// sampled at 201 heights from just above the armpit (`eps`) to the neck, following the
/// torso loop up from `axis` (the torso centroid at the armpit).
pub(super) fn shoulders_and_side_necks(
    scan: &Scan<'_>,
    mut axis: DVec2,
    (armpit_y, neck_y, eps): (f64, f64, f64),
    mid_x: f64,
) -> Result<([DVec3; 2], [DVec3; 2]), LandmarkError> {
    let fine = 200;
    let mut silhouette: Vec<(f64, MeasuredLoop)> = Vec::with_capacity(fine + 1);
    for i in 0..=fine {
        let y = armpit_y + eps + (neck_y - armpit_y - eps) * i as f64 / fine as f64;
        let loops = scan.loops(y);
        if let Some(ti) = loop_at(&loops, axis) {
            axis = loops[ti].centroid;
            silhouette.push((y, loops[ti].clone()));
        }
    }
    let side_curve = |left: bool| -> Vec<DVec2> {
        silhouette
            .iter()
            .map(|(y, l)| DVec2::new(if left { l.max.x - mid_x } else { mid_x - l.min.x }, *y))
            .collect()
    };
    let mut shoulder = [DVec3::ZERO; 2];
    let mut side_neck = [DVec3::ZERO; 2];
    for (s, left) in [(0, true), (1, false)] {
        let curve = side_curve(left);
        let ai = corner(&curve, DVec2::new(1.0, 1.0)).ok_or(LandmarkError::NoNeck)?;
        let ni = ai + corner(&curve[ai..], DVec2::new(-1.0, -1.0)).ok_or(LandmarkError::NoNeck)?;
        let extreme = |i: usize| {
            let l = &silhouette[i].1;
            if left { l.extreme(|p| p.x) } else { l.extreme(|p| -p.x) }
        };
        shoulder[s] = extreme(ai);
        side_neck[s] = extreme(ni);
    }
    Ok((shoulder, side_neck))
}

/// The front-neck point on the torso levels `torso` (bust to neck), m.
pub(super) fn front_neck(torso: &[(f64, MeasuredLoop)], mid_x: f64) -> Result<DVec3, LandmarkError> {
    let front: Vec<(f64, f64)> = torso
        .iter()
        .filter_map(|(y, l)| front_z_at(l, mid_x).map(|z| (*y, z)))
        .collect();
    let front_curve: Vec<DVec2> = front.iter().map(|(y, z)| DVec2::new(*z, *y)).collect();
    let fi = corner(&front_curve, DVec2::new(-1.0, 0.0)).ok_or(LandmarkError::NoNeck)?;
    Ok(DVec3::new(mid_x, front[fi].0, front[fi].1))
}
