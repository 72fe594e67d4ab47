//! The jumpsuit: a torso tube, two leg tubes joined at the crotch, front and back panels up
//! to the neckline held by straps over the shoulders. Sleeveless: 11 rings, the crotch
//! curve and two straps, 10 contours (24 curves); 50 patches. With sleeves (see
//! [`super::sleeve`]) the armholes each carry a sleeve; with a collar (see
//! [`super::collar`]) the neckline carries it.
//!
//! Without its legs (`legs: false`) the same bodice is the shirt: the torso tube down to
//! the hip ring, its hem.

mod curves;
mod cut;
mod levels;
mod open_curves;
mod patches;

pub use cut::{CONTOURS, Jumpsuit};

use super::spec::{CurveRoles, EndJoint, TangentJoint, Template};
use super::{collar, sleeve};
use crate::garment::anchors::{LEFT_LEG, QUAD, RIGHT_LEG, TORSO, mirror_pairs};
use crate::garment::model::{FeatureLine, Fit, Framework, FrameworkError, Style, TemplateKind};
use crate::garment::probe::BodyProbe;
use crate::garment::solve::{BuildCtx, Parts};
use crate::garment::surface::Surfacer;

impl Template for Jumpsuit {
    fn kind(&self) -> TemplateKind {
        if self.legs {
            TemplateKind::Jumpsuit
        } else {
            TemplateKind::Shirt
        }
    }

    fn style(&self) -> Style {
        self.style
    }

    fn rings(&self) -> Vec<&'static str> {
        let mut out = self.body_rings().to_vec();
        out.extend(sleeve::rings(self.style.sleeves));
        out.extend(collar::rings(self.style.collar));
        out
    }

    fn lengths(&self) -> Vec<(&'static str, &'static str)> {
        let mut out = Vec::new();
        if self.legs {
            out.push((
                "inseam",
                "crotch height minus hem height, m (default: down to the ankles)",
            ));
        }
        out.push(("neck_rise", "neckline above the neck-base plane, m (default 0)"));
        out.push((
            "strap_position",
            "where the straps cross the shoulder, 0 at the side neck to 1 at the shoulder point (default 0.5; with sleeves, as near the shoulder point as the chest allows, at most 0.8)",
        ));
        out.extend(sleeve::lengths(self.style.sleeves));
        out.extend(collar::lengths(self.style.collar));
        out
    }

    fn ring_anchors(&self) -> Vec<(&'static str, &'static [&'static str])> {
        let mut out: Vec<(&'static str, &'static [&'static str])> = self
            .body_rings()
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
            .collect();
        for k in 0..2 {
            let anchors: &'static [&'static str] = sleeve::anchor_names(k);
            out.extend(
                sleeve::ring_names(self.style.sleeves, k)
                    .into_iter()
                    .map(|r| (r, anchors)),
            );
        }
        out.extend(collar::rings(self.style.collar).into_iter().map(|r| (r, &QUAD[..])));
        out
    }

    fn open_curves(&self) -> Vec<(&'static str, &'static str)> {
        let mut out = vec![("left_strap", "top"), ("right_strap", "top")];
        if self.legs {
            out.insert(0, ("crotch", "point"));
        }
        out
    }

    fn contours(&self) -> Vec<&'static str> {
        let mut out: Vec<&'static str> = if self.legs {
            CONTOURS.to_vec()
        } else {
            CONTOURS.iter().copied().filter(|c| !c.starts_with("inner")).collect()
        };
        out.extend(sleeve::contours(self.style.sleeves));
        out.extend(collar::contours(self.style.collar));
        out
    }

    fn curves(&self, ctx: &mut BuildCtx<'_>, fit: Fit) -> Result<Parts, FrameworkError> {
        curves::solve(ctx, fit, self)
    }

    fn lines(&self, fw: &Framework, probe: &BodyProbe) -> Result<Vec<FeatureLine>, FrameworkError> {
        patches::lines(fw, probe, self)
    }

    fn patches(&self, s: &mut Surfacer<'_>, lines: &[FeatureLine]) -> Result<(), FrameworkError> {
        patches::patches(s, lines, self)
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
        let mut mirrored = vec![("left_strap", "right_strap")];
        let mut ends = vec![strap("left_strap", "left"), strap("right_strap", "right")];
        if self.legs {
            mirrored.splice(
                0..0,
                [
                    ("left_thigh", "right_thigh"),
                    ("left_knee", "right_knee"),
                    ("left_hem", "right_hem"),
                ],
            );
            ends.insert(
                0,
                EndJoint {
                    curve: "crotch",
                    ring: "hip",
                    anchors: ["front", "back"],
                },
            );
        }
        let sleeves = self.style.sleeves;
        mirrored.extend(
            sleeve::ring_names(sleeves, 0)
                .into_iter()
                .zip(sleeve::ring_names(sleeves, 1)),
        );
        let collar_rings = collar::rings(self.style.collar);
        centred.extend(collar_rings.into_iter().map(|r| (r, mirror_pairs(&QUAD))));
        CurveRoles {
            mirrored,
            centred,
            ends,
            tangents,
            mirror_plane: self.legs.then_some("crotch"),
            axial: sleeve::rings(sleeves),
        }
    }
}
