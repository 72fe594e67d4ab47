//! Ring anchors: the named control points where rings meet contours. How an anchor is
//! found on a ring (an extreme in a direction, or where the ring crosses a vertical plane at
//! a fraction of its half width), and the anchor layouts the templates use, with the
//! left-right mirror rule of their names.

use glam::DVec3;

use crate::body::Side;

/// Where a ring's anchor (a named control point shared with a contour) sits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AnchorRule {
    /// The ring point farthest along a world direction (`+z` front, `+x` left, ...).
    Extreme(DVec3),
    /// Where the ring crosses the vertical plane `x = mid + f (x_extreme - mid)` with
    /// `x_extreme` the ring's extreme on that side (`f > 0` left, `f < 0` right, `0` the
    /// centre line), on the front (`true`) or back half.
    Across {
        /// Signed fraction of the half width.
        fraction: f64,
        /// Front half (larger `z`) or back.
        front: bool,
    },
}

/// A named anchor and how to find it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnchorSpec {
    /// `front`, `front_left`, `outer`, ...
    pub name: &'static str,
    /// Where it is.
    pub rule: AnchorRule,
}

/// The anchors of a torso ring, in ring order (counter-clockwise seen from above, from the
/// centre front): the centre line, the princess lines and the sides.
pub const TORSO: [&str; 8] = [
    "front",
    "front_left",
    "left",
    "back_left",
    "back",
    "back_right",
    "right",
    "front_right",
];

/// The anchors of a ring with four: the centre line and the sides.
pub const QUAD: [&str; 4] = ["front", "left", "back", "right"];

/// The anchors of the left leg's rings, in ring order.
pub const LEFT_LEG: [&str; 4] = ["front", "outer", "back", "inner"];

/// The anchors of the right leg's rings, in ring order (the mirror of the left's).
pub const RIGHT_LEG: [&str; 4] = ["front", "inner", "back", "outer"];

/// [`QUAD`]: the centre line across the middle, the sides at the extremes.
pub fn quad_anchors() -> Vec<AnchorSpec> {
    vec![
        AnchorSpec {
            name: "front",
            rule: AnchorRule::Across {
                fraction: 0.0,
                front: true,
            },
        },
        AnchorSpec {
            name: "left",
            rule: AnchorRule::Extreme(DVec3::X),
        },
        AnchorSpec {
            name: "back",
            rule: AnchorRule::Across {
                fraction: 0.0,
                front: false,
            },
        },
        AnchorSpec {
            name: "right",
            rule: AnchorRule::Extreme(DVec3::NEG_X),
        },
    ]
}

/// A leg ring's anchors: the extremes front, outer, back and inner.
pub fn leg_anchors(side: Side) -> Vec<AnchorSpec> {
    let names = if side == Side::Left { LEFT_LEG } else { RIGHT_LEG };
    let dirs = [DVec3::Z, DVec3::X, DVec3::NEG_Z, DVec3::NEG_X];
    names
        .iter()
        .zip(dirs)
        .map(|(name, d)| AnchorSpec {
            name,
            rule: AnchorRule::Extreme(d),
        })
        .collect()
}

/// [`TORSO`]: the centre line, the extremes, and the princess lines at signed fractions
/// `(left, right)` of the half width.
pub fn torso_anchors(left: f64, right: f64) -> Vec<AnchorSpec> {
    let across = |fraction: f64, front: bool| AnchorRule::Across { fraction, front };
    let rules = [
        across(0.0, true),
        across(left, true),
        AnchorRule::Extreme(DVec3::X),
        across(left, false),
        across(0.0, false),
        across(-right, false),
        AnchorRule::Extreme(DVec3::NEG_X),
        across(-right, true),
    ];
    TORSO
        .iter()
        .zip(rules)
        .map(|(name, rule)| AnchorSpec { name, rule })
        .collect()
}

/// The mirror image of an anchor name: `..left` and `..right` swap, a centre name
/// (`front`, `back`) is its own.
pub fn mirror_name(name: &str) -> String {
    if let Some(x) = name.strip_suffix("left") {
        format!("{x}right")
    } else if let Some(x) = name.strip_suffix("right") {
        format!("{x}left")
    } else {
        name.to_string()
    }
}

/// The mirror pairs among `names` (a ring centred on the mirror plane), each pair once in
/// ring order: the left member (or a centre name, paired with itself) first.
pub fn mirror_pairs(names: &[&'static str]) -> Vec<(&'static str, &'static str)> {
    names
        .iter()
        .filter(|a| !a.ends_with("right"))
        .filter_map(|a| {
            let partner = mirror_name(a);
            names.iter().find(|b| **b == partner).map(|b| (*a, *b))
        })
        .collect()
}

/// Where the closed polyline crosses `x = c` on the front (larger z) or back side.
fn crossing(points: &[DVec3], c: f64, front: bool) -> Option<(usize, f64, DVec3)> {
    let n = points.len();
    let mut best: Option<(usize, f64, DVec3)> = None;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        let (da, db) = (a.x - c, b.x - c);
        if (da <= 0.0 && db > 0.0) || (da > 0.0 && db <= 0.0) {
            let t = da / (da - db);
            let p = a.lerp(b, t);
            let better = best.is_none_or(|(_, _, q)| if front { p.z > q.z } else { p.z < q.z });
            if better {
                best = Some((i, t, p));
            }
        }
    }
    best
}

/// Locates anchors on a closed polyline: `(segment, t, point)` per anchor.
pub(super) fn locate(
    points: &[DVec3],
    anchors: &[AnchorSpec],
    mid_x: f64,
) -> Result<Vec<(usize, f64, DVec3)>, &'static str> {
    let xmax = points.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
    let xmin = points.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
    anchors
        .iter()
        .map(|a| match a.rule {
            AnchorRule::Extreme(d) => {
                let i = (0..points.len()).fold(0, |b, i| if points[i].dot(d) > points[b].dot(d) { i } else { b });
                Ok((i, 0.0, points[i]))
            }
            AnchorRule::Across { fraction, front } => {
                let edge = if fraction >= 0.0 { xmax } else { xmin };
                let c = mid_x + fraction.abs() * (edge - mid_x);
                // Stay a hair inside the extreme so the plane really crosses.
                let c = c.clamp(xmin + 1e-9 * (xmax - xmin), xmax - 1e-9 * (xmax - xmin));
                crossing(points, c, front).ok_or(a.name)
            }
        })
        .collect()
}
