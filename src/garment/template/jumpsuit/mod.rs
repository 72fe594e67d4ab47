//! The sleeveless jumpsuit: a torso tube, two leg tubes joined at the crotch, front and
//! back panels up to the neckline held by straps over the shoulders. 11 rings, the crotch
//! curve and two straps, 10 contours; 50 patches.

mod curves;
mod patches;

use super::spec::{CurveRoles, EndJoint, TangentJoint, Template};
use crate::garment::anchors::{LEFT_LEG, QUAD, RIGHT_LEG, TORSO, mirror_pairs};
use crate::garment::model::{FeatureLine, Fit, Framework, FrameworkError, TemplateKind};
use crate::garment::probe::BodyProbe;
use crate::garment::solve::{BuildCtx, Parts};
use crate::garment::surface::Surfacer;

/// Rings of the jumpsuit, top to bottom.
pub const RINGS: [&str; 11] = [
    "neckline",
    "chest",
    "bust",
    "waist",
    "hip",
    "left_thigh",
    "right_thigh",
    "left_knee",
    "right_knee",
    "left_hem",
    "right_hem",
];

/// Contours of the jumpsuit.
pub const CONTOURS: [&str; 10] = [
    "centre_front",
    "centre_back",
    "front_left",
    "side_left",
    "back_left",
    "inner_left",
    "front_right",
    "side_right",
    "back_right",
    "inner_right",
];

/// The jumpsuit template.
#[derive(Clone, Copy, Debug, Default)]
pub struct Jumpsuit;

impl Template for Jumpsuit {
    fn kind(&self) -> TemplateKind {
        TemplateKind::Jumpsuit
    }

    fn rings(&self) -> &'static [&'static str] {
        &RINGS
    }

    fn lengths(&self) -> &'static [(&'static str, &'static str)] {
        &[
            (
                "inseam",
                "crotch height minus hem height, m (default: down to the ankles)",
            ),
            ("neck_rise", "neckline above the neck-base plane, m (default 0)"),
            (
                "strap_position",
                "where the straps cross the shoulder, 0 at the side neck to 1 at the shoulder point (default 0.5)",
            ),
        ]
    }

    fn ring_anchors(&self) -> Vec<(&'static str, &'static [&'static str])> {
        RINGS
            .iter()
            .map(|r| {
                let anchors: &'static [&'static str] = match *r {
                    "neckline" => &QUAD,
                    r if r.starts_with("left_") => &LEFT_LEG,
                    r if r.starts_with("right_") => &RIGHT_LEG,
                    _ => &TORSO,
                };
                (*r, anchors)
            })
            .collect()
    }

    fn open_curves(&self) -> &'static [(&'static str, &'static str)] {
        &[("crotch", "point"), ("left_strap", "top"), ("right_strap", "top")]
    }

    fn contours(&self) -> &'static [&'static str] {
        &CONTOURS
    }

    fn curves(&self, ctx: &mut BuildCtx<'_>, fit: Fit) -> Result<Parts, FrameworkError> {
        curves::solve(ctx, fit)
    }

    fn lines(&self, fw: &Framework, probe: &BodyProbe) -> Result<Vec<FeatureLine>, FrameworkError> {
        patches::lines(fw, probe)
    }

    fn patches(&self, s: &mut Surfacer<'_>, lines: &[FeatureLine]) -> Result<(), FrameworkError> {
        patches::patches(s, lines)
    }

    fn roles(&self) -> CurveRoles {
        let mut centred = vec![("neckline", mirror_pairs(&QUAD))];
        centred.extend(["chest", "bust", "waist", "hip"].map(|r| (r, mirror_pairs(&TORSO))));
        let strap = |curve, side| EndJoint {
            curve,
            ring: "chest",
            anchors: if side == "left" {
                ["front_left", "back_left"]
            } else {
                ["front_right", "back_right"]
            },
        };
        let tangents = [
            ("left_strap", "front_left", true),
            ("left_strap", "back_left", false),
            ("right_strap", "front_right", true),
            ("right_strap", "back_right", false),
        ]
        .map(|(curve, contour, front)| TangentJoint { curve, contour, front })
        .to_vec();
        CurveRoles {
            mirrored: vec![
                ("left_thigh", "right_thigh"),
                ("left_knee", "right_knee"),
                ("left_hem", "right_hem"),
                ("left_strap", "right_strap"),
            ],
            centred,
            ends: vec![
                EndJoint {
                    curve: "crotch",
                    ring: "hip",
                    anchors: ["front", "back"],
                },
                strap("left_strap", "left"),
                strap("right_strap", "right"),
            ],
            tangents,
            mirror_plane: Some("crotch"),
        }
    }
}
