//! The sleeves' surface: the armhole (the bodice's boundary around the arm: the strap over
//! the shoulder and the chest ring under the arm, cut at the sleeve's four anchors), and
//! four patches around each band of a sleeve, from the armhole down to the cuff.

use glam::DVec3;

use super::{ARMHOLES, anchor_names, armhole_points, contour_names, ring_names};
use crate::garment::anchors::TORSO;
use crate::garment::m0::CurveRef;
use crate::garment::model::{FeatureLine, Framework, FrameworkError};
use crate::garment::surface::{Surfacer, arc, missing, open, reversed};
use crate::geom::{ChordSpline3, CurveEnds};

/// The armhole of `side` (0 left, 1 right) in four pieces, in the sleeve's ring order from
/// its top: piece `i` runs from anchor `i` to anchor `i + 1`, with `strap` segments on the
/// strap's halves and `k` on the chest ring's arcs (the bodice's own samples there).
pub fn armhole(fw: &Framework, side: usize, strap: usize, k: usize) -> Result<[Vec<DVec3>; 4], FrameworkError> {
    let order = anchor_names(side);
    let points = armhole_points(side);
    let point_of = |name: &str| -> Result<DVec3, FrameworkError> {
        let (curve, anchor, _) = points
            .iter()
            .find(|(_, _, n)| *n == name)
            .ok_or_else(|| missing(ARMHOLES[side], &format!("no point {name}")))?;
        match fw.open_curves.iter().find(|c| &c.name == curve) {
            Some(c) => Ok(c.apex),
            None => crate::garment::surface::anchor(fw, curve, anchor),
        }
    };
    let s = if side == 0 { "left" } else { "right" };
    let strap_curve = open(fw, &format!("{s}_strap"))?;
    let chest_name = |n: &str| match n {
        "front" => format!("front_{s}"),
        "back" => format!("back_{s}"),
        _ => s.to_string(),
    };
    let mut out: [Vec<DVec3>; 4] = Default::default();
    for i in 0..4 {
        let (a, b) = (order[i], order[(i + 1) % 4]);
        let piece = match (a, b) {
            ("top", "front") | ("front", "top") => strap_curve.half(true, strap),
            ("top", "back") | ("back", "top") => strap_curve.half(false, strap),
            _ => {
                let (p, q) = (chest_name(a), chest_name(b));
                let ip = TORSO.iter().position(|t| *t == p).unwrap_or(0);
                let iq = TORSO.iter().position(|t| *t == q).unwrap_or(0);
                if iq == (ip + 1) % TORSO.len() {
                    arc(fw, "chest", &p, &q, k)?
                } else {
                    reversed(arc(fw, "chest", &q, &p, k)?)
                }
            }
        };
        let start = point_of(a)?;
        let (first, last) = (piece[0], piece[piece.len() - 1]);
        out[i] = if first.distance(start) <= last.distance(start) {
            piece
        } else {
            reversed(piece)
        };
    }
    Ok(out)
}

/// The armholes as feature lines: closed splines fitted through the bodice's boundary
/// samples around each arm, resampled at `samples` points (the first repeated at the end).
pub fn armhole_lines(
    fw: &Framework,
    strap: usize,
    k: usize,
    samples: usize,
) -> Result<Vec<FeatureLine>, FrameworkError> {
    let mut out = Vec::new();
    for side in 0..2 {
        let pieces = armhole(fw, side, strap, k)?;
        let mut boundary: Vec<DVec3> = Vec::new();
        for p in &pieces {
            boundary.extend_from_slice(&p[..p.len() - 1]);
        }
        let spline = ChordSpline3::try_new(&boundary, CurveEnds::Closed)
            .map_err(|e| FrameworkError::Contour(ARMHOLES[side].to_string(), e))?;
        let mut points = spline.subdivide(samples.div_ceil(boundary.len()).max(1), true);
        if let Some(first) = points.first().copied() {
            points.push(first);
        }
        out.push(FeatureLine {
            name: ARMHOLES[side].to_string(),
            points,
        });
    }
    Ok(out)
}

/// Both sleeves' patches: per band (armhole to the first ring, then ring to ring down to
/// the cuff, `bands[j]` segments along it) four around, `[strap, k, k, strap]` segments
/// along the anchor arcs in ring order.
pub fn sleeve_patches(s: &mut Surfacer<'_>, strap: usize, k: usize, bands: &[usize]) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let sleeves = fw.style.sleeves;
    let around = [strap, k, k, strap];
    for side in 0..2 {
        let rings = ring_names(sleeves, side);
        let order = anchor_names(side);
        let contours = contour_names(sleeves, side);
        let hole = armhole(fw, side, strap, k)?;
        let sname = if side == 0 { "left" } else { "right" };
        for (j, lower) in rings.iter().enumerate() {
            let nv = bands.get(j).copied().ok_or_else(|| missing(lower, "no band count"))?;
            let upper = if j == 0 { None } else { Some(rings[j - 1]) };
            let band = match upper {
                None => "cap".to_string(),
                Some(u) => format!("{}_{}", short(u), short(lower)),
            };
            let mut curves = vec![CurveRef::whole(lower)];
            match upper {
                None => curves.extend([CurveRef::whole("chest"), CurveRef::whole(&format!("{sname}_strap"))]),
                Some(u) => curves.push(CurveRef::whole(u)),
            }
            for i in 0..4 {
                let (a, b) = (order[i], order[(i + 1) % 4]);
                let bottom = arc(fw, lower, a, b, around[i])?;
                let top = match upper {
                    None => hole[i].clone(),
                    Some(u) => arc(fw, u, a, b, around[i])?,
                };
                let left = s.span(contours[i], lower, nv)?;
                let right = s.span(contours[(i + 1) % 4], lower, nv)?;
                let mut refs = curves.clone();
                refs.push(s.span_ref(contours[i], lower)?);
                refs.push(s.span_ref(contours[(i + 1) % 4], lower)?);
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
