//! What a drag may not do, checked before solving: move a whole ring out of its band (past
//! the ring next to it on one of its contours, or off the body's height) or off the part of
//! the body it goes around (a hem off its leg, a waist off the torso), or take an open
//! curve (the crotch curve, a strap) through the body: in at one side and out at the other,
//! or so deep in that its nearest way out is elsewhere. (A ring point dragged through the
//! body is refused by the solver: the ring would cross itself.)

use glam::{DVec2, DVec3};

use super::EditError;
use crate::constraint::curves::{self, CurveKind, CurveNode};
use crate::garment::{BodyProbe, Framework, template};
use crate::geom::polygon;

/// A ring may come no nearer its neighbours (or the body's ends) than this fraction of the
/// body's height.
const BAND_MARGIN: f64 = 0.01;

/// The height of a named control point (`ring.anchor`, `crotch.point`) along `up`, m.
fn point_height(fw: &Framework, name: &str, up: DVec3) -> Option<f64> {
    fw.control_points()
        .into_iter()
        .find(|(n, _)| n == name)
        .map(|(_, p)| along(p, up))
}

/// `p`'s coordinate along the unit `up`: exactly `p.y` for `+y`.
fn along(p: DVec3, up: DVec3) -> f64 {
    if up == DVec3::Y { p.y } else { p.dot(up) }
}

/// The mean height of a curve's control points along `up`, m.
fn height_of(fw: &Framework, c: &CurveNode, up: DVec3) -> f64 {
    let pts = curves::points(fw, c);
    pts.iter().map(|p| along(*p, up)).sum::<f64>() / pts.len().max(1) as f64
}

/// The direction a ring's band runs in: up the body, or for a ring of a type-I part (a
/// sleeve's, positioned by its own axis) its plane's normal, up the sleeve.
fn band_direction(fw: &Framework, c: &CurveNode) -> Option<DVec3> {
    let roles = template::styled(fw.template, fw.style).roles();
    if roles.axial.contains(&c.name.as_str()) {
        fw.ring(&c.name).map(|r| r.plane.normal)
    } else {
        None
    }
}

/// Refuses a whole-ring drag by `by` that would take the ring out of its band: between the
/// highest of the points below it and the lowest above it on the contours through it, and
/// within the body's height, each with a margin of [`BAND_MARGIN`] of the height.
pub(super) fn check_band(fw: &Framework, c: &CurveNode, by: DVec3, probe: &BodyProbe) -> Result<(), EditError> {
    if c.kind != CurveKind::Ring {
        return Ok(());
    }
    let axial = band_direction(fw, c);
    let up = axial.unwrap_or(DVec3::Y);
    let index = probe.index();
    let (floor, top) = index
        .positions
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    let margin = BAND_MARGIN * index.height;
    let (mut lo, mut below) = (floor, "the floor".to_string());
    let (mut hi, mut above) = (top, "the top of the body".to_string());
    if axial.is_some() {
        // Along a sleeve the body's ends bound nothing: its neighbours on the contours do.
        (lo, below) = (f64::NEG_INFINITY, "the hand".to_string());
        (hi, above) = (f64::INFINITY, "the shoulder".to_string());
    }
    let prefix = format!("{}.", c.name);
    for contour in &fw.contours {
        let Some(k) = contour.through.iter().position(|t| t.starts_with(&prefix)) else {
            continue;
        };
        if let Some(name) = k.checked_sub(1).and_then(|j| contour.through.get(j))
            && let Some(y) = point_height(fw, name, up)
            && y > lo
        {
            (lo, below) = (y, name.clone());
        }
        if let Some(name) = contour.through.get(k + 1)
            && let Some(y) = point_height(fw, name, up)
            && y < hi
        {
            (hi, above) = (y, name.clone());
        }
    }
    let y = height_of(fw, c, up) + along(by, up);
    if axial.is_some() {
        if y < lo + margin || y > hi - margin {
            return Err(EditError::OutOfAxialBand {
                curve: c.name.clone(),
                at: y,
                lo: lo + margin,
                hi: hi - margin,
                below,
                above,
            });
        }
        return Ok(());
    }
    if y < lo + margin || y > hi - margin {
        return Err(EditError::OutOfBand {
            curve: c.name.clone(),
            y,
            lo: lo + margin,
            hi: hi - margin,
            below,
            above,
        });
    }
    Ok(())
}

/// Refuses a whole-ring drag by `by` that would take the ring off a part of the body it goes
/// around. The body's horizontal section at the ring's height has one loop per part there
/// (the torso, each arm, each leg); the ring goes around those whose centre its control
/// polygon, seen from above, contains. Each of them passes on through the ring's plane at
/// its new height: its section there (the loop of the section at the new height whose
/// centre is nearest) must still lie around a centre inside the dragged ring, or the part
/// would leave the garment through its wall.
pub(super) fn check_around(fw: &Framework, c: &CurveNode, by: DVec3, probe: &BodyProbe) -> Result<(), EditError> {
    // A sleeve's ring goes around the arm across its own axis, not a horizontal slice: the
    // collision keeps the arm inside it.
    if c.kind != CurveKind::Ring || band_direction(fw, c).is_some() {
        return Ok(());
    }
    let slices = &probe.index().slices;
    let ring: Vec<DVec2> = curves::points(fw, c).iter().map(|p| DVec2::new(p.x, p.z)).collect();
    let moved: Vec<DVec2> = ring.iter().map(|p| *p + DVec2::new(by.x, by.z)).collect();
    let y = height_of(fw, c, DVec3::Y);
    let (Some(before), Some(after)) = (slices.at(y), slices.at(y + by.y)) else {
        return Ok(());
    };
    let centre = |l: &crate::body::slices::Loop2| polygon::centroid(l.points());
    let centres_after: Vec<DVec2> = after.loops.iter().map(centre).collect();
    for around in before.loops.iter().map(centre).filter(|&m| polygon::contains(&ring, m)) {
        let Some(&next) = centres_after
            .iter()
            .min_by(|a, b| a.distance(around).total_cmp(&b.distance(around)))
        else {
            continue;
        };
        if !polygon::contains(&moved, next) {
            let n = moved.len();
            let off = (0..n)
                .map(|i| polygon::segment_distance2(next, moved[i], moved[(i + 1) % n]).sqrt())
                .fold(f64::INFINITY, f64::min);
            return Err(EditError::OffTheBody {
                curve: c.name.clone(),
                by,
                y: after.y,
                centre: next,
                off,
            });
        }
    }
    Ok(())
}

/// Refuses moving point `name` from `from` to `to` along a straight path that enters the
/// body and leaves it again, or that ends inside it nearer another part of its surface than
/// the way it came in (the collision would take the point out there, through the body: the
/// surface nearest the end lies more than twice the depth from where the path entered). A
/// drag a little into the body is allowed: the collision brings the point back out.
pub(super) fn check_path(name: &str, from: DVec3, to: DVec3, probe: &BodyProbe) -> Result<(), EditError> {
    let index = probe.index();
    let d = to - from;
    if d == DVec3::ZERO {
        return Ok(());
    }
    let Some((t_in, _)) = index.cast_ray(from, d, 0.0, 1.0) else {
        return Ok(());
    };
    let skip = 1e-6 * index.height / d.length();
    let entry = from + d * t_in;
    let Some((foot, signed, _)) = probe.nearest(to) else {
        return Ok(());
    };
    if signed > 0.0 {
        if let Some((t_out, _)) = index.cast_ray(from, d, t_in + skip, 1.0) {
            return Err(EditError::ThroughBody {
                point: name.to_string(),
                entry,
                exit: from + d * t_out,
            });
        }
    } else if foot.distance(entry) > 2.0 * (-signed) {
        return Err(EditError::DeepInside {
            point: name.to_string(),
            depth: -signed,
            entry,
            nearest: foot,
        });
    }
    Ok(())
}
