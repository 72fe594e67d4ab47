//! The dress (a skirt from the waist): waist, hip, thigh and hem rings, the rings below the
//! hip wrapping both legs; four contours (centre front and back, the sides), straight below
//! the hip (always the loose fit); twelve patches.

use glam::DVec3;

use super::spec::{CurveRoles, THIGH_DROP, Template};
use crate::body::LandmarkKind;
use crate::garment::anchors::{QUAD, mirror_pairs, quad_anchors};
use crate::garment::m0::CurveRef;
use crate::garment::model::{Counts, FeatureLine, Fit, FrameworkError, TemplateKind};
use crate::garment::solve::{BuildCtx, ContourSpec, Parts, fit_contours, loosen};
use crate::garment::surface::{Surfacer, arc, missing};
use crate::geom::Plane;

/// Rings of the dress, top to bottom.
pub const RINGS: [&str; 4] = ["waist", "hip", "thigh", "hem"];

/// Contours of the dress, in ring order from the front.
pub const CONTOURS: [&str; 4] = ["centre_front", "side_left", "centre_back", "side_right"];

/// The dress template.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dress;

impl Template for Dress {
    fn kind(&self) -> TemplateKind {
        TemplateKind::Dress
    }

    fn rings(&self) -> Vec<&'static str> {
        RINGS.to_vec()
    }

    fn lengths(&self) -> Vec<(&'static str, &'static str)> {
        vec![(
            "length",
            "waist height minus hem height, m (default: down to the knees)",
        )]
    }

    fn ring_anchors(&self) -> Vec<(&'static str, &'static [&'static str])> {
        RINGS.iter().map(|r| (*r, &QUAD[..])).collect()
    }

    fn contours(&self) -> Vec<&'static str> {
        CONTOURS.to_vec()
    }

    fn fit(&self, _asked: Fit) -> Fit {
        Fit::Loose
    }

    fn curves(&self, ctx: &mut BuildCtx<'_>, _fit: Fit) -> Result<Parts, FrameworkError> {
        solve(ctx)
    }

    fn patches(&self, s: &mut Surfacer<'_>, _lines: &[FeatureLine]) -> Result<(), FrameworkError> {
        patches(s)
    }

    fn roles(&self) -> CurveRoles {
        // Every ring wraps the body's middle, so every ring is centred.
        CurveRoles {
            centred: RINGS.iter().map(|r| (*r, mirror_pairs(&QUAD))).collect(),
            ..CurveRoles::default()
        }
    }
}

fn solve(ctx: &mut BuildCtx<'_>) -> Result<Parts, FrameworkError> {
    let body = ctx.body;
    let lm = &body.landmarks;
    let h = ctx.height;
    let (floor, _) = body.mesh.mesh.bounds().map_or((DVec3::ZERO, DVec3::ZERO), |b| b);
    let waist_y = lm.height(LandmarkKind::Waist);
    let hip_y = lm.height(LandmarkKind::Hip);
    let crotch_y = lm.height(LandmarkKind::Crotch);
    let thigh_y = crotch_y - THIGH_DROP * h;
    let knee_y = lm.height(LandmarkKind::Knee);
    let length = ctx.value(
        "length",
        waist_y - knee_y,
        (waist_y - thigh_y + 0.05 * h, waist_y - floor.y - 0.02 * h),
        "the hem must lie between the thigh and the floor",
    )?;
    let hem_y = waist_y - length;
    let mut rings = Vec::new();
    let mut planes = Vec::new();
    for (name, y) in [("waist", waist_y), ("hip", hip_y)] {
        let raw = ctx.torso_loop(name, y)?;
        let e = ctx.ring_ease(name)?;
        let ease = ctx.limited_ease(y, std::slice::from_ref(&raw), e);
        rings.push(ctx.ring(name, Plane::horizontal(y), vec![raw], &quad_anchors(), ease)?);
    }
    for (name, y) in [("thigh", thigh_y), ("hem", hem_y)] {
        let raw: Vec<Vec<DVec3>> = ctx.leg_loops(name, y)?.into_iter().map(|(_, p)| p).collect();
        let e = ctx.ring_ease(name)?;
        let ease = ctx.limited_ease(y, &raw, e);
        rings.push(ctx.ring(name, Plane::horizontal(y), raw, &quad_anchors(), ease)?);
    }
    for r in &rings {
        let y = r.plane.offset;
        let centre = lm
            .torso_at(y)
            .map_or(DVec3::new(ctx.mid_x, y, 0.0), |t| DVec3::new(t.x, y, t.y));
        planes.push(ctx.plane_for(&r.name, r.plane, centre));
    }
    let levels = ["hem", "thigh", "hip", "waist"];
    let names = CONTOURS;
    let specs: Vec<ContourSpec> = names
        .iter()
        .zip(QUAD)
        .map(|(n, a)| {
            (
                n.to_string(),
                levels.iter().map(|l| (l.to_string(), a.to_string())).collect(),
            )
        })
        .collect();
    let straightened = loosen(&mut rings, &specs, "hip", &ctx.options.ring)?;
    let contours = fit_contours(&specs, &rings, &[], ctx.options.contours)?;
    let layout = ctx.layout(Counts::Dress(
        [thigh_y - knee_y, hip_y - thigh_y, waist_y - hip_y].map(|dy| ctx.segments(dy, 1.0)),
    ));
    Ok(Parts {
        planes,
        rings,
        open_curves: Vec::new(),
        contours,
        straightened,
        layout,
    })
}

fn patches(s: &mut Surfacer<'_>) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let Counts::Dress(nv) = s.layout().counts else {
        return Err(missing("layout", "not a dress's"));
    };
    let k = s.layout().k;
    let names = CONTOURS;
    for ((lo, hi), nv) in [("hem", "thigh"), ("thigh", "hip"), ("hip", "waist")]
        .into_iter()
        .zip(nv)
    {
        for i in 0..4 {
            let (a, b) = (QUAD[i], QUAD[(i + 1) % 4]);
            let bottom = arc(fw, lo, a, b, 2 * k)?;
            let top = arc(fw, hi, a, b, 2 * k)?;
            let left = s.span(names[i], lo, nv)?;
            let right = s.span(names[(i + 1) % 4], lo, nv)?;
            let curves = vec![
                CurveRef::whole(lo),
                CurveRef::whole(hi),
                s.span_ref(names[i], lo)?,
                s.span_ref(names[(i + 1) % 4], lo)?,
            ];
            s.patch(&format!("skirt.{lo}_{hi}.{a}"), [&bottom, &top, &left, &right], curves)?;
        }
    }
    Ok(())
}
