//! The heights the jumpsuit's curves are cut at, from the landmarks, and the dimensions
//! that place them (`inseam`, `neck_rise`, `strap_position`).

use glam::DVec3;

use super::cut::Jumpsuit;
use crate::body::{LandmarkKind, Side};
use crate::garment::bridge::{Bridging, bridge};
use crate::garment::model::{FrameworkError, Sleeves};
use crate::garment::solve::{BuildCtx, landmark};
use crate::garment::template::spec::{BRIDGE_REACH, THIGH_DROP};

/// With sleeves, how far the chest ring drops below the armpit, as a fraction of the body's
/// height.
const UNDERARM_DROP: f64 = 0.01;

/// The heights the jumpsuit's curves are cut at, m, and the dimensions that place them.
pub(super) struct Levels {
    /// The body's height.
    pub(super) h: f64,
    /// The chest ring's: just below the armpit.
    pub(super) chest_y: f64,
    /// The crotch landmark.
    pub(super) crotch_ref: DVec3,
    /// The thigh rings': below where the legs part.
    pub(super) thigh_y: f64,
    /// The thigh rings' height from the landmarks alone (the mesh's counts come from it: the
    /// topology must not depend on the ease).
    pub(super) thigh_count_y: f64,
    pub(super) knee_y: f64,
    pub(super) ankle_y: f64,
    pub(super) hem_y: f64,
    pub(super) shoulder_y: f64,
    /// The neckline's rise over the neck base (`neck_rise`).
    pub(super) neck_rise: f64,
    /// Where the straps cross the shoulders, from the side neck (0) to the shoulder point
    /// (1) (`strap_position`).
    pub(super) strap_position: f64,
    /// Every landmark's height.
    pub(super) heights: [(LandmarkKind, f64); 4],
}

impl Levels {
    /// A landmark's height among those kept (bust, waist, hip, shoulder).
    pub(super) fn y_of(&self, kind: LandmarkKind) -> f64 {
        self.heights
            .iter()
            .find(|(k, _)| *k == kind)
            .map_or(f64::NAN, |(_, y)| *y)
    }
}

/// How the curves bridge a gap of the body `gap` deep (the crotch curve and the straps).
pub(super) fn bridging(ctx: &BuildCtx<'_>, gap: f64) -> Bridging {
    Bridging {
        gap,
        width: (2.0 * gap).max(ctx.edge_length()),
        reach: BRIDGE_REACH * ctx.height,
    }
}

/// The levels, and the dimensions `inseam`, `neck_rise` and `strap_position`.
pub(super) fn levels(ctx: &mut BuildCtx<'_>, cut: &Jumpsuit) -> Result<Levels, FrameworkError> {
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
