//! The sleeves' surface and where they meet the bodice.
//!
//! The armhole runs through four points ([`ArmholePoints`]): the strap's top `T`, the
//! points `A` (front) and `A'` (back) where the strap is halfway down from its top to the
//! chest ring (the paper's ring halfway between the armpit and the shoulder point crosses
//! the strap there), and the chest ring's side `S` under the arm. Between them: the strap's
//! upper parts (`A` to `T`, `T` to `A'`) and two lines cleared off the body through the
//! armpit's front and back folds (`S` to `A`, `S` to `A'`, [`armhole_lower_lines`]). The
//! armhole itself, a closed spline fitted through those boundary samples, is a feature line
//! ([`armhole_lines`]). Below the armhole the bodice keeps a three-sided patch in front and
//! behind each arm (chest ring, strap, armhole line).
//!
//! A sleeve's bands: the cap (the armhole to the cap ring, its sides the cap's lines:
//! [`cap_lines`]), then ring to ring down to the cuff, four patches around each.

use glam::DVec3;

use super::{ARMHOLES, anchor_names, contour_names, ring_names};
use crate::garment::contour::{clear_inner, clear_line};
use crate::garment::m0::CurveRef;
use crate::garment::model::{FeatureLine, Framework, FrameworkError};
use crate::garment::open_curve::OpenCurve;
use crate::garment::probe::BodyProbe;
use crate::garment::surface::{Surfacer, anchor, arc, contour, line, missing, open, reversed};
use crate::geom::{ChordSpline3, CurveEnds};

/// The side's name (`side` 0 left, 1 right).
fn side_name(side: usize) -> &'static str {
    if side == 0 { "left" } else { "right" }
}

/// Where an armhole runs: its four points and the strap's parameters at `A` and `A'`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmholePoints {
    /// The strap's top `T`, m.
    pub top: DVec3,
    /// `A`: the strap halfway down in front, m.
    pub front: DVec3,
    /// `S`: the chest ring's side anchor, m.
    pub under: DVec3,
    /// `A'`: the strap halfway down behind, m.
    pub back: DVec3,
    /// The strap's spline parameter at `A`.
    pub front_param: f64,
    /// At `A'`.
    pub back_param: f64,
}

impl ArmholePoints {
    /// The armhole of `side` on a strap and the chest ring's side anchor `under`.
    pub fn new(strap: &OpenCurve, under: DVec3) -> Self {
        let (front_param, back_param) = (strap.midway(true), strap.midway(false));
        let (front, back) = (
            strap.between(front_param, front_param, 1)[0],
            strap.between(back_param, back_param, 1)[0],
        );
        Self {
            top: strap.apex,
            front,
            under,
            back,
            front_param,
            back_param,
        }
    }

    /// In the order `outer` (the top), `front`, `inner` (under the arm), `back`.
    pub fn all(&self) -> [DVec3; 4] {
        [self.top, self.front, self.under, self.back]
    }

    /// The point of anchor `name`.
    pub fn of(&self, name: &str) -> DVec3 {
        match name {
            "outer" => self.top,
            "front" => self.front,
            "inner" => self.under,
            _ => self.back,
        }
    }

    /// Of `side` on a solved framework.
    pub fn on(fw: &Framework, side: usize) -> Result<Self, FrameworkError> {
        let s = side_name(side);
        Ok(Self::new(open(fw, &format!("{s}_strap"))?, anchor(fw, "chest", s)?))
    }
}

/// The strap's part on `side`, in front (`front`) or behind, below `A` (from the chest ring
/// up to it: `lower`) or above it (from `A` up to the top), `n` segments.
pub fn strap_part(
    fw: &Framework,
    side: usize,
    front: bool,
    lower: bool,
    n: usize,
) -> Result<Vec<DVec3>, FrameworkError> {
    let strap = open(fw, &format!("{}_strap", side_name(side)))?;
    let a = ArmholePoints::on(fw, side)?;
    let (end, mid) = if front {
        (0.0, a.front_param)
    } else {
        (strap.spline.length(), a.back_param)
    };
    Ok(if lower {
        strap.between(end, mid, n)
    } else {
        strap.between(mid, strap.apex_param, n)
    })
}

/// The armhole's lower lines of both sides, `k` segments each, from `S` up to `A` in front
/// (`<side>_armhole_front`) and to `A'` behind (`<side>_armhole_back`), cleared `gap` off
/// the body.
pub fn armhole_lower_lines(
    fw: &Framework,
    k: usize,
    probe: &BodyProbe,
    gap: f64,
) -> Result<Vec<FeatureLine>, FrameworkError> {
    let mut out = Vec::new();
    for side in 0..2 {
        let a = ArmholePoints::on(fw, side)?;
        let s = side_name(side);
        for (part, to) in [("front", a.front), ("back", a.back)] {
            out.push(FeatureLine {
                name: format!("{s}_armhole_{part}"),
                points: clear_line(a.under, to, k, probe, gap),
            });
        }
    }
    Ok(out)
}

/// The cap's lines of both sleeves, `n` segments each: from each cap-ring anchor
/// (`<side>_bicep.<anchor>`) to its armhole point, leaving the ring along its contour (a
/// cubic Hermite curve: the contour's tangent at the ring, the chord at the armhole),
/// cleared `gap` off the body. Named `<side>_cap_<anchor>`.
pub fn cap_lines(fw: &Framework, n: usize, probe: &BodyProbe, gap: f64) -> Result<Vec<FeatureLine>, FrameworkError> {
    let sleeves = fw.style.sleeves;
    let mut out = Vec::new();
    for side in 0..2 {
        let Some(cap) = ring_names(sleeves, side).first().copied() else {
            continue;
        };
        let a = ArmholePoints::on(fw, side)?;
        for (c, name) in contour_names(sleeves, side).iter().zip(anchor_names(side)) {
            let from = anchor(fw, cap, name)?;
            let to = a.of(name);
            let chord = to - from;
            let m0 = contour(fw, c)?.end_tangent(1) * chord.length();
            let n = n.max(1);
            let samples: Vec<DVec3> = (0..=n)
                .map(|k| {
                    let t = k as f64 / n as f64;
                    let (t2, t3) = (t * t, t * t * t);
                    from * (2.0 * t3 - 3.0 * t2 + 1.0)
                        + m0 * (t3 - 2.0 * t2 + t)
                        + to * (-2.0 * t3 + 3.0 * t2)
                        + chord * (t3 - t2)
                })
                .collect();
            let mut points = clear_inner(&samples, probe, gap);
            points[0] = from;
            points[n] = to;
            out.push(FeatureLine {
                name: format!("{}_cap_{name}", side_name(side)),
                points,
            });
        }
    }
    Ok(out)
}

/// The armhole of `side` in four pieces, in the sleeve's ring order from its top: piece `i`
/// runs from anchor `i` to anchor `i + 1`; the strap's upper parts with `upper` segments,
/// the lower lines as given among `lines`.
pub fn armhole(
    fw: &Framework,
    lines: &[FeatureLine],
    side: usize,
    upper: usize,
) -> Result<[Vec<DVec3>; 4], FrameworkError> {
    let order = anchor_names(side);
    let s = side_name(side);
    let a = ArmholePoints::on(fw, side)?;
    let mut out: [Vec<DVec3>; 4] = Default::default();
    let mut at = a.top;
    for i in 0..4 {
        let (p, q) = (order[i], order[(i + 1) % 4]);
        let piece = match (p, q) {
            ("outer", "front") | ("front", "outer") => strap_part(fw, side, true, false, upper)?,
            ("outer", "back") | ("back", "outer") => strap_part(fw, side, false, false, upper)?,
            ("front", _) | (_, "front") => line(lines, &format!("{s}_armhole_front"))?.to_vec(),
            _ => line(lines, &format!("{s}_armhole_back"))?.to_vec(),
        };
        let (first, last) = (piece[0], piece[piece.len() - 1]);
        out[i] = if first.distance(at) <= last.distance(at) {
            piece
        } else {
            reversed(piece)
        };
        at = out[i][out[i].len() - 1];
    }
    Ok(out)
}

/// The armholes as feature lines: closed splines fitted through the bodice's boundary
/// samples around each arm, resampled at about `samples` points (the first repeated at the
/// end).
pub fn armhole_lines(
    fw: &Framework,
    lines: &[FeatureLine],
    upper: usize,
    samples: usize,
) -> Result<Vec<FeatureLine>, FrameworkError> {
    let mut out = Vec::new();
    for (side, name) in ARMHOLES.iter().enumerate() {
        let pieces = armhole(fw, lines, side, upper)?;
        let mut boundary: Vec<DVec3> = Vec::new();
        for p in &pieces {
            boundary.extend_from_slice(&p[..p.len() - 1]);
        }
        let spline = ChordSpline3::try_new(&boundary, CurveEnds::Closed)
            .map_err(|e| FrameworkError::Contour(name.to_string(), e))?;
        let mut points = spline.subdivide(samples.div_ceil(boundary.len()).max(1), true);
        if let Some(first) = points.first().copied() {
            points.push(first);
        }
        out.push(FeatureLine {
            name: name.to_string(),
            points,
        });
    }
    Ok(out)
}

/// Both sleeves' patches: per band (the armhole to the cap ring, then ring to ring down to
/// the cuff, `bands[j]` segments along it) four around, `[upper, k, k, upper]` segments
/// along the anchor arcs in ring order.
pub fn sleeve_patches(
    s: &mut Surfacer<'_>,
    lines: &[FeatureLine],
    upper: usize,
    k: usize,
    bands: &[usize],
) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let sleeves = fw.style.sleeves;
    let around = [upper, k, k, upper];
    for side in 0..2 {
        let rings = ring_names(sleeves, side);
        let order = anchor_names(side);
        let contours = contour_names(sleeves, side);
        let hole = armhole(fw, lines, side, upper)?;
        let sname = side_name(side);
        for (j, lower) in rings.iter().enumerate() {
            let nv = bands.get(j).copied().ok_or_else(|| missing(lower, "no band count"))?;
            let upper_ring = if j == 0 { None } else { Some(rings[j - 1]) };
            let band = match upper_ring {
                None => "cap".to_string(),
                Some(u) => format!("{}_{}", short(u), short(lower)),
            };
            for i in 0..4 {
                let (a, b) = (order[i], order[(i + 1) % 4]);
                let bottom = arc(fw, lower, a, b, around[i])?;
                let (top, left, right, mut refs) = match upper_ring {
                    None => {
                        let cap = |x: &str| line(lines, &format!("{sname}_cap_{x}")).map(<[DVec3]>::to_vec);
                        let refs = [
                            lower.to_string(),
                            "chest".to_string(),
                            format!("{sname}_strap"),
                            contours[i].to_string(),
                            contours[(i + 1) % 4].to_string(),
                        ]
                        .iter()
                        .map(|c| CurveRef::whole(c))
                        .collect::<Vec<_>>();
                        (hole[i].clone(), cap(a)?, cap(b)?, refs)
                    }
                    Some(u) => (
                        arc(fw, u, a, b, around[i])?,
                        s.span(contours[i], lower, nv)?,
                        s.span(contours[(i + 1) % 4], lower, nv)?,
                        vec![
                            CurveRef::whole(lower),
                            CurveRef::whole(u),
                            s.span_ref(contours[i], lower)?,
                            s.span_ref(contours[(i + 1) % 4], lower)?,
                        ],
                    ),
                };
                refs.dedup();
                s.patch(
                    &format!("sleeve.{sname}.{band}.{a}"),
                    [&bottom, &top, &left, &right],
                    refs,
                )?;
            }
        }
    }
    Ok(())
}

/// A sleeve ring's name without its side (`bicep`).
fn short(ring: &str) -> &str {
    ring.split_once('_').map_or(ring, |(_, r)| r)
}
