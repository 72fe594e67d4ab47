//! The stand collar, a \[frame\] type-I part on the neckline: positioned by the neckline
//! curve and joined to the bodice there. Its top ring (`collar`, the paper's upper neck
//! ring) is the neck's section by the neckline's plane moved up by `collar_height`, eased
//! by `collar_ease` plus the lean: `collar_height * tan(collar_angle)` more (a positive
//! angle leans the collar out, a negative one in against the neck). Four straight contours
//! (`collar_front`, `collar_left`, `collar_back`, `collar_right`) run up from the
//! neckline's anchors; four patches around, the top edge open.

use glam::DVec3;

use crate::garment::anchors::{QUAD, quad_anchors};
use crate::garment::ease::Ease;
use crate::garment::m0::CurveRef;
use crate::garment::model::{Collar, FrameworkError, NamedPlane};
use crate::garment::ring::GarmentRing;
use crate::garment::solve::{BuildCtx, ContourSpec, section_error};
use crate::garment::surface::{Surfacer, arc};
use crate::geom::{Plane, polygon};

/// The collar's top ring.
pub const RING: &str = "collar";

/// The collar's contours, in the neckline's ring order.
pub const CONTOURS: [&str; 4] = ["collar_front", "collar_left", "collar_back", "collar_right"];

/// The collar's default height as a fraction of the body's height.
const HEIGHT: f64 = 0.02;

/// The collar's rings (its top).
pub fn rings(collar: Collar) -> Vec<&'static str> {
    if collar == Collar::None { Vec::new() } else { vec![RING] }
}

/// The collar's contours.
pub fn contours(collar: Collar) -> Vec<&'static str> {
    if collar == Collar::None {
        Vec::new()
    } else {
        CONTOURS.to_vec()
    }
}

/// The collar's dimensions (its ring's `collar_girth` and `collar_ease` come with every
/// ring).
pub fn lengths(collar: Collar) -> Vec<(&'static str, &'static str)> {
    if collar == Collar::None {
        return Vec::new();
    }
    vec![
        (
            "collar_height",
            "the collar's rise over the neckline, m (default 2% of the body's height)",
        ),
        (
            "collar_angle",
            "the collar's lean from the neck, degrees, positive outwards (default 0)",
        ),
    ]
}

/// The collar's contour specs: from each neckline anchor up to the collar's.
pub fn contour_specs(collar: Collar) -> Vec<ContourSpec> {
    if collar == Collar::None {
        return Vec::new();
    }
    CONTOURS
        .iter()
        .zip(QUAD)
        .map(|(c, a)| {
            (
                c.to_string(),
                vec![
                    ("neckline".to_string(), a.to_string()),
                    (RING.to_string(), a.to_string()),
                ],
            )
        })
        .collect()
}

/// Segments up the collar, from the body's height alone (the topology stays fixed).
pub fn band_count(ctx: &BuildCtx<'_>, collar: Collar) -> usize {
    if collar == Collar::None {
        0
    } else {
        ctx.segments(HEIGHT * ctx.height, 1.0)
    }
}

/// Solves the collar's top ring over `neckline`; adds its plane.
pub fn solve(
    ctx: &mut BuildCtx<'_>,
    collar: Collar,
    neckline: &GarmentRing,
    planes: &mut Vec<NamedPlane>,
) -> Result<Option<GarmentRing>, FrameworkError> {
    if collar == Collar::None {
        return Ok(None);
    }
    let h = ctx.height;
    let n = neckline.stages.control.len().max(1) as f64;
    let base_centre = neckline.stages.control.iter().sum::<DVec3>() / n;
    let e_default = ctx.dims.get("collar_ease").unwrap_or(ctx.ease);
    let jaw = neck_reach(ctx, &neckline.plane, base_centre);
    let most = (jaw - e_default).min(0.045 * h);
    let rise = ctx.value(
        "collar_height",
        (HEIGHT * h).min(0.5 * most),
        (0.005 * h, most),
        "the collar must stand on the neck, its top an ease below the jaw",
    )?;
    let angle = ctx.value(
        "collar_angle",
        0.0,
        (-30.0, 45.0),
        "the collar may lean out up to 45 degrees and in by 30",
    )?;
    let e = ctx.ring_ease(RING)?;
    let lean = rise * angle.to_radians().tan();
    if e + lean < 0.0 {
        return Err(FrameworkError::Dimension {
            name: "collar_angle".into(),
            value: angle,
            reason: format!(
                "leaning in this far would take the collar's top {:.4} m into the neck (collar_ease {e:.4} m): lean less or add ease",
                -(e + lean)
            ),
        });
    }
    let plane = Plane {
        normal: neckline.plane.normal,
        offset: neckline.plane.offset + rise,
    };
    let centre = base_centre + plane.normal * rise;
    let neck = ctx.loop_around(&plane, centre).ok_or_else(|| {
        section_error(
            RING,
            "the plane over the neckline cuts no closed loop of the neck".into(),
        )
    })?;
    let ring = ctx.ring(RING, plane, vec![neck], &quad_anchors(), Ease::Uniform(e + lean))?;
    planes.push(ctx.plane_for(RING, plane, centre));
    Ok(Some(ring))
}

/// The collar's four patches between the neckline and its top ring, `neck` segments along
/// each neckline arc (the panels' count there), `up` segments up.
pub fn collar_patches(s: &mut Surfacer<'_>, neck: usize, up: usize) -> Result<(), FrameworkError> {
    let fw = s.framework();
    for i in 0..4 {
        let (a, b) = (QUAD[i], QUAD[(i + 1) % 4]);
        let bottom = arc(fw, "neckline", a, b, neck)?;
        let top = arc(fw, RING, a, b, neck)?;
        let left = s.span(CONTOURS[i], "neckline", up)?;
        let right = s.span(CONTOURS[(i + 1) % 4], "neckline", up)?;
        let curves = vec![
            CurveRef::whole("neckline"),
            CurveRef::whole(RING),
            s.span_ref(CONTOURS[i], "neckline")?,
            s.span_ref(CONTOURS[(i + 1) % 4], "neckline")?,
        ];
        s.patch(&format!("collar.{a}"), [&bottom, &top, &left, &right], curves)?;
    }
    Ok(())
}

/// How far over the neckline's plane (along its normal, from `centre`) the neck stays a
/// neck, m: the last rise, in steps of a 400th of the body's height, before the section's
/// area grows past 1.3 times the least seen below it (the jaw and the chin join it) or its
/// centre moves off the neck's by more than the neck's radius.
fn neck_reach(ctx: &BuildCtx<'_>, neckline: &Plane, centre: DVec3) -> f64 {
    let h = ctx.height;
    let step = h / 400.0;
    let mut least = f64::INFINITY;
    let mut reach = 0.0;
    for i in 0..=40 {
        let rise = step * i as f64;
        let plane = Plane {
            normal: neckline.normal,
            offset: neckline.offset + rise,
        };
        let at = centre + plane.normal * rise;
        let Some(l) = ctx.loop_around(&plane, at) else {
            break;
        };
        let flat: Vec<glam::DVec2> = l.iter().map(|p| plane.project(*p)).collect();
        let area = polygon::signed_area(&flat).abs();
        let radius = (area / std::f64::consts::PI).sqrt();
        let mid = l.iter().sum::<DVec3>() / l.len() as f64;
        if area > 1.3 * least || mid.distance(at) > radius {
            break;
        }
        least = least.min(area);
        reach = rise;
    }
    reach
}
