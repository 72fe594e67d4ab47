//! Sleeves, the \[frame\] paper's type-I parts on the armholes: each positioned by its own
//! axis (the arm's centre line from the shoulder point through the elbow to the wrist,
//! lifted by the sleeve angle) and joined to the bodice through one curve, the armhole.
//!
//! By the reference-plane method (\[frame\] figure 7c): the cap ring C1 (`<side>_bicep`,
//! `cap_height` down the axis) and the cuff ring C2 (`<side>_cuff`, `sleeve_length` down
//! it) are the arm's sections in planes across the axis, eased, each in its own plane (the
//! constraint network keeps them there). The rings between them (`<side>_elbow` at the
//! elbow, `<side>_forearm` halfway to the cuff; long sleeves only) are interpolated: the
//! reference plane II between C1's and C2's, the ring C4 blended from theirs
//! ([`interpolate`]), deformed to C3, the hull of C4 and the arm's eased section (the ring
//! is built around both loops; its raw stage keeps them). Four contours run down each sleeve (`outer`, `front`, `inner`, `back`) from
//! the cuff to the cap ring, and on from there the cap's lines to the armhole's four points
//! (see [`ArmholePoints`]): the strap's top, where the strap is halfway down in front and
//! behind, and the chest ring's side under the arm.
//!
//! A long sleeve has 9 curves (the armhole, four rings, four contours), a short one 7.

mod axis;
mod interpolate;
mod patches;

pub use axis::SleeveAxis;
pub use interpolate::{RingFrame, interpolate};
pub use patches::{ArmholePoints, armhole, armhole_lines, armhole_lower_lines, cap_lines, sleeve_patches, strap_part};

use glam::DVec3;

use crate::body::Side;
use crate::garment::anchors::{AnchorRule, AnchorSpec};
use crate::garment::convexify::convex_ring;
use crate::garment::ease::{Ease, ease_ring};
use crate::garment::model::{FrameworkError, NamedPlane, Sleeves};
use crate::garment::resample::resample_closed;
use crate::garment::ring::GarmentRing;
use crate::garment::solve::{BuildCtx, ContourSpec, section_error};
use crate::geom::Plane;

/// The anchors of the left sleeve's rings, in ring order (counter-clockwise about the
/// normal up the sleeve: seen from the hand).
pub const LEFT_SLEEVE: [&str; 4] = ["outer", "back", "inner", "front"];

/// The anchors of the right sleeve's rings, in ring order (the mirror of the left's).
pub const RIGHT_SLEEVE: [&str; 4] = ["outer", "front", "inner", "back"];

/// The rings of a long sleeve, cap to cuff, left then right.
const LONG: [[&str; 4]; 2] = [
    ["left_bicep", "left_elbow", "left_forearm", "left_cuff"],
    ["right_bicep", "right_elbow", "right_forearm", "right_cuff"],
];

/// The rings of a short sleeve, cap to cuff, left then right.
const SHORT: [[&str; 2]; 2] = [["left_bicep", "left_cuff"], ["right_bicep", "right_cuff"]];

/// The contours of the sleeves, left then right, in each sleeve's ring order.
const CONTOURS: [[&str; 4]; 2] = [
    [
        "left_sleeve_outer",
        "left_sleeve_back",
        "left_sleeve_inner",
        "left_sleeve_front",
    ],
    [
        "right_sleeve_outer",
        "right_sleeve_front",
        "right_sleeve_inner",
        "right_sleeve_back",
    ],
];

/// The armholes, left then right.
pub const ARMHOLES: [&str; 2] = ["left_armhole", "right_armhole"];

/// The two sides: side, its name, its index into the arm axes.
const SIDES: [(Side, &str, usize); 2] = [(Side::Left, "left", 0), (Side::Right, "right", 1)];

/// One sleeve's rings, cap to cuff (`side` 0 left, 1 right).
pub fn ring_names(sleeves: Sleeves, side: usize) -> Vec<&'static str> {
    match sleeves {
        Sleeves::None => Vec::new(),
        Sleeves::Short => SHORT[side].to_vec(),
        Sleeves::Long => LONG[side].to_vec(),
    }
}

/// Every sleeve ring, left sleeve first.
pub fn rings(sleeves: Sleeves) -> Vec<&'static str> {
    (0..2).flat_map(|k| ring_names(sleeves, k)).collect()
}

/// One sleeve's anchors in ring order (`side` 0 left, 1 right).
pub fn anchor_names(side: usize) -> &'static [&'static str; 4] {
    if side == 0 { &LEFT_SLEEVE } else { &RIGHT_SLEEVE }
}

/// One sleeve's contours, in its ring order.
pub fn contour_names(sleeves: Sleeves, side: usize) -> Vec<&'static str> {
    if sleeves == Sleeves::None {
        Vec::new()
    } else {
        CONTOURS[side].to_vec()
    }
}

/// Every sleeve contour, left sleeve first.
pub fn contours(sleeves: Sleeves) -> Vec<&'static str> {
    (0..2).flat_map(|k| contour_names(sleeves, k)).collect()
}

/// The sleeves' dimensions, each with what it measures.
pub fn lengths(sleeves: Sleeves) -> Vec<(&'static str, &'static str)> {
    let mut out = match sleeves {
        Sleeves::None => return Vec::new(),
        _ => vec![
            (
                "sleeve_length",
                "shoulder point to cuff along the sleeve's axis, m (default: to the wrist, or halfway down the upper arm for a short sleeve)",
            ),
            (
                "cap_height",
                "shoulder point to the cap ring (bicep) along the axis, m (default: just past the armhole)",
            ),
            (
                "sleeve_angle",
                "the sleeve's lift from the arm about the shoulder point, degrees (default 0)",
            ),
            ("bicep_girth", "girth of both cap rings, m (default: the arm's, eased)"),
            ("cuff_girth", "girth of both cuffs, m (default: the arm's, eased)"),
        ],
    };
    if sleeves == Sleeves::Long {
        out.push((
            "elbow_girth",
            "girth of both elbow rings, m (default: interpolated, clearing the arm)",
        ));
    }
    out
}

/// A sleeve ring's anchors (`side` 0 left, 1 right): the outer (up and out), front, inner and
/// back extremes, in ring order.
fn anchor_specs(side: usize) -> Vec<AnchorSpec> {
    let out = if side == 0 { DVec3::X } else { DVec3::NEG_X };
    let top = (DVec3::Y + out).normalize();
    anchor_names(side)
        .iter()
        .map(|name| AnchorSpec {
            name,
            rule: AnchorRule::Extreme(match *name {
                "outer" => top,
                "inner" => -top,
                "front" => DVec3::Z,
                _ => DVec3::NEG_Z,
            }),
        })
        .collect()
}

/// The sleeves' contour specs: each from the cuff up through every ring to the cap ring
/// (above it the cap's lines run on to the armhole, see [`cap_lines`]).
pub fn contour_specs(sleeves: Sleeves) -> Vec<ContourSpec> {
    let mut out = Vec::new();
    if sleeves == Sleeves::None {
        return out;
    }
    for side in 0..2 {
        let rings = ring_names(sleeves, side);
        for (contour, anchor) in contour_names(sleeves, side).iter().zip(anchor_names(side)) {
            let pts: Vec<(String, String)> = rings
                .iter()
                .rev()
                .map(|r| (r.to_string(), anchor.to_string()))
                .collect();
            out.push((contour.to_string(), pts));
        }
    }
    out
}

/// Where each sleeve ring sits along the axis, m from the shoulder point, cap to cuff.
fn positions(sleeves: Sleeves, axis: &SleeveAxis, cap: f64, length: f64) -> Vec<f64> {
    match sleeves {
        Sleeves::None => Vec::new(),
        Sleeves::Short => vec![cap, length],
        Sleeves::Long => {
            let elbow = axis.upper();
            vec![cap, elbow, 0.5 * (elbow + length), length]
        }
    }
}

/// Segment counts of a sleeve's bands, armhole to cuff, from the arm alone (the mesh's
/// topology must not depend on the dimensions): the cap band a quarter of the upper arm,
/// the rest where the default rings sit.
pub fn band_counts(ctx: &BuildCtx<'_>, sleeves: Sleeves) -> Result<Vec<usize>, FrameworkError> {
    if sleeves == Sleeves::None {
        return Ok(Vec::new());
    }
    let axis = arm(ctx, 0)?;
    let cap = 0.25 * axis.upper();
    let length = default_length(sleeves, &axis, cap);
    let mut stops = vec![0.0];
    stops.extend(positions(sleeves, &axis, cap, length));
    Ok(stops.windows(2).map(|w| ctx.segments(w[1] - w[0], 1.0)).collect())
}

/// The sleeve's default length: to the wrist, or halfway down the upper arm past the cap.
fn default_length(sleeves: Sleeves, axis: &SleeveAxis, cap: f64) -> f64 {
    match sleeves {
        Sleeves::Long => axis.length(),
        _ => cap + 0.5 * (axis.upper() - cap),
    }
}

/// The arm's axis on `side` (0 left, 1 right), as found.
fn arm(ctx: &BuildCtx<'_>, side: usize) -> Result<SleeveAxis, FrameworkError> {
    SleeveAxis::of_arm(&ctx.body.landmarks.arm_axis[side]).ok_or_else(|| {
        section_error(
            ARMHOLES[side],
            format!("the {} arm was not found down to its wrist", SIDES[side].1),
        )
    })
}

/// Solves both sleeves' rings: the armholes' points `armholes[side]` (`outer, front, inner,
/// back`: see [`ArmholePoints`]), the dimensions, the cap and cuff rings from the arm, the rings between them by
/// the reference planes. Adds every ring's plane to `planes`.
pub fn solve(
    ctx: &mut BuildCtx<'_>,
    sleeves: Sleeves,
    armholes: [[DVec3; 4]; 2],
    planes: &mut Vec<NamedPlane>,
) -> Result<Vec<GarmentRing>, FrameworkError> {
    if sleeves == Sleeves::None {
        return Ok(Vec::new());
    }
    let h = ctx.height;
    let angle = ctx.value(
        "sleeve_angle",
        0.0,
        (-15.0, 45.0),
        "the sleeve may lift from the arm up to 45 degrees and close in by 15",
    )?;
    let axes = [
        arm(ctx, 0)?.lifted(angle.to_radians()),
        arm(ctx, 1)?.lifted(angle.to_radians()),
    ];
    // The cap ring lies past every armhole point along the axis.
    let past = axes
        .iter()
        .zip(&armholes)
        .flat_map(|(a, pts)| pts[1..].iter().map(move |p| a.along_upper(*p)))
        .fold(0.0f64, f64::max);
    let upper = axes[0].upper().min(axes[1].upper());
    let cap = ctx.value(
        "cap_height",
        past + 0.02 * h,
        (past + 0.005 * h, 0.8 * upper),
        "the cap ring must lie past the armhole and above the elbow",
    )?;
    let whole = axes[0].length().min(axes[1].length());
    let length = ctx.value(
        "sleeve_length",
        match sleeves {
            Sleeves::Long => whole,
            _ => cap + 0.5 * (upper - cap),
        },
        match sleeves {
            Sleeves::Long => (upper + 0.15 * (whole - upper), whole),
            _ => (cap + 0.02 * h, 0.95 * upper),
        },
        "the cuff must lie below the elbow and above the wrist on a long sleeve, between the cap and the elbow on a short one",
    )?;
    let mut out = Vec::new();
    let mut girths: Vec<(&str, f64)> = Vec::new();
    for (_, name, k) in SIDES {
        let axis = axes[k];
        let at = positions(sleeves, &axis, cap, length);
        let names = ring_names(sleeves, k);
        let specs = anchor_specs(k);
        let frame = |s: f64| RingFrame {
            origin: axis.point(s),
            normal: -axis.direction(s),
        };
        let last = at.len() - 1;
        let shared = |ring: &'static str| ring.trim_start_matches(name).trim_start_matches('_');
        // C1 and C2: the arm's sections, eased.
        let mut ends = Vec::with_capacity(2);
        for i in [0, last] {
            let (ring, f) = (names[i], frame(at[i]));
            let e = ctx.ring_ease(ring)?;
            let plane = f.plane();
            let arm_loop = arm_section(ctx, ring, &plane, f.origin)?;
            let key = format!("{}_girth", shared(ring));
            ends.push(ctx.ring_with(ring, &[&key], plane, vec![arm_loop], &specs, Ease::Uniform(e))?);
        }
        let (c1, c2) = (ends.remove(0), ends.remove(0));
        let mut built = vec![c1];
        // Between them: C4 on the reference plane II, deformed to C3.
        for i in 1..last {
            let (ring, s) = (names[i], at[i]);
            let e = ctx.ring_ease(ring)?;
            let t = (s - at[0]) / (at[last] - at[0]);
            let (f4, c4) = interpolate(
                (&built[0].stages.fitted, frame(at[0])),
                (&c2.stages.fitted, frame(at[last])),
                t,
                axis.point(s),
            );
            let plane = f4.plane();
            let arm_loop = arm_section(ctx, ring, &plane, f4.origin)?;
            // C3: the ring is built around both loops, C4 and the arm's section eased, by
            // their common convex hull (kept as its raw stage: both loops).
            let arm = eased_section(ctx, &arm_loop, &plane, e, ring)?;
            let key = format!("{}_girth", shared(ring));
            built.push(ctx.ring_with(ring, &[&key], plane, vec![c4, arm], &specs, Ease::Uniform(0.0))?);
        }
        built.push(c2);
        for (i, (r, &s)) in built.iter().zip(&at).enumerate() {
            if k == 0 {
                girths.push((shared(names[i]), r.girth));
            }
            let mut p = ctx.plane_for(&r.name, r.plane, axis.point(s));
            p.extent = 0.05 * h;
            planes.push(p);
        }
        out.extend(built);
    }
    for (shared, girth) in girths {
        let name = format!("{shared}_girth");
        if name == "forearm_girth" {
            continue;
        }
        let target = ctx.dims.get(&name);
        ctx.dimensions.push(crate::garment::model::DimensionValue {
            name,
            value: girth,
            target,
        });
    }
    Ok(out)
}

/// The arm's section in `plane`: the closed loop around `centre` (or the nearest), refused
/// when it reaches farther than an arm could (the plane cuts the torso as well).
fn arm_section(ctx: &BuildCtx<'_>, ring: &str, plane: &Plane, centre: DVec3) -> Result<Vec<DVec3>, FrameworkError> {
    let around = ctx
        .loop_around(plane, centre)
        .ok_or_else(|| section_error(ring, "its plane cuts no closed loop of the arm".into()))?;
    let reach = around.iter().map(|p| p.distance(centre)).fold(0.0, f64::max);
    if reach > 0.12 * ctx.height {
        return Err(section_error(
            ring,
            format!(
                "its plane cuts the torso as well as the arm (the section reaches {reach:.3} m from the axis): move it down the arm (cap_height, sleeve_length)"
            ),
        ));
    }
    Ok(around)
}

/// The arm's section `arm` convexified and eased by `ease` in `plane` (the ring C3 must
/// enclose it).
fn eased_section(
    ctx: &BuildCtx<'_>,
    arm: &[DVec3],
    plane: &Plane,
    ease: f64,
    ring: &str,
) -> Result<Vec<DVec3>, FrameworkError> {
    let convex = convex_ring(arm, plane);
    let resampled = resample_closed(&convex.points, &convex.anchors, ctx.options.ring.resample_per_arc)
        .map_err(|e| FrameworkError::Ring(crate::garment::ring::RingBuildError::Resample(ring.to_string(), e)))?;
    ease_ring(&resampled, &convex.points, plane, Ease::Uniform(ease))
        .map_err(|e| FrameworkError::Ring(crate::garment::ring::RingBuildError::Ease(ring.to_string(), e)))
}
