//! The garment framework: planes, rings, open curves, contours and patches of a template
//! solved against a body, and the stitched mesh M0 ([frame] sections 2-4).

use glam::DVec3;
use thiserror::Error;

use super::adjust::{combined_adjustment, straighten};
use super::assemble::{Counts, LEFT_LEG, Layout, QUAD, RIGHT_LEG, TORSO, assemble};
use super::contour::Contour;
use super::ease::Ease;
use super::m0::{M0, PatchError, PatchGrid};
use super::open_curve::{Apex, OpenCurve, OpenInput, section_part};
use super::probe::BodyProbe;
use super::ring::{AnchorRule, AnchorSpec, GarmentRing, RingBuildError, RingInput, RingOptions};
use super::template::{Dimensions, Fit, TemplateKind};
use crate::body::rings::{RingPick, pick_rings};
use crate::body::{Body, LandmarkKind, Side};
use crate::geom::{Plane, SplineError, section_mesh};

/// Settings of a framework solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameworkOptions {
    /// Segments per anchor arc of a ring in M0 (default 6: 48 around the torso, 24 around a leg).
    pub resolution: usize,
    /// Contour fit (default tight for the jumpsuit; the dress is always loose below the hip).
    pub fit: Fit,
    /// Ring processing.
    pub ring: RingOptions,
    /// Weld threshold as a fraction of the body's height (default 1e-9).
    pub weld_threshold: f64,
    /// Default ease as a fraction of the body's height (default 0.012: 1.9 cm on 1.59 m).
    pub ease_fraction: f64,
}

impl Default for FrameworkOptions {
    fn default() -> Self {
        Self {
            resolution: 6,
            fit: Fit::Tight,
            ring: RingOptions::default(),
            weld_threshold: 1e-9,
            ease_fraction: 0.012,
        }
    }
}

impl FrameworkOptions {
    /// With this resolution.
    pub fn with_resolution(mut self, resolution: usize) -> Self {
        self.resolution = resolution;
        self
    }

    /// With this fit.
    pub fn with_fit(mut self, fit: Fit) -> Self {
        self.fit = fit;
        self
    }
}

/// Why a framework cannot be solved.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FrameworkError {
    /// A ring or open curve failed.
    #[error(transparent)]
    Ring(#[from] RingBuildError),
    /// A plane cuts no usable section.
    #[error("{curve}: {what}")]
    Section {
        /// Curve.
        curve: String,
        /// What is missing.
        what: String,
    },
    /// A contour could not be fitted.
    #[error("contour '{0}': {1}")]
    Contour(String, SplineError),
    /// A patch failed.
    #[error(transparent)]
    Patch(#[from] PatchError),
    /// A dimension is out of range.
    #[error("dimension {name} = {value}: {reason}")]
    Dimension {
        /// Name.
        name: String,
        /// Value.
        value: f64,
        /// Allowed range.
        reason: String,
    },
    /// The body mesh cannot be queried.
    #[error("the body mesh cannot be prepared for distance queries")]
    Probe,
}

/// A named plane with where to draw it.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedPlane {
    /// Name.
    pub name: String,
    /// The plane.
    pub plane: Plane,
    /// A point of it near the body (the centre of the drawn square).
    pub centre: DVec3,
    /// Half the drawn square's side, m.
    pub extent: f64,
}

/// A short feature line (seam, junction).
#[derive(Clone, Debug, PartialEq)]
pub struct FeatureLine {
    /// Name.
    pub name: String,
    /// Samples, ends exact.
    pub points: Vec<DVec3>,
}

/// A dimension's value after the solve.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DimensionValue {
    /// Name.
    pub name: String,
    /// Value reached (m, or a fraction).
    pub value: f64,
    /// The value set by the session, if any.
    pub target: Option<f64>,
}

/// A contour straightened by the loose fit: its control points before and after.
#[derive(Clone, Debug, PartialEq)]
pub struct Straightened {
    /// Contour.
    pub contour: String,
    /// Before.
    pub before: Vec<DVec3>,
    /// After.
    pub after: Vec<DVec3>,
}

/// A solved framework and its mesh.
#[derive(Clone, Debug)]
pub struct Framework {
    /// Template.
    pub template: TemplateKind,
    /// Fit.
    pub fit: Fit,
    /// Planes used.
    pub planes: Vec<NamedPlane>,
    /// Rings, top to bottom.
    pub rings: Vec<GarmentRing>,
    /// Open curves.
    pub open_curves: Vec<OpenCurve>,
    /// Seams and junctions.
    pub lines: Vec<FeatureLine>,
    /// Contours.
    pub contours: Vec<Contour>,
    /// Loose-fit straightening.
    pub straightened: Vec<Straightened>,
    /// Patches.
    pub patches: Vec<PatchGrid>,
    /// The stitched mesh.
    pub m0: M0,
    /// Dimensions reached.
    pub dimensions: Vec<DimensionValue>,
    /// Sample counts of the patches and lines (fixed for the garment's life).
    pub layout: Layout,
}

impl Framework {
    /// A ring by name.
    pub fn ring(&self, name: &str) -> Option<&GarmentRing> {
        self.rings.iter().find(|r| r.name == name)
    }

    /// Every named control point (`waist.front`, `left_knee.outer`, `crotch.point`,
    /// `left_strap.top`, ...), in a fixed order.
    pub fn control_points(&self) -> Vec<(String, DVec3)> {
        let mut out: Vec<(String, DVec3)> = self
            .rings
            .iter()
            .flat_map(|r| {
                r.anchors
                    .iter()
                    .map(move |a| (format!("{}.{}", r.name, a.name), a.point))
            })
            .collect();
        for c in &self.open_curves {
            let apex = if c.name == "crotch" { "point" } else { "top" };
            out.push((format!("{}.{apex}", c.name), c.apex));
        }
        out
    }

    /// The control points of every feature curve by name: rings and open curves (their
    /// spline control points), contours (the points they pass), seams and junction lines
    /// (their samples).
    pub fn curve_controls(&self) -> std::collections::BTreeMap<String, Vec<DVec3>> {
        let mut out = std::collections::BTreeMap::new();
        for r in &self.rings {
            out.insert(r.name.clone(), r.stages.control.clone());
        }
        for c in &self.open_curves {
            out.insert(c.name.clone(), c.stages.control.clone());
        }
        for c in &self.contours {
            out.insert(c.name.clone(), c.points.clone());
        }
        for l in &self.lines {
            out.insert(l.name.clone(), l.points.clone());
        }
        out
    }

    /// The ease (the `ease` dimension), m.
    pub fn ease(&self) -> f64 {
        self.dimension("ease").unwrap_or(0.0)
    }

    /// A dimension's value.
    pub fn dimension(&self, name: &str) -> Option<f64> {
        self.dimensions.iter().find(|d| d.name == name).map(|d| d.value)
    }
}

/// The thigh ring below the crotch, as a fraction of the body's height.
const THIGH_DROP: f64 = 0.025;

fn quad_anchors() -> Vec<AnchorSpec> {
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

fn leg_anchors(side: Side) -> Vec<AnchorSpec> {
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

/// Torso anchors: the centre line, the extremes, and the princess lines at signed
/// fractions `(left, right)` of the half width.
fn torso_anchors(left: f64, right: f64) -> Vec<AnchorSpec> {
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

/// The solve's shared context.
struct Ctx<'a> {
    body: &'a Body,
    probe: &'a BodyProbe,
    dims: &'a Dimensions,
    options: &'a FrameworkOptions,
    height: f64,
    ease: f64,
    mid_x: f64,
    dimensions: Vec<DimensionValue>,
}

impl Ctx<'_> {
    fn value(&mut self, name: &str, default: f64, range: (f64, f64), reason: &str) -> Result<f64, FrameworkError> {
        let target = self.dims.get(name);
        let value = target.unwrap_or(default);
        if !(value.is_finite() && value >= range.0 && value <= range.1) {
            return Err(FrameworkError::Dimension {
                name: name.to_string(),
                value,
                reason: format!("{reason} ({:.4}..{:.4} here)", range.0, range.1),
            });
        }
        self.dimensions.push(DimensionValue {
            name: name.to_string(),
            value,
            target,
        });
        Ok(value)
    }

    fn ring_ease(&mut self, ring: &str) -> Result<f64, FrameworkError> {
        let global = self.ease;
        let cap = 0.1 * self.height;
        self.value(
            &format!("{ring}_ease"),
            global,
            (0.0, cap),
            "ease must be between 0 and a tenth of the body's height",
        )
    }

    fn torso_loop(&self, name: &str, y: f64) -> Result<Vec<DVec3>, FrameworkError> {
        let b = &self.body;
        pick_rings(
            &b.mesh.mesh,
            &b.mesh.adjacency,
            &b.landmarks,
            (name, None),
            y,
            RingPick::Torso,
        )
        .map_err(|e| section_error(name, e.to_string()))
        .map(|mut r| r.remove(0).points)
    }

    fn leg_loops(&self, name: &str, y: f64) -> Result<Vec<(Side, Vec<DVec3>)>, FrameworkError> {
        let b = &self.body;
        pick_rings(
            &b.mesh.mesh,
            &b.mesh.adjacency,
            &b.landmarks,
            (name, None),
            y,
            RingPick::Legs,
        )
        .map_err(|e| section_error(name, e.to_string()))
        .map(|rings| rings.into_iter().map(|r| (r.side, r.points)).collect())
    }

    fn ring(
        &mut self,
        name: &str,
        plane: Plane,
        raw: Vec<Vec<DVec3>>,
        anchors: &[AnchorSpec],
        ease: Ease,
    ) -> Result<GarmentRing, FrameworkError> {
        let key = format!("{name}_girth");
        let target = self.dims.get(&key);
        let ring = GarmentRing::build(
            &RingInput {
                name,
                plane,
                raw,
                anchors,
                mid_x: self.mid_x,
                ease,
                target,
            },
            &self.options.ring,
        )?;
        self.dimensions.push(DimensionValue {
            name: key,
            value: ring.girth,
            target,
        });
        Ok(ring)
    }

    /// A ring's ease, each side (left, right) at most 45% of the gap to the nearest other
    /// body loop on that side at the ring's height (the other leg, an arm), so that the
    /// garment ring never reaches a neighbouring limb.
    fn limited_ease(&self, y: f64, raw: &[Vec<DVec3>], ease: f64) -> Ease {
        let b = &self.body;
        let loops = section_mesh(&b.mesh.mesh, &b.mesh.adjacency, &Plane::horizontal(y));
        let mine: Vec<DVec3> = raw.iter().flatten().copied().collect();
        let centre = mine.iter().sum::<DVec3>() / mine.len().max(1) as f64;
        let (mut left, mut right) = (ease, ease);
        for l in &loops {
            let gap = l
                .points
                .iter()
                .map(|p| {
                    mine.iter()
                        .map(|q| DVec3::new(p.x - q.x, 0.0, p.z - q.z).length())
                        .fold(f64::INFINITY, f64::min)
                })
                .fold(f64::INFINITY, f64::min);
            // Zero gap: one of the ring's own loops.
            if gap <= 1e-9 * self.height || l.points.is_empty() {
                continue;
            }
            let c = l.points.iter().sum::<DVec3>() / l.points.len() as f64;
            if c.x > centre.x {
                left = left.min(0.45 * gap);
            } else {
                right = right.min(0.45 * gap);
            }
        }
        if left == ease && right == ease {
            Ease::Uniform(ease)
        } else {
            Ease::PerDirection {
                front: ease,
                left,
                back: ease,
                right,
            }
        }
    }

    fn segments(&self, dy: f64, stretch: f64) -> usize {
        let edge = self.height * 0.09 / self.options.resolution.max(1) as f64;
        ((dy.abs() * stretch / edge).round() as usize).max(2)
    }

    fn layout(&self, counts: Counts) -> Layout {
        Layout {
            height: self.height,
            clearance: self.ease,
            weld: self.options.weld_threshold * self.height,
            k: self.options.resolution.max(2),
            counts,
        }
    }

    fn plane_for(&self, name: &str, plane: Plane, centre: DVec3) -> NamedPlane {
        NamedPlane {
            name: name.to_string(),
            plane,
            centre,
            extent: 0.16 * self.height,
        }
    }
}

fn section_error(curve: &str, what: String) -> FrameworkError {
    FrameworkError::Section {
        curve: curve.to_string(),
        what,
    }
}

fn find<'r>(rings: &'r [GarmentRing], name: &str) -> &'r GarmentRing {
    // Names come from this module's own tables, so a miss is a bug here, not bad input.
    rings
        .iter()
        .find(|r| r.name == name)
        .unwrap_or_else(|| unreachable!("ring {name} is built before it is used"))
}

fn point(rings: &[GarmentRing], ring: &str, anchor: &str) -> DVec3 {
    find(rings, ring)
        .anchor(anchor)
        .map(|a| a.point)
        .unwrap_or_else(|| unreachable!("anchor {ring}.{anchor} exists"))
}

/// A contour spec: name and the `(ring, anchor)` points it passes, lowest first.
type ContourSpec = (String, Vec<(String, String)>);

fn fit_contours(
    specs: &[ContourSpec],
    rings: &[GarmentRing],
    extra: &[(String, DVec3)],
) -> Result<Vec<Contour>, FrameworkError> {
    specs
        .iter()
        .map(|(name, pts)| {
            let through: Vec<String> = pts.iter().map(|(r, a)| format!("{r}.{a}")).collect();
            let points: Vec<DVec3> = pts
                .iter()
                .zip(&through)
                .map(|((r, a), full)| {
                    extra
                        .iter()
                        .find(|(n, _)| n == full)
                        .map_or_else(|| point(rings, r, a), |(_, p)| *p)
                })
                .collect();
            Contour::fit(name, through, points).map_err(|e| FrameworkError::Contour(name.clone(), e))
        })
        .collect()
}

/// Loose fit: straightens the contours below `fixed` and deforms the rings below it.
fn loosen(
    rings: &mut [GarmentRing],
    contours: &[ContourSpec],
    fixed: &str,
    options: &RingOptions,
) -> Result<Vec<Straightened>, FrameworkError> {
    let mut moves: Vec<(String, &'static str, DVec3)> = Vec::new();
    let mut out = Vec::new();
    for (name, pts) in contours {
        let Some(top) = pts.iter().position(|(r, _)| r == fixed) else {
            continue;
        };
        // From the fixed ring down.
        let part: Vec<(String, String)> = pts[..=top].iter().rev().cloned().collect();
        let points: Vec<DVec3> = part.iter().map(|(r, a)| point(rings, r, a)).collect();
        let outward: Vec<DVec3> = part
            .iter()
            .map(|(r, a)| {
                let ring = find(rings, r);
                let c = ring.stages.control.iter().copied().sum::<DVec3>() / ring.stages.control.len() as f64;
                let p = point(rings, r, a);
                DVec3::new(p.x - c.x, 0.0, p.z - c.z).normalize_or_zero()
            })
            .collect();
        let after = straighten(&points, &outward);
        for ((r, a), (p, q)) in part.iter().zip(points.iter().zip(&after)).skip(1) {
            let anchor = find(rings, r)
                .anchor(a)
                .map(|x| x.name)
                .unwrap_or_else(|| unreachable!("anchor {r}.{a} exists"));
            moves.push((r.clone(), anchor, *q - *p));
        }
        out.push(Straightened {
            contour: name.clone(),
            before: points,
            after,
        });
    }
    for ring in rings.iter_mut() {
        let ring_moves: Vec<DVec3> = ring
            .anchors
            .iter()
            .map(|a| {
                moves
                    .iter()
                    .find(|(r, n, _)| *r == ring.name && *n == a.name)
                    .map_or(DVec3::ZERO, |m| m.2)
            })
            .collect();
        if ring_moves.iter().all(|m| *m == DVec3::ZERO) {
            continue;
        }
        let at: Vec<usize> = ring.anchors.iter().map(|a| a.control).collect();
        let control = combined_adjustment(&ring.stages.control, &at, &ring_moves, &ring.plane);
        ring.refit(control, options)?;
    }
    Ok(out)
}

/// Solves the framework of `template` on `body` with the session's dimensions.
pub fn build_framework(
    body: &Body,
    probe: &BodyProbe,
    template: TemplateKind,
    dims: &Dimensions,
    options: &FrameworkOptions,
) -> Result<Framework, FrameworkError> {
    let height = body.mesh.height();
    let mut ctx = Ctx {
        body,
        probe,
        dims,
        options,
        height,
        ease: 0.0,
        mid_x: body.landmarks.mid_x,
        dimensions: Vec::new(),
    };
    ctx.ease = ctx.value(
        "ease",
        options.ease_fraction * height,
        (0.0, 0.1 * height),
        "ease must be between 0 and a tenth of the body's height",
    )?;
    let fit = if template == TemplateKind::Dress {
        Fit::Loose
    } else {
        options.fit
    };
    let mut fw = match template {
        TemplateKind::Jumpsuit => jumpsuit(&mut ctx, fit)?,
        TemplateKind::Dress => dress(&mut ctx)?,
    };
    fw.dimensions = std::mem::take(&mut ctx.dimensions);
    fw.dimensions.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(fw)
}

struct Parts {
    planes: Vec<NamedPlane>,
    rings: Vec<GarmentRing>,
    open_curves: Vec<OpenCurve>,
    contours: Vec<Contour>,
    straightened: Vec<Straightened>,
    layout: Layout,
}

/// Assembles the lines, patches and M0 from the curves. Patch interiors are left where
/// the Coons blend puts them: where they dip into the body (the seat below the hip ring)
/// the mesh-layer collision finds and moves them.
fn finish(ctx: &Ctx<'_>, template: TemplateKind, fit: Fit, parts: Parts) -> Result<Framework, FrameworkError> {
    let mut fw = Framework {
        template,
        fit,
        planes: parts.planes,
        rings: parts.rings,
        open_curves: parts.open_curves,
        lines: Vec::new(),
        contours: parts.contours,
        straightened: parts.straightened,
        patches: Vec::new(),
        m0: M0::default(),
        dimensions: Vec::new(),
        layout: parts.layout,
    };
    let built = assemble(&fw, ctx.probe, None)?;
    fw.lines = built.lines;
    fw.patches = built.patches;
    fw.m0 = built.m0;
    Ok(fw)
}

fn landmark(body: &Body, kind: LandmarkKind, side: Side) -> Result<DVec3, FrameworkError> {
    body.landmarks
        .get(kind, side)
        .map(|l| l.position())
        .ok_or_else(|| section_error(kind.name(), "landmark missing".into()))
}

fn jumpsuit(ctx: &mut Ctx<'_>, fit: Fit) -> Result<Framework, FrameworkError> {
    let body = ctx.body;
    let lm = &body.landmarks;
    let h = ctx.height;
    let (floor, _) = body.mesh.mesh.bounds().map_or((DVec3::ZERO, DVec3::ZERO), |b| b);
    let eps = 2e-3 * h;
    let y_of = |k: LandmarkKind| lm.height(k);
    let chest_y = y_of(LandmarkKind::Armpit) - eps;
    let crotch_y = y_of(LandmarkKind::Crotch);
    let thigh_y = crotch_y - THIGH_DROP * h;
    let knee_y = y_of(LandmarkKind::Knee);
    let ankle_y = y_of(LandmarkKind::Ankle);
    let inseam = ctx.value(
        "inseam",
        crotch_y - ankle_y,
        (crotch_y - knee_y + 0.05 * h, crotch_y - floor.y - 0.02 * h),
        "the hem must lie between the knee and the foot",
    )?;
    let hem_y = crotch_y - inseam;
    let neck_rise = ctx.value(
        "neck_rise",
        0.0,
        (-0.02 * h, 0.03 * h),
        "the neckline must stay near the neck base",
    )?;
    let strap_position = ctx.value("strap_position", 0.5, (0.1, 0.9), "the strap must lie on the shoulder")?;
    let mut planes = Vec::new();

    // Neckline: the neck-base plane, shifted up by the rise.
    let base = lm
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
            let c = |l: &crate::geom::SectionLoop| l.points.iter().sum::<DVec3>() / l.points.len() as f64;
            c(a).distance(neck_centre).total_cmp(&c(b).distance(neck_centre))
        })
        .ok_or_else(|| section_error("neckline", "the neck plane cuts no closed loop".into()))?;
    let e = ctx.ring_ease("neckline")?;
    let neckline = ctx.ring(
        "neckline",
        neck_plane,
        vec![neck_loop.points.clone()],
        &quad_anchors(),
        Ease::Uniform(e),
    )?;

    // Straps: vertical planes across each shoulder.
    let strap_x = |side: Side| -> Result<f64, FrameworkError> {
        let sn = landmark(body, LandmarkKind::SideNeck, side)?;
        let sh = landmark(body, LandmarkKind::Shoulder, side)?;
        Ok(sn.x + strap_position * (sh.x - sn.x))
    };
    let (xl, xr) = (strap_x(Side::Left)?, strap_x(Side::Right)?);
    let shoulder_y = y_of(LandmarkKind::Shoulder);

    // Chest ring first: its princess anchors lie in the strap planes.
    let mut rings = vec![neckline];
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
    for (name, kind) in [
        ("bust", LandmarkKind::Bust),
        ("waist", LandmarkKind::Waist),
        ("hip", LandmarkKind::Hip),
    ] {
        let y = y_of(kind);
        let raw = ctx.torso_loop(name, y)?;
        let e = ctx.ring_ease(name)?;
        let ease = ctx.limited_ease(y, std::slice::from_ref(&raw), e);
        let r = ctx.ring(name, Plane::horizontal(y), vec![raw], &torso_anchors(fl, fr), ease)?;
        rings.push(r);
    }
    for (level, y) in [("thigh", thigh_y), ("knee", knee_y), ("hem", hem_y)] {
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
    for (name, y) in [
        ("chest", chest_y),
        ("bust", y_of(LandmarkKind::Bust)),
        ("waist", y_of(LandmarkKind::Waist)),
        ("hip", y_of(LandmarkKind::Hip)),
        ("thigh", thigh_y),
        ("knee", knee_y),
        ("hem", hem_y),
    ] {
        let centre = lm
            .torso_at(y)
            .map_or(DVec3::new(ctx.mid_x, y, 0.0), |t| DVec3::new(t.x, y, t.y));
        planes.push(ctx.plane_for(name, Plane::horizontal(y), centre));
    }

    // The crotch curve in the vertical crotch plane, from the hip's centre front down
    // through the crotch and up to its centre back.
    let hip_y = y_of(LandmarkKind::Hip);
    let crotch_plane = Plane::from_point_normal(DVec3::new(ctx.mid_x, 0.0, 0.0), DVec3::X);
    let crotch_ref = landmark(body, LandmarkKind::Crotch, Side::Centre)?;
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
        plane: crotch_plane,
        raw: crotch_part,
        ease: Ease::Uniform(ctx.ease),
        ends: [point(&rings, "hip", "front"), point(&rings, "hip", "back")],
        per_half,
        control_per_half: 4,
        fitted_per_half: ctx.options.ring.fitted_points / 4,
    })?;
    let mut open_curves = vec![crotch];
    for (side, x) in [(Side::Left, xl), (Side::Right, xr)] {
        let (name, suffix) = if side == Side::Left {
            ("left_strap", "left")
        } else {
            ("right_strap", "right")
        };
        let plane = Plane::from_point_normal(DVec3::new(x, 0.0, 0.0), DVec3::X);
        let reference = landmark(body, LandmarkKind::Shoulder, side)?;
        let reference = DVec3::new(x, shoulder_y, reference.z);
        planes.push(ctx.plane_for(name, plane, DVec3::new(x, shoulder_y - 0.04 * h, reference.z)));
        let part = section_mesh(&body.mesh.mesh, &body.mesh.adjacency, &plane)
            .iter()
            .filter_map(|l| section_part(l, chest_y, Apex::Highest))
            .min_by(|a, b| a.0[a.1].distance(reference).total_cmp(&b.0[b.1].distance(reference)))
            .ok_or_else(|| section_error(name, "the strap plane cuts no curve over the shoulder".into()))?;
        let e = find(&rings, "chest").ease;
        let e = match e {
            Ease::Uniform(v) => v,
            Ease::PerDirection { front, .. } => front,
        };
        let strap = OpenCurve::build(&OpenInput {
            name,
            plane,
            raw: part,
            ease: Ease::Uniform(e),
            ends: [
                point(&rings, "chest", &format!("front_{suffix}")),
                point(&rings, "chest", &format!("back_{suffix}")),
            ],
            per_half,
            control_per_half: 4,
            fitted_per_half: ctx.options.ring.fitted_points / 4,
        })?;
        open_curves.push(strap);
    }

    // Contours, lowest point first.
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
        specs.push((format!("inner_{s}"), inner));
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
            straightened.extend(loosen(&mut rings, &mine, &fixed, &ctx.options.ring)?);
        }
    }
    let crotch_point = vec![("crotch.point".to_string(), open_curves[0].apex)];
    let mut contours = fit_contours(&specs, &rings, &crotch_point)?;
    // The princess lines run on into the straps: each meets its strap's end tangent.
    for c in &mut contours {
        let strap = match c.name.split_once('_') {
            Some((part @ ("front" | "back"), side @ ("left" | "right"))) => Some((part == "front", side)),
            _ => None,
        };
        if let Some((front, side)) = strap {
            let i = if side == "left" { 1 } else { 2 };
            let t = open_curves[i].end_tangent(front);
            c.refit(c.points.clone(), [None, Some(t)])
                .map_err(|e| FrameworkError::Contour(c.name.clone(), e))?;
        }
    }

    let k = ctx.options.resolution.max(2);
    let seam = (k / 3).max(1);
    let junction = ctx.segments(hip_y - thigh_y, 1.0);
    let inner = (junction / 3).max(1);
    let torso = [("hip", "waist"), ("waist", "bust"), ("bust", "chest")].map(|(lo, hi)| {
        let (ylo, yhi) = (find(&rings, lo).plane.offset, find(&rings, hi).plane.offset);
        ctx.segments(yhi - ylo, 1.0)
    });
    // Counts from the landmarks, not the hem dimension: the topology stays fixed.
    let leg = [knee_y - ankle_y, thigh_y - knee_y].map(|dy| ctx.segments(dy, 1.0));
    let layout = ctx.layout(Counts::Jumpsuit {
        seam,
        neck: k - seam,
        junction,
        inner,
        crotch: junction - inner,
        strap: ctx.segments(shoulder_y - chest_y, 1.5),
        torso,
        leg,
    });
    finish(
        ctx,
        TemplateKind::Jumpsuit,
        fit,
        Parts {
            planes,
            rings,
            open_curves,
            contours,
            straightened,
            layout,
        },
    )
}

fn dress(ctx: &mut Ctx<'_>) -> Result<Framework, FrameworkError> {
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
    let names = ["centre_front", "side_left", "centre_back", "side_right"];
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
    let contours = fit_contours(&specs, &rings, &[])?;
    let layout = ctx.layout(Counts::Dress(
        [thigh_y - knee_y, hip_y - thigh_y, waist_y - hip_y].map(|dy| ctx.segments(dy, 1.0)),
    ));
    finish(
        ctx,
        TemplateKind::Dress,
        Fit::Loose,
        Parts {
            planes,
            rings,
            open_curves: Vec::new(),
            contours,
            straightened,
            layout,
        },
    )
}
