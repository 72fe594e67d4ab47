//! Assembly: the seams, Coons patches and M0 of a template, built from its feature curves
//! (rings, open curves, contours) as they stand ([frame] section 4).
//!
//! The framework solve calls this once; an edit calls it again after the constraint
//! solver has moved the curves. Sample counts come from the [`Layout`] fixed when the
//! garment was built, so M0 keeps its topology whatever the edit. Given the framework
//! before the edit, a patch none of whose boundary curves changed keeps its surface
//! (it would be recomputed bit for bit the same): only the changed patches are re-surfaced.

use std::collections::BTreeMap;

use glam::DVec3;

use super::contour::{Contour, clear_line};
use super::framework::{FeatureLine, Framework, FrameworkError};
use super::m0::{CurveRef, M0, PatchGrid, stitch};
use super::probe::BodyProbe;
use super::ring::GarmentRing;
use super::template::TemplateKind;

/// Sample counts of a template's patches and lines, fixed when the garment is built.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// Body height, m.
    pub height: f64,
    /// Clearance of contour spans and seams from the body, m.
    pub clearance: f64,
    /// Weld threshold, m.
    pub weld: f64,
    /// Segments per anchor arc of a ring.
    pub k: usize,
    /// Per-template counts.
    pub counts: Counts,
}

/// Segment counts along the contours of each band.
#[derive(Clone, Debug, PartialEq)]
pub enum Counts {
    /// The jumpsuit.
    Jumpsuit {
        /// Shoulder seam.
        seam: usize,
        /// Neckline arcs of the panels.
        neck: usize,
        /// Thigh-to-hip junction.
        junction: usize,
        /// Inner contour part of the junction.
        inner: usize,
        /// Crotch-curve part of the junction.
        crotch: usize,
        /// Strap halves.
        strap: usize,
        /// Torso bands hip-waist, waist-bust, bust-chest.
        torso: [usize; 3],
        /// Leg bands hem-knee, knee-thigh.
        leg: [usize; 2],
    },
    /// The dress: bands hem-thigh, thigh-hip, hip-waist.
    Dress([usize; 3]),
}

/// What an assembly produced.
#[derive(Clone, Debug)]
pub struct Assembled {
    /// Seams and junction lines.
    pub lines: Vec<FeatureLine>,
    /// Patches.
    pub patches: Vec<PatchGrid>,
    /// The stitched mesh.
    pub m0: M0,
    /// Names of the patches surfaced anew (all of them without a previous framework).
    pub resurfaced: Vec<String>,
}

pub(crate) const TORSO: [&str; 8] = [
    "front",
    "front_left",
    "left",
    "back_left",
    "back",
    "back_right",
    "right",
    "front_right",
];
pub(crate) const QUAD: [&str; 4] = ["front", "left", "back", "right"];
pub(crate) const LEFT_LEG: [&str; 4] = ["front", "outer", "back", "inner"];
pub(crate) const RIGHT_LEG: [&str; 4] = ["front", "inner", "back", "outer"];

fn missing(curve: &str, what: &str) -> FrameworkError {
    FrameworkError::Section {
        curve: curve.to_string(),
        what: what.to_string(),
    }
}

fn ring<'r>(fw: &'r Framework, name: &str) -> Result<&'r GarmentRing, FrameworkError> {
    fw.ring(name)
        .ok_or_else(|| missing(name, "ring missing from the framework"))
}

fn arc(fw: &Framework, name: &str, from: &str, to: &str, n: usize) -> Result<Vec<DVec3>, FrameworkError> {
    ring(fw, name)?
        .arc(from, to, n)
        .ok_or_else(|| missing(name, &format!("anchors {from} and {to} missing")))
}

fn anchor(fw: &Framework, name: &str, a: &str) -> Result<DVec3, FrameworkError> {
    ring(fw, name)?
        .anchor(a)
        .map(|x| x.point)
        .ok_or_else(|| missing(name, &format!("anchor {a} missing")))
}

/// Joins sample runs that share their end points.
pub(crate) fn join(parts: &[Vec<DVec3>]) -> Vec<DVec3> {
    let mut out: Vec<DVec3> = Vec::new();
    for p in parts {
        if out.is_empty() {
            out.extend_from_slice(p);
        } else {
            out.extend_from_slice(&p[1..]);
        }
    }
    out
}

pub(crate) fn reversed(mut v: Vec<DVec3>) -> Vec<DVec3> {
    v.reverse();
    v
}

fn contour<'c>(fw: &'c Framework, name: &str) -> Result<&'c Contour, FrameworkError> {
    fw.contours
        .iter()
        .find(|c| c.name == name)
        .ok_or_else(|| missing(name, "contour missing from the framework"))
}

/// Where contour `name` passes ring `from`.
fn through_at(c: &Contour, from: &str) -> Result<usize, FrameworkError> {
    c.through
        .iter()
        .position(|t| t.split('.').next() == Some(from))
        .ok_or_else(|| missing(&c.name, &format!("does not pass ring {from}")))
}

/// The patch-surfacing context: clearance for contour spans, and the previous framework
/// whose unchanged patches are kept.
struct Surfacer<'a> {
    fw: &'a Framework,
    probe: &'a BodyProbe,
    layout: &'a Layout,
    previous: Option<(&'a Framework, BTreeMap<String, Vec<DVec3>>)>,
    shapes: BTreeMap<String, Vec<DVec3>>,
    patches: Vec<PatchGrid>,
    resurfaced: Vec<String>,
}

impl Surfacer<'_> {
    /// Samples of contour `name` from its point on ring `from` up to the next one, inner
    /// samples cleared off the body.
    fn span(&self, name: &str, from: &str, n: usize) -> Result<Vec<DVec3>, FrameworkError> {
        let c = contour(self.fw, name)?;
        Ok(c.span(through_at(c, from)?, n, Some((self.probe, self.layout.clearance))))
    }

    /// The control points of contour `name` that shape its span from ring `from`.
    fn span_ref(&self, name: &str, from: &str) -> Result<CurveRef, FrameworkError> {
        let c = contour(self.fw, name)?;
        let k = through_at(c, from)?;
        Ok(CurveRef {
            curve: name.to_string(),
            first: k.saturating_sub(1),
            last: k + 2,
        })
    }

    /// Surfaces one patch, or keeps the previous one when none of its curves changed.
    fn patch(&mut self, name: &str, sides: [&[DVec3]; 4], curves: Vec<CurveRef>) -> Result<(), FrameworkError> {
        if let Some((old, shapes)) = &self.previous {
            let same = curves.iter().all(|c| shapes.get(&c.curve) == self.shapes.get(&c.curve));
            if same && let Some(p) = old.patches.iter().find(|p| p.name == name) {
                self.patches.push(p.clone());
                return Ok(());
            }
        }
        let grid = PatchGrid::coons(name, sides, 1e-9 * self.layout.height)?.with_curves(curves);
        self.patches.push(grid);
        self.resurfaced.push(name.to_string());
        Ok(())
    }
}

/// Every curve's shape by name: rings and open curves (control points), contours (points
/// and end tangents), lines (samples). Two frameworks whose curve has the same shape
/// give that curve the same samples.
pub fn curve_shapes(fw: &Framework, lines: &[FeatureLine]) -> BTreeMap<String, Vec<DVec3>> {
    let mut out = BTreeMap::new();
    for r in &fw.rings {
        out.insert(r.name.clone(), r.stages.control.clone());
    }
    for c in &fw.open_curves {
        out.insert(c.name.clone(), c.stages.control.clone());
    }
    for c in &fw.contours {
        let mut key = c.points.clone();
        key.extend([c.tangents[0], c.tangents[1]].map(|t| t.unwrap_or(DVec3::splat(f64::NAN))));
        // NaN != NaN would call every natural end changed: use a sentinel instead.
        for p in &mut key {
            if p.is_nan() {
                *p = DVec3::splat(f64::MAX);
            }
        }
        out.insert(c.name.clone(), key);
    }
    for l in lines {
        out.insert(l.name.clone(), l.points.clone());
    }
    out
}

/// Builds the lines, patches and M0 of `fw` from its curves. With `previous`, patches
/// whose curves did not change are taken from it.
pub fn assemble(fw: &Framework, probe: &BodyProbe, previous: Option<&Framework>) -> Result<Assembled, FrameworkError> {
    let layout = &fw.layout;
    let lines = match (&layout.counts, fw.template) {
        (Counts::Jumpsuit { seam, inner, .. }, TemplateKind::Jumpsuit) => jumpsuit_lines(fw, probe, *seam, *inner)?,
        _ => Vec::new(),
    };
    let mut s = Surfacer {
        fw,
        probe,
        layout,
        previous: previous.map(|p| (p, curve_shapes(p, &p.lines))),
        shapes: curve_shapes(fw, &lines),
        patches: Vec::new(),
        resurfaced: Vec::new(),
    };
    match &layout.counts {
        Counts::Jumpsuit {
            neck,
            junction,
            inner,
            crotch,
            strap,
            torso,
            leg,
            ..
        } => jumpsuit_patches(
            &mut s,
            &lines,
            JumpsuitCounts {
                neck: *neck,
                junction: *junction,
                inner: *inner,
                crotch: *crotch,
                strap: *strap,
                torso: *torso,
                leg: *leg,
            },
        )?,
        Counts::Dress(nv) => dress_patches(&mut s, *nv)?,
    }
    let m0 = stitch(&s.patches, layout.weld);
    Ok(Assembled {
        lines,
        patches: s.patches,
        m0,
        resurfaced: s.resurfaced,
    })
}

struct JumpsuitCounts {
    neck: usize,
    junction: usize,
    inner: usize,
    crotch: usize,
    strap: usize,
    torso: [usize; 3],
    leg: [usize; 2],
}

fn open<'c>(fw: &'c Framework, name: &str) -> Result<&'c super::open_curve::OpenCurve, FrameworkError> {
    fw.open_curves
        .iter()
        .find(|c| c.name == name)
        .ok_or_else(|| missing(name, "open curve missing from the framework"))
}

/// Shoulder seams (neckline side to strap top) and crotch junctions (the inner contours'
/// span from the thigh).
fn jumpsuit_lines(
    fw: &Framework,
    probe: &BodyProbe,
    n_seam: usize,
    n_inner: usize,
) -> Result<Vec<FeatureLine>, FrameworkError> {
    let gap = fw.layout.clearance;
    let mut lines = Vec::new();
    for (s, strap) in [("left", "left_strap"), ("right", "right_strap")] {
        lines.push(FeatureLine {
            name: format!("seam_{s}"),
            points: clear_line(anchor(fw, "neckline", s)?, open(fw, strap)?.apex, n_seam, probe, gap),
        });
    }
    for s in ["left", "right"] {
        let c = contour(fw, &format!("inner_{s}"))?;
        let k = through_at(c, &format!("{s}_thigh"))?;
        lines.push(FeatureLine {
            name: format!("junction_{s}"),
            points: c.span(k, n_inner, Some((probe, gap))),
        });
    }
    Ok(lines)
}

fn line<'l>(lines: &'l [FeatureLine], name: &str) -> Result<&'l [DVec3], FrameworkError> {
    lines
        .iter()
        .find(|l| l.name == name)
        .map(|l| l.points.as_slice())
        .ok_or_else(|| missing(name, "line missing"))
}

fn jumpsuit_patches(s: &mut Surfacer<'_>, lines: &[FeatureLine], n: JumpsuitCounts) -> Result<(), FrameworkError> {
    let fw = s.fw;
    let k = s.layout.k;
    let torso_contours = [
        "centre_front",
        "front_left",
        "side_left",
        "back_left",
        "centre_back",
        "back_right",
        "side_right",
        "front_right",
    ];
    let torso_spans = [("hip", "waist"), ("waist", "bust"), ("bust", "chest")];
    for ((lo, hi), nv) in torso_spans.into_iter().zip(n.torso) {
        for i in 0..8 {
            let (a, b) = (TORSO[i], TORSO[(i + 1) % 8]);
            let bottom = arc(fw, lo, a, b, k)?;
            let top = arc(fw, hi, a, b, k)?;
            let left = s.span(torso_contours[i], lo, nv)?;
            let right = s.span(torso_contours[(i + 1) % 8], lo, nv)?;
            let curves = vec![
                CurveRef::whole(lo),
                CurveRef::whole(hi),
                s.span_ref(torso_contours[i], lo)?,
                s.span_ref(torso_contours[(i + 1) % 8], lo)?,
            ];
            s.patch(&format!("torso.{lo}_{hi}.{a}"), [&bottom, &top, &left, &right], curves)?;
        }
    }
    let crotch = open(fw, "crotch")?;
    let crotch_front = reversed(crotch.half(true, n.crotch));
    let crotch_back = crotch.half(false, n.crotch);
    for side in ["left", "right"] {
        let thigh = format!("{side}_thigh");
        let c = |name: &str| format!("{name}_{side}");
        let sp = |s: &Surfacer<'_>, name: &str| s.span(name, &thigh, n.junction);
        let inner_span = s.span(&c("inner"), &thigh, n.inner)?;
        let inner_front = join(&[inner_span.clone(), crotch_front.clone()]);
        let inner_back = join(&[inner_span, crotch_back.clone()]);
        // Around the thigh in ring order: five stops (thigh anchor, hip anchor, the boundary
        // between bands), the first and last both on the inner seam; a band between each
        // two. The right leg goes round the other way (the mirror of the left).
        let (stops, bands) = if side == "left" {
            (
                [
                    ("inner", "front", inner_front),
                    ("front", "front_left", sp(s, &c("front"))?),
                    ("outer", "left", sp(s, &c("side"))?),
                    ("back", "back_left", sp(s, &c("back"))?),
                    ("inner", "back", inner_back),
                ],
                ["front_inner", "front_outer", "back_outer", "back_inner"],
            )
        } else {
            (
                [
                    ("inner", "back", inner_back),
                    ("back", "back_right", sp(s, &c("back"))?),
                    ("outer", "right", sp(s, &c("side"))?),
                    ("front", "front_right", sp(s, &c("front"))?),
                    ("inner", "front", inner_front),
                ],
                ["back_inner", "back_outer", "front_outer", "front_inner"],
            )
        };
        let mut specs: Vec<(&str, [Vec<DVec3>; 4])> = Vec::with_capacity(4);
        for (band, w) in bands.into_iter().zip(stops.windows(2)) {
            let ((t0, h0, b0), (t1, h1, b1)) = (&w[0], &w[1]);
            specs.push((
                band,
                [
                    arc(fw, &thigh, t0, t1, k)?,
                    arc(fw, "hip", h0, h1, k)?,
                    b0.clone(),
                    b1.clone(),
                ],
            ));
        }
        let junction_curves = vec![
            CurveRef::whole(&thigh),
            CurveRef::whole("hip"),
            s.span_ref(&c("front"), &thigh)?,
            s.span_ref(&c("side"), &thigh)?,
            s.span_ref(&c("back"), &thigh)?,
            s.span_ref(&c("inner"), &thigh)?,
            CurveRef::whole("crotch"),
        ];
        for (name, [bottom, top, left, right]) in specs {
            s.patch(
                &format!("junction.{side}.{name}"),
                [&bottom, &top, &left, &right],
                junction_curves.clone(),
            )?;
        }
        let (order, cont) = if side == "left" {
            (LEFT_LEG, ["front", "side", "back", "inner"])
        } else {
            (RIGHT_LEG, ["front", "inner", "back", "side"])
        };
        for ((lo, hi), nv) in [("hem", "knee"), ("knee", "thigh")].into_iter().zip(n.leg) {
            let (lo_ring, hi_ring) = (format!("{side}_{lo}"), format!("{side}_{hi}"));
            for i in 0..4 {
                let (a, b) = (order[i], order[(i + 1) % 4]);
                let bottom = arc(fw, &lo_ring, a, b, k)?;
                let top = arc(fw, &hi_ring, a, b, k)?;
                let left = s.span(&c(cont[i]), &lo_ring, nv)?;
                let right = s.span(&c(cont[(i + 1) % 4]), &lo_ring, nv)?;
                let curves = vec![
                    CurveRef::whole(&lo_ring),
                    CurveRef::whole(&hi_ring),
                    s.span_ref(&c(cont[i]), &lo_ring)?,
                    s.span_ref(&c(cont[(i + 1) % 4]), &lo_ring)?,
                ];
                s.patch(
                    &format!("leg.{side}.{lo}_{hi}.{a}"),
                    [&bottom, &top, &left, &right],
                    curves,
                )?;
            }
        }
    }
    // Front and back panels between the chest ring, the straps and the neckline.
    let (left_strap, right_strap) = (open(fw, "left_strap")?, open(fw, "right_strap")?);
    let strap = |c: &super::open_curve::OpenCurve, front: bool| c.half(front, n.strap);
    let (seam_left, seam_right) = (line(lines, "seam_left")?, line(lines, "seam_right")?);
    let front_bottom = join(&[
        arc(fw, "chest", "front_right", "front", k)?,
        arc(fw, "chest", "front", "front_left", k)?,
    ]);
    let front_top = join(&[
        reversed(seam_right.to_vec()),
        arc(fw, "neckline", "right", "front", n.neck)?,
        arc(fw, "neckline", "front", "left", n.neck)?,
        seam_left.to_vec(),
    ]);
    let panel_curves: Vec<CurveRef> = [
        "chest",
        "neckline",
        "left_strap",
        "right_strap",
        "seam_left",
        "seam_right",
    ]
    .map(CurveRef::whole)
    .to_vec();
    s.patch(
        "panel.front",
        [
            &front_bottom,
            &front_top,
            &strap(right_strap, true),
            &strap(left_strap, true),
        ],
        panel_curves.clone(),
    )?;
    let back_bottom = join(&[
        arc(fw, "chest", "back_left", "back", k)?,
        arc(fw, "chest", "back", "back_right", k)?,
    ]);
    let back_top = join(&[
        reversed(seam_left.to_vec()),
        arc(fw, "neckline", "left", "back", n.neck)?,
        arc(fw, "neckline", "back", "right", n.neck)?,
        seam_right.to_vec(),
    ]);
    s.patch(
        "panel.back",
        [
            &back_bottom,
            &back_top,
            &reversed(strap(left_strap, false)),
            &reversed(strap(right_strap, false)),
        ],
        panel_curves,
    )
}

fn dress_patches(s: &mut Surfacer<'_>, nv: [usize; 3]) -> Result<(), FrameworkError> {
    let fw = s.fw;
    let k = s.layout.k;
    let names = ["centre_front", "side_left", "centre_back", "side_right"];
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
