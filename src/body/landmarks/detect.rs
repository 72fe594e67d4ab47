//! The landmark scan: the body's sections from the feet up, each landmark from an event or
//! an extreme of them (the rules in the folder's notes).

use glam::{DVec2, DVec3};

use super::scan::{Scan, front_z_at};
use super::types::{ArmAxis, Landmark, LandmarkError, LandmarkKind, LandmarkOptions, Landmarks, Side};
use super::{arms, legs, neck, overrides, torso};
use crate::body::mesh::BodyMesh;
use crate::body::profile::{MeasuredLoop, loop_at};
use crate::mesh::TriMesh;

/// Finds the landmarks of a closed, validated body mesh.
///
/// # Failures
/// [`LandmarkError`] when a body event cannot be found (no legs apart, arms touching the
/// torso all the way, no neck).
pub fn detect_landmarks(body: &BodyMesh, options: &LandmarkOptions) -> Result<Landmarks, LandmarkError> {
    let mesh = &body.mesh;
    let (lo, hi) = mesh.bounds().ok_or(LandmarkError::NoHeight)?;
    let height = hi.y - lo.y;
    if height.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(LandmarkError::NoHeight);
    }
    let mid_x = mid_plane_x(mesh, lo.x, hi.x);
    let scan = Scan {
        body,
        floor: lo.y,
        height,
    };
    let levels = options.levels.max(40);
    let eps = height * 1e-3;
    let steps = options.bisection_steps;

    // Legs, feet up to the crotch.
    let legs = legs::scan_legs(&scan, levels, mid_x)?;
    let crotch_y = legs::crotch(&scan, &legs, steps)?;
    let leg_girth = legs.girths();
    let ankle_i = legs::ankle(&leg_girth);
    let knee_i = legs::knee(&leg_girth, ankle_i, crotch_y);

    // Torso, crotch up to the neck; arms beside it.
    let (joined_y, joined_index, joined_loops) = &legs.joined;
    let t = torso::scan_torso(&scan, levels, (*joined_y, &joined_loops[*joined_index]))?;
    let armpit_y = torso::armpit(&scan, &t, levels, steps);
    let girths = t.girths();
    let waist_i = torso::waist(&girths, crotch_y, armpit_y)?;
    let hip_i = torso::hip(&t.torso, waist_i);
    let bust_i = torso::bust(&girths, waist_i, armpit_y);

    // Shoulder line and neck base from the silhouettes.
    let (torso, neck_index) = (&t.torso, t.neck_index);
    let below_loop = &torso[t.armpit_index].1;
    let (shoulder, side_neck) =
        neck::shoulders_and_side_necks(&scan, below_loop.centroid, (armpit_y, torso[neck_index].0, eps), mid_x)?;
    let front_neck = neck::front_neck(&torso[bust_i..=neck_index], mid_x)?;

    let centre_point = |l: &MeasuredLoop| {
        let y = l.y();
        DVec3::new(mid_x, y, front_z_at(l, mid_x).unwrap_or(l.max.y))
    };
    let mut items = Vec::new();
    let mut push = |kind, side, point: DVec3| {
        items.push(Landmark {
            kind,
            side,
            point: point.to_array(),
            overridden: false,
        });
    };
    let leg = &legs.legs;
    push(LandmarkKind::Ankle, Side::Left, leg[ankle_i].1.front_point());
    push(LandmarkKind::Ankle, Side::Right, leg[ankle_i].2.front_point());
    push(LandmarkKind::Knee, Side::Left, leg[knee_i].1.front_point());
    push(LandmarkKind::Knee, Side::Right, leg[knee_i].2.front_point());
    let (cl, cr) = leg
        .last()
        .map_or((DVec2::ZERO, DVec2::ZERO), |(_, l, r)| (l.centroid, r.centroid));
    push(
        LandmarkKind::Crotch,
        Side::Centre,
        DVec3::new(mid_x, crotch_y, 0.5 * (cl.y + cr.y)),
    );
    push(LandmarkKind::Hip, Side::Centre, centre_point(&torso[hip_i].1));
    push(LandmarkKind::Waist, Side::Centre, centre_point(&torso[waist_i].1));
    push(LandmarkKind::Bust, Side::Centre, centre_point(&torso[bust_i].1));
    let armpit_loop = scan.loops(armpit_y - eps);
    let armpit_point = loop_at(&armpit_loop, below_loop.centroid)
        .map_or(DVec3::new(mid_x, armpit_y, below_loop.max.y), |i| {
            centre_point(&armpit_loop[i])
        });
    push(
        LandmarkKind::Armpit,
        Side::Centre,
        DVec3::new(armpit_point.x, armpit_y, armpit_point.z),
    );
    push(LandmarkKind::Shoulder, Side::Left, shoulder[0]);
    push(LandmarkKind::Shoulder, Side::Right, shoulder[1]);
    push(LandmarkKind::FrontNeck, Side::Centre, front_neck);
    push(LandmarkKind::SideNeck, Side::Left, side_neck[0]);
    push(LandmarkKind::SideNeck, Side::Right, side_neck[1]);
    push(LandmarkKind::Neck, Side::Centre, centre_point(&torso[neck_index].1));
    // The arms, each followed down from the last level it was seen beside the torso.
    let (arm_items, arm_axis) = arm_landmarks(&scan, &t, height / levels as f64, shoulder);
    items.extend(arm_items);
    let order = |kind: LandmarkKind| {
        LandmarkKind::ALL
            .into_iter()
            .chain(LandmarkKind::ARMS)
            .position(|k| k == kind)
    };
    items.sort_by_key(|l| (order(l.kind), l.side));

    let leg_axis = leg.iter().map(|(y, l, r)| (*y, l.centroid, r.centroid)).collect();
    let torso_axis = torso[..=neck_index].iter().map(|(y, l)| (*y, l.centroid)).collect();
    let mut landmarks = Landmarks {
        items,
        mid_x,
        leg_axis,
        torso_axis,
        arm_axis,
    };
    overrides::apply_overrides(&scan, &mut landmarks, &options.overrides);
    Ok(landmarks)
}

/// Each arm (left, right) followed down from the last level it was seen beside the torso
/// (levels `step` apart): its elbow and wrist landmarks and its centre line from `shoulder`.
/// An arm that cannot be followed (touching the body all the way) has neither.
fn arm_landmarks(
    scan: &Scan<'_>,
    t: &torso::TorsoScan,
    step: f64,
    shoulder: [DVec3; 2],
) -> (Vec<Landmark>, [ArmAxis; 2]) {
    let landmark = |kind, side, point: DVec3| Landmark {
        kind,
        side,
        point: point.to_array(),
        overridden: false,
    };
    let mut items = Vec::new();
    let mut arm_axis: [ArmAxis; 2] = Default::default();
    for (k, side) in [Side::Left, Side::Right].into_iter().enumerate() {
        let Some((index, centroid)) = t.last_arms[k] else {
            continue;
        };
        let y = t.torso[index].0;
        let loops = scan.loops(y);
        let Some(start) = loops.iter().find(|l| l.contains(centroid)) else {
            continue;
        };
        let Some(arm) = arms::scan_arm(scan, (y, start), step) else {
            continue;
        };
        let outer = |l: &MeasuredLoop| {
            if side == Side::Left {
                l.extreme(|p| p.x)
            } else {
                l.extreme(|p| -p.x)
            }
        };
        items.push(landmark(LandmarkKind::Elbow, side, outer(&arm.chain[arm.elbow].1)));
        items.push(landmark(LandmarkKind::Wrist, side, outer(&arm.chain[arm.wrist].1)));
        let mut points = vec![shoulder[k]];
        points.extend((0..=arm.wrist).map(|j| arm.centre(j)));
        arm_axis[k] = ArmAxis {
            points,
            elbow: arm.elbow + 1,
        };
    }
    (items, arm_axis)
}

/// The body's mid-plane `x`: the area-weighted mean `x` of its surface (the middle of its
/// bounds `lo_x..hi_x` for a mesh without area), m.
fn mid_plane_x(mesh: &TriMesh, lo_x: f64, hi_x: f64) -> f64 {
    let (mut weighted_x, mut total_area) = (0.0, 0.0);
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        let area = 0.5 * (b - a).cross(c - a).length();
        weighted_x += area * (a.x + b.x + c.x) / 3.0;
        total_area += area;
    }
    if total_area > 0.0 {
        weighted_x / total_area
    } else {
        0.5 * (lo_x + hi_x)
    }
}
