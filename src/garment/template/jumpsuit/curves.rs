//! The jumpsuit's curves on a body: the neckline in the neck-base plane, the straps in
//! vertical planes across the shoulders, the torso rings (chest, bust, waist, hip) with the
//! princess anchors in the strap planes, the leg rings (thigh, knee, hem), the crotch curve
//! in the vertical crotch plane, and the contours through the anchors (\[frame\] sections
//! 2.1-2.5).

use glam::DVec3;

use crate::body::{LandmarkKind, Side};
use crate::garment::anchors::{leg_anchors, quad_anchors, torso_anchors};
use crate::garment::bridge::{Bridging, bridge};
use crate::garment::contour::Contour;
use crate::garment::ease::Ease;
use crate::garment::model::{Counts, Fit, FrameworkError, Layout, NamedPlane, Sleeves, Straightened};
use crate::garment::open_curve::{Apex, OpenCurve, OpenInput, section_part};
use crate::garment::ring::GarmentRing;
use crate::garment::solve::{BuildCtx, ContourSpec, Parts, find, fit_contours, landmark, loosen, point, section_error};
use crate::garment::template::spec::{BRIDGE_REACH, THIGH_DROP};
use crate::garment::template::{collar, sleeve};

use super::Jumpsuit;
use crate::geom::{Plane, SectionLoop, section_mesh};

/// With sleeves, how far the chest ring drops below the armpit, as a fraction of the body's
/// height.
const UNDERARM_DROP: f64 = 0.01;

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

/// The heights the jumpsuit's curves are cut at, m, and the dimensions that place them.
struct Levels {
    /// The body's height.
    h: f64,
    /// The chest ring's: just below the armpit.
    chest_y: f64,
    /// The crotch landmark.
    crotch_ref: DVec3,
    /// The thigh rings': below where the legs part.
    thigh_y: f64,
    /// The thigh rings' height from the landmarks alone (the mesh's counts come from it: the
    /// topology must not depend on the ease).
    thigh_count_y: f64,
    knee_y: f64,
    ankle_y: f64,
    hem_y: f64,
    shoulder_y: f64,
    /// The neckline's rise over the neck base (`neck_rise`).
    neck_rise: f64,
    /// Where the straps cross the shoulders, from the side neck (0) to the shoulder point
    /// (1) (`strap_position`).
    strap_position: f64,
    /// Every landmark's height.
    heights: [(LandmarkKind, f64); 4],
}

impl Levels {
    /// A landmark's height among those kept (bust, waist, hip, shoulder).
    fn y_of(&self, kind: LandmarkKind) -> f64 {
        self.heights
            .iter()
            .find(|(k, _)| *k == kind)
            .map_or(f64::NAN, |(_, y)| *y)
    }
}

/// How the curves bridge a gap of the body `gap` deep (the crotch curve and the straps).
fn bridging(ctx: &BuildCtx<'_>, gap: f64) -> Bridging {
    Bridging {
        gap,
        width: (2.0 * gap).max(ctx.edge_length()),
        reach: BRIDGE_REACH * ctx.height,
    }
}

/// The levels, and the dimensions `inseam`, `neck_rise` and `strap_position`.
fn levels(ctx: &mut BuildCtx<'_>, cut: &Jumpsuit) -> Result<Levels, FrameworkError> {
    let body = ctx.body;
    let lm = &body.landmarks;
    let h = ctx.height;
    let (floor, _) = body.mesh.mesh.bounds().map_or((DVec3::ZERO, DVec3::ZERO), |b| b);
    let eps = 2e-3 * h;
    let y_of = |k: LandmarkKind| lm.height(k);
    // With sleeves the chest ring (whose side is the armhole's lowest point) runs a little
    // lower, on the torso's side below the armpit's hollow: the sleeve's cap bridges the
    // hollow from there.
    let drop = if cut.style.sleeves == Sleeves::None {
        0.0
    } else {
        UNDERARM_DROP * h
    };
    let chest_y = y_of(LandmarkKind::Armpit) - eps - drop;
    let crotch_y = y_of(LandmarkKind::Crotch);
    // Where the legs part: the crotch, or lower where the thighs meet below it and leave
    // the garment no room (the crotch curve bridges that gap, so the thigh rings go below).
    let crotch_ref = landmark(body, LandmarkKind::Crotch, Side::Centre)?;
    let below = DVec3::new(ctx.mid_x, crotch_y - ctx.ease, crotch_ref.z);
    let legs_part_y = (bridge(ctx.probe, below, DVec3::NEG_Y, &bridging(ctx, ctx.ease)).y + ctx.ease).min(crotch_y);
    let thigh_y = legs_part_y - THIGH_DROP * h;
    let thigh_count_y = crotch_y - THIGH_DROP * h;
    let knee_y = y_of(LandmarkKind::Knee);
    let ankle_y = y_of(LandmarkKind::Ankle);
    let inseam = if cut.legs {
        ctx.value(
            "inseam",
            crotch_y - ankle_y,
            (crotch_y - knee_y + 0.05 * h, crotch_y - floor.y - 0.02 * h),
            "the hem must lie between the knee and the foot",
        )?
    } else {
        crotch_y - ankle_y
    };
    let neck_rise = ctx.value(
        "neck_rise",
        0.0,
        (-0.02 * h, 0.03 * h),
        "the neckline must stay near the neck base",
    )?;
    // With sleeves the straps are the armholes' tops: as near the shoulder point as the
    // chest ring allows (the strap planes within 85% of its half width), at most 0.8.
    let strap_default = if cut.style.sleeves == Sleeves::None {
        0.5
    } else {
        let chest = ctx.torso_loop("chest", chest_y)?;
        let (xmax, xmin) = chest
            .iter()
            .fold((f64::NEG_INFINITY, f64::INFINITY), |(a, b), p| (a.max(p.x), b.min(p.x)));
        let mid = ctx.mid_x;
        let mut f: f64 = 0.8;
        for (side, edge) in [
            (Side::Left, mid + 0.85 * (xmax - mid)),
            (Side::Right, mid - 0.85 * (mid - xmin)),
        ] {
            let sn = landmark(body, LandmarkKind::SideNeck, side)?;
            let sh = landmark(body, LandmarkKind::Shoulder, side)?;
            if (sh.x - sn.x).abs() > 1e-9 {
                f = f.min((edge - sn.x) / (sh.x - sn.x));
            }
        }
        f.clamp(0.1, 0.8)
    };
    let strap_position = ctx.value(
        "strap_position",
        strap_default,
        (0.1, 0.9),
        "the strap must lie on the shoulder",
    )?;
    Ok(Levels {
        h,
        chest_y,
        crotch_ref,
        thigh_y,
        thigh_count_y,
        knee_y,
        ankle_y,
        hem_y: crotch_y - inseam,
        shoulder_y: y_of(LandmarkKind::Shoulder),
        neck_rise,
        strap_position,
        heights: [
            LandmarkKind::Bust,
            LandmarkKind::Waist,
            LandmarkKind::Hip,
            LandmarkKind::Shoulder,
        ]
        .map(|k| (k, y_of(k))),
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

/// The open curves: the crotch curve in the vertical crotch plane, from the hip's centre
/// front down through the crotch and up to its centre back; then a strap over each
/// shoulder in its plane `(xl, xr)`, from the chest ring's front princess anchor to its
/// back one. Adds their planes.
fn open_curves(
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
