//! The jumpsuit's open curves: the crotch curve in the vertical crotch plane and a strap
//! over each shoulder in its vertical plane (\[frame\] section 2.4).

use glam::DVec3;

use super::levels::{Levels, bridging};
use crate::body::{LandmarkKind, Side};
use crate::garment::ease::Ease;
use crate::garment::model::{FrameworkError, NamedPlane};
use crate::garment::open_curve::{Apex, OpenCurve, OpenInput, section_part};
use crate::garment::ring::GarmentRing;
use crate::garment::solve::{BuildCtx, find, landmark, point, section_error};
use crate::geom::{Plane, section_mesh};

/// The open curves: the crotch curve in the vertical crotch plane, from the hip's centre
/// front down through the crotch and up to its centre back; then a strap over each
/// shoulder in its plane `(xl, xr)`, from the chest ring's front princess anchor to its
/// back one. Adds their planes.
pub(super) fn open_curves(
    ctx: &BuildCtx<'_>,
    lv: &Levels,
    (xl, xr): (f64, f64),
    rings: &[GarmentRing],
    planes: &mut Vec<NamedPlane>,
    legs: bool,
) -> Result<Vec<OpenCurve>, FrameworkError> {
    let mut open_curves = if legs {
        vec![crotch_curve(ctx, lv, rings, planes)?]
    } else {
        Vec::new()
    };
    straps(ctx, lv, (xl, xr), rings, planes, &mut open_curves)?;
    Ok(open_curves)
}

/// The crotch curve in the vertical crotch plane, from the hip's centre front down through
/// the crotch and up to its centre back. Adds its plane.
fn crotch_curve(
    ctx: &BuildCtx<'_>,
    lv: &Levels,
    rings: &[GarmentRing],
    planes: &mut Vec<NamedPlane>,
) -> Result<OpenCurve, FrameworkError> {
    let body = ctx.body;
    let crotch_ref = lv.crotch_ref;
    let hip_y = lv.y_of(LandmarkKind::Hip);
    let crotch_plane = Plane::from_point_normal(DVec3::new(ctx.mid_x, 0.0, 0.0), DVec3::X);
    planes.push(ctx.plane_for(
        "crotch",
        crotch_plane,
        DVec3::new(ctx.mid_x, crotch_ref.y, crotch_ref.z),
    ));
    let crotch_part = section_mesh(&body.mesh.mesh, &body.mesh.adjacency, &crotch_plane)
        .iter()
        .filter_map(|l| section_part(l, hip_y, Apex::Lowest))
        .min_by(|a, b| a.0[a.1].distance(crotch_ref).total_cmp(&b.0[b.1].distance(crotch_ref)))
        .ok_or_else(|| section_error("crotch", "the crotch plane cuts no curve below the hip".into()))?;
    let per_half = ctx.options.ring.resample_per_arc;
    let crotch = OpenCurve::build(&OpenInput {
        name: "crotch",
        apex_name: "point",
        plane: crotch_plane,
        raw: crotch_part,
        ease: Ease::Uniform(ctx.ease),
        ends: [point(rings, "hip", "front")?, point(rings, "hip", "back")?],
        per_half,
        control_per_half: 4,
        fitted_per_half: ctx.options.ring.fitted_points / 4,
        bridge: Some((ctx.probe, bridging(ctx, ctx.ease))),
    })?;
    Ok(crotch)
}

/// A strap over each shoulder in its plane `(xl, xr)`, from the chest ring's front princess
/// anchor to its back one: added to `open_curves`. Adds their planes.
fn straps(
    ctx: &BuildCtx<'_>,
    lv: &Levels,
    (xl, xr): (f64, f64),
    rings: &[GarmentRing],
    planes: &mut Vec<NamedPlane>,
    open_curves: &mut Vec<OpenCurve>,
) -> Result<(), FrameworkError> {
    let body = ctx.body;
    let h = lv.h;
    let per_half = ctx.options.ring.resample_per_arc;
    for (side, x) in [(Side::Left, xl), (Side::Right, xr)] {
        let (name, suffix) = if side == Side::Left {
            ("left_strap", "left")
        } else {
            ("right_strap", "right")
        };
        let plane = Plane::from_point_normal(DVec3::new(x, 0.0, 0.0), DVec3::X);
        let reference = landmark(body, LandmarkKind::Shoulder, side)?;
        let reference = DVec3::new(x, lv.shoulder_y, reference.z);
        planes.push(ctx.plane_for(name, plane, DVec3::new(x, lv.shoulder_y - 0.04 * h, reference.z)));
        let part = section_mesh(&body.mesh.mesh, &body.mesh.adjacency, &plane)
            .iter()
            .filter_map(|l| section_part(l, lv.chest_y, Apex::Highest))
            .min_by(|a, b| a.0[a.1].distance(reference).total_cmp(&b.0[b.1].distance(reference)))
            .ok_or_else(|| section_error(name, "the strap plane cuts no curve over the shoulder".into()))?;
        let e = match find(rings, "chest")?.ease {
            Ease::Uniform(v) => v,
            Ease::PerDirection { front, .. } => front,
        };
        let strap = OpenCurve::build(&OpenInput {
            name,
            apex_name: "top",
            plane,
            raw: part,
            ease: Ease::Uniform(e),
            ends: [
                point(rings, "chest", &format!("front_{suffix}"))?,
                point(rings, "chest", &format!("back_{suffix}"))?,
            ],
            per_half,
            control_per_half: 4,
            fitted_per_half: ctx.options.ring.fitted_points / 4,
            bridge: Some((ctx.probe, bridging(ctx, e))),
        })?;
        open_curves.push(strap);
    }
    Ok(())
}
