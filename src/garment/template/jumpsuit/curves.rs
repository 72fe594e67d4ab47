//! The jumpsuit's curves on a body: the neckline in the neck-base plane, the straps in
//! vertical planes across the shoulders, the torso rings (chest, bust, waist, hip) with the
//! princess anchors in the strap planes, the leg rings (thigh, knee, hem), the crotch curve
//! in the vertical crotch plane, and the contours through the anchors (\[frame\] sections
//! 2.1-2.5).

use glam::DVec3;

use crate::body::{LandmarkKind, Side};
use crate::garment::anchors::{leg_anchors, quad_anchors, torso_anchors};
use crate::garment::contour::Contour;
use crate::garment::ease::Ease;
use crate::garment::model::{Counts, Fit, FrameworkError, Layout, NamedPlane, Sleeves, Straightened};
use crate::garment::open_curve::OpenCurve;
use crate::garment::ring::GarmentRing;
use crate::garment::solve::{BuildCtx, ContourSpec, Parts, find, fit_contours, landmark, loosen, point, section_error};
use crate::garment::template::{collar, sleeve};

use super::cut::Jumpsuit;
use super::levels::{Levels, levels};
use super::open_curves::open_curves;
use crate::geom::{Plane, SectionLoop, section_mesh};

/// Solves the jumpsuit's curves on the body.
pub(super) fn solve(ctx: &mut BuildCtx<'_>, fit: Fit, cut: &Jumpsuit) -> Result<Parts, FrameworkError> {
    let lv = levels(ctx, cut)?;
    let mut planes = Vec::new();
    let neckline = neckline(ctx, lv.neck_rise, &mut planes)?;
    let collar = collar::solve(ctx, cut.style.collar, &neckline, &mut planes)?;
    // Straps: vertical planes across each shoulder.
    let body = ctx.body;
    let strap_x = |side: Side| -> Result<f64, FrameworkError> {
        let sn = landmark(body, LandmarkKind::SideNeck, side)?;
        let sh = landmark(body, LandmarkKind::Shoulder, side)?;
        Ok(sn.x + lv.strap_position * (sh.x - sn.x))
    };
    let straps = (strap_x(Side::Left)?, strap_x(Side::Right)?);
    let mut rings = vec![neckline];
    let princess = chest_ring(ctx, &lv, straps, &mut rings)?;
    torso_and_leg_rings(ctx, &lv, princess, &mut rings, cut.legs)?;
    let levels = [
        ("chest", lv.chest_y),
        ("bust", lv.y_of(LandmarkKind::Bust)),
        ("waist", lv.y_of(LandmarkKind::Waist)),
        ("hip", lv.y_of(LandmarkKind::Hip)),
        ("thigh", lv.thigh_y),
        ("knee", lv.knee_y),
        ("hem", lv.hem_y),
    ];
    for (name, y) in &levels[..if cut.legs { 7 } else { 4 }] {
        let (name, y) = (*name, *y);
        let centre = body
            .landmarks
            .torso_at(y)
            .map_or(DVec3::new(ctx.mid_x, y, 0.0), |t| DVec3::new(t.x, y, t.y));
        planes.push(ctx.plane_for(name, Plane::horizontal(y), centre));
    }
    let open_curves = open_curves(ctx, &lv, straps, &rings, &mut planes, cut.legs)?;
    let mut armholes = [[DVec3::ZERO; 4]; 2];
    if cut.style.sleeves != Sleeves::None {
        for (k, s) in ["left", "right"].into_iter().enumerate() {
            let strap = open_curves
                .iter()
                .find(|c| c.name == format!("{s}_strap"))
                .ok_or_else(|| section_error(s, "no strap".into()))?;
            armholes[k] = sleeve::ArmholePoints::new(strap, point(&rings, "chest", s)?).all();
        }
    }
    let sleeve_rings = sleeve::solve(ctx, cut.style.sleeves, armholes, &mut planes)?;
    rings.extend(sleeve_rings);
    rings.extend(collar);
    let (contours, straightened) = contours(ctx, fit, &mut rings, &open_curves, cut)?;
    let layout = layout(ctx, &lv, &rings, cut)?;
    Ok(Parts {
        planes,
        rings,
        open_curves,
        contours,
        straightened,
        layout,
    })
}

/// The neckline: the body's section by the neck-base plane shifted up by the rise, the
/// loop nearest the neck's landmarks. Adds the neck-base and upper neck planes.
fn neckline(
    ctx: &mut BuildCtx<'_>,
    neck_rise: f64,
    planes: &mut Vec<NamedPlane>,
) -> Result<GarmentRing, FrameworkError> {
    let body = ctx.body;
    let h = ctx.height;
    let base = body
        .landmarks
        .neck_plane()
        .ok_or_else(|| section_error("neckline", "the neck landmarks do not span a plane".into()))?;
    let neck_plane = Plane {
        normal: base.normal,
        offset: base.offset + neck_rise,
    };
    let neck_centre = [
        landmark(body, LandmarkKind::FrontNeck, Side::Centre)?,
        landmark(body, LandmarkKind::SideNeck, Side::Left)?,
        landmark(body, LandmarkKind::SideNeck, Side::Right)?,
    ]
    .iter()
    .sum::<DVec3>()
        / 3.0;
    let upper_neck = Plane {
        normal: base.normal,
        offset: base.offset + 0.03 * h,
    };
    planes.push(ctx.plane_for("neck_base", base, neck_centre));
    planes.push(ctx.plane_for("neck_upper", upper_neck, neck_centre + base.normal * 0.03 * h));
    let neck_loops = section_mesh(&body.mesh.mesh, &body.mesh.adjacency, &neck_plane);
    let neck_loop = neck_loops
        .iter()
        .filter(|l| l.closed)
        .min_by(|a, b| {
            let c = |l: &SectionLoop| l.points.iter().sum::<DVec3>() / l.points.len() as f64;
            c(a).distance(neck_centre).total_cmp(&c(b).distance(neck_centre))
        })
        .ok_or_else(|| section_error("neckline", "the neck plane cuts no closed loop".into()))?;
    let e = ctx.ring_ease("neckline")?;
    ctx.ring(
        "neckline",
        neck_plane,
        vec![neck_loop.points.clone()],
        &quad_anchors(),
        Ease::Uniform(e),
    )
}

/// The chest ring, its princess anchors in the strap planes `(xl, xr)`: added to `rings`.
/// Returns the princess fractions of the eased half widths that put them there.
fn chest_ring(
    ctx: &mut BuildCtx<'_>,
    lv: &Levels,
    (xl, xr): (f64, f64),
    rings: &mut Vec<GarmentRing>,
) -> Result<(f64, f64), FrameworkError> {
    let chest_y = lv.chest_y;
    let chest_raw = ctx.torso_loop("chest", chest_y)?;
    let e = ctx.ring_ease("chest")?;
    let chest_anchors = {
        let (xmax, xmin) = chest_raw
            .iter()
            .fold((f64::NEG_INFINITY, f64::INFINITY), |(a, b), p| (a.max(p.x), b.min(p.x)));
        let (hl, hr) = (xmax + e - ctx.mid_x, ctx.mid_x - (xmin - e));
        if !(xl - ctx.mid_x < 0.95 * hl && ctx.mid_x - xr < 0.95 * hr) {
            return Err(section_error(
                "straps",
                format!("the strap planes (x = {xl:.4}, {xr:.4} m) miss the chest ring; lower strap_position"),
            ));
        }
        // Fractions of the eased half width; refined below on the eased ring itself.
        torso_anchors((xl - ctx.mid_x) / hl, (ctx.mid_x - xr) / hr)
    };
    let chest_ease = ctx.limited_ease(chest_y, std::slice::from_ref(&chest_raw), e);
    let chest = ctx.ring(
        "chest",
        Plane::horizontal(chest_y),
        vec![chest_raw.clone()],
        &chest_anchors,
        chest_ease,
    )?;
    // The princess fractions that put the chest anchors exactly in the strap planes.
    let (cxmax, cxmin) = chest
        .stages
        .eased
        .iter()
        .fold((f64::NEG_INFINITY, f64::INFINITY), |(a, b), p| (a.max(p.x), b.min(p.x)));
    let (fl, fr) = (
        (xl - ctx.mid_x) / (cxmax - ctx.mid_x),
        (ctx.mid_x - xr) / (ctx.mid_x - cxmin),
    );
    ctx.dimensions.retain(|d| d.name != "chest_girth");
    let chest = ctx.ring(
        "chest",
        Plane::horizontal(chest_y),
        vec![chest_raw],
        &torso_anchors(fl, fr),
        chest_ease,
    )?;
    rings.push(chest);
    Ok((fl, fr))
}

/// The bust, waist and hip rings (princess fractions `(fl, fr)`), then the thigh, knee and
/// hem rings of each leg: added to `rings`.
fn torso_and_leg_rings(
    ctx: &mut BuildCtx<'_>,
    lv: &Levels,
    (fl, fr): (f64, f64),
    rings: &mut Vec<GarmentRing>,
    legs: bool,
) -> Result<(), FrameworkError> {
    for (name, kind) in [
        ("bust", LandmarkKind::Bust),
        ("waist", LandmarkKind::Waist),
        ("hip", LandmarkKind::Hip),
    ] {
        let y = lv.y_of(kind);
        let raw = ctx.torso_loop(name, y)?;
        let e = ctx.ring_ease(name)?;
        let ease = ctx.limited_ease(y, std::slice::from_ref(&raw), e);
        let r = ctx.ring(name, Plane::horizontal(y), vec![raw], &torso_anchors(fl, fr), ease)?;
        rings.push(r);
    }
    if !legs {
        return Ok(());
    }
    for (level, y) in [("thigh", lv.thigh_y), ("knee", lv.knee_y), ("hem", lv.hem_y)] {
        let loops = ctx.leg_loops(level, y)?;
        for side in [Side::Left, Side::Right] {
            let name = format!("{}_{level}", if side == Side::Left { "left" } else { "right" });
            let raw = loops
                .iter()
                .find(|(s, _)| *s == side)
                .map(|(_, p)| p.clone())
                .ok_or_else(|| section_error(&name, "no leg loop on this side".into()))?;
            let e = ctx.ring_ease(&name)?;
            let ease = ctx.limited_ease(y, std::slice::from_ref(&raw), e);
            let r = ctx.ring(&name, Plane::horizontal(y), vec![raw], &leg_anchors(side), ease)?;
            rings.push(r);
        }
    }
    Ok(())
}

/// The contours (lowest point first), the leg rings straightened below the thigh for a
/// loose fit, and the princess lines run on into the straps' end tangents.
fn contours(
    ctx: &BuildCtx<'_>,
    fit: Fit,
    rings: &mut [GarmentRing],
    open_curves: &[OpenCurve],
    cut: &Jumpsuit,
) -> Result<(Vec<Contour>, Vec<Straightened>), FrameworkError> {
    let side_names = [(Side::Left, "left"), (Side::Right, "right")];
    let mut specs: Vec<ContourSpec> = Vec::new();
    let torso_levels = ["hip", "waist", "bust", "chest"];
    let pts = |levels: &[&str], anchor: &str| -> Vec<(String, String)> {
        levels.iter().map(|l| (l.to_string(), anchor.to_string())).collect()
    };
    specs.push(("centre_front".into(), pts(&torso_levels, "front")));
    specs.push(("centre_back".into(), pts(&torso_levels, "back")));
    for (_, s) in side_names {
        let leg = |a: &str| -> Vec<(String, String)> {
            if !cut.legs {
                return Vec::new();
            }
            ["hem", "knee", "thigh"]
                .iter()
                .map(|l| (format!("{s}_{l}"), a.to_string()))
                .collect()
        };
        let mut front = leg("front");
        front.extend(pts(&torso_levels, &format!("front_{s}")));
        let mut side = leg("outer");
        side.extend(pts(&torso_levels, s));
        let mut back = leg("back");
        back.extend(pts(&torso_levels, &format!("back_{s}")));
        let mut inner = leg("inner");
        inner.push(("crotch".into(), "point".into()));
        specs.push((format!("front_{s}"), front));
        specs.push((format!("side_{s}"), side));
        specs.push((format!("back_{s}"), back));
        if cut.legs {
            specs.push((format!("inner_{s}"), inner));
        }
    }
    let mut straightened = Vec::new();
    if fit == Fit::Loose {
        let leg_specs: Vec<ContourSpec> = specs
            .iter()
            .map(|(n, p)| {
                (
                    n.clone(),
                    p.iter()
                        .filter(|(r, _)| r.ends_with("hem") || r.ends_with("knee") || r.ends_with("thigh"))
                        .cloned()
                        .collect(),
                )
            })
            .collect();
        for (_, s) in side_names {
            let fixed = format!("{s}_thigh");
            let mine: Vec<ContourSpec> = leg_specs
                .iter()
                .filter(|(_, p)| p.first().is_some_and(|(r, _)| r.starts_with(s)))
                .cloned()
                .collect();
            // `loosen` reads points lowest first and straightens below the fixed ring.
            straightened.extend(loosen(rings, &mine, &fixed, &ctx.options.ring)?);
        }
    }
    let apexes: Vec<(String, DVec3)> = open_curves
        .iter()
        .map(|c| (format!("{}.{}", c.name, c.apex_name), c.apex))
        .collect();
    specs.extend(sleeve::contour_specs(cut.style.sleeves));
    specs.extend(collar::contour_specs(cut.style.collar));
    let mut contours = fit_contours(&specs, rings, &apexes, ctx.options.contours)?;
    // The princess lines run on into the straps: each meets its strap's end tangent.
    for c in &mut contours {
        let strap = match c.name.split_once('_') {
            Some((part @ ("front" | "back"), side @ ("left" | "right"))) => Some((part == "front", side)),
            _ => None,
        };
        if let Some((front, side)) = strap {
            let name = format!("{side}_strap");
            let Some(strap) = open_curves.iter().find(|c| c.name == name) else {
                continue;
            };
            let t = strap.end_tangent(front);
            c.refit(c.points.clone(), [None, Some(t)])
                .map_err(|e| FrameworkError::Contour(c.name.clone(), e))?;
        }
    }
    Ok((contours, straightened))
}

/// The mesh's sample counts, from the landmarks (not the hem dimension: the topology stays
/// fixed).
fn layout(ctx: &BuildCtx<'_>, lv: &Levels, rings: &[GarmentRing], cut: &Jumpsuit) -> Result<Layout, FrameworkError> {
    let k = ctx.options.resolution.max(2);
    let seam = (k / 3).max(1);
    let hip_y = lv.y_of(LandmarkKind::Hip);
    let junction = ctx.segments(hip_y - lv.thigh_count_y, 1.0);
    let inner = (junction / 3).max(1);
    let mut torso = [0; 3];
    for (n, (lo, hi)) in torso
        .iter_mut()
        .zip([("hip", "waist"), ("waist", "bust"), ("bust", "chest")])
    {
        let (ylo, yhi) = (find(rings, lo)?.plane.offset, find(rings, hi)?.plane.offset);
        *n = ctx.segments(yhi - ylo, 1.0);
    }
    let leg = [lv.knee_y - lv.ankle_y, lv.thigh_count_y - lv.knee_y].map(|dy| ctx.segments(dy, 1.0));
    let sleeve = sleeve::band_counts(ctx, cut.style.sleeves)?;
    let armhole = if sleeve.is_empty() {
        0
    } else {
        ctx.segments(0.5 * (lv.shoulder_y - lv.chest_y), 1.5)
    };
    let collar = collar::band_count(ctx, cut.style.collar);
    Ok(ctx.layout(Counts::Jumpsuit {
        seam,
        neck: k - seam,
        junction,
        inner,
        crotch: junction - inner,
        strap: ctx.segments(lv.shoulder_y - lv.chest_y, 1.5),
        torso,
        leg,
        sleeve,
        armhole,
        collar,
    }))
}
