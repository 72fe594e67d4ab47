//! Contours through the rings' anchors (\[frame\] section 2.3), and the loose fit that
//! straightens them below a fixed ring and adjusts the rings they pass (section 2.5).

use glam::DVec3;

use super::context::{find, point, section_error};
use crate::garment::adjust::{combined_adjustment, straighten};
use crate::garment::contour::Contour;
use crate::garment::contour::ContourKind;
use crate::garment::model::{FrameworkError, Straightened};
use crate::garment::ring::{GarmentRing, RingOptions};

/// A contour spec: name and the `(ring, anchor)` points it passes, lowest first.
pub type ContourSpec = (String, Vec<(String, String)>);

/// Fits every contour of `specs` through its ring anchors (or the `extra` named points,
/// such as `crotch.point`), as curves of kind `kind` with free ends.
pub fn fit_contours(
    specs: &[ContourSpec],
    rings: &[GarmentRing],
    extra: &[(String, DVec3)],
    kind: ContourKind,
) -> Result<Vec<Contour>, FrameworkError> {
    specs
        .iter()
        .map(|(name, pts)| {
            let through: Vec<String> = pts.iter().map(|(r, a)| format!("{r}.{a}")).collect();
            let points: Vec<DVec3> = pts
                .iter()
                .zip(&through)
                .map(|((r, a), full)| match extra.iter().find(|(n, _)| n == full) {
                    Some((_, p)) => Ok(*p),
                    None => point(rings, r, a),
                })
                .collect::<Result<_, _>>()?;
            Contour::fit(name, through, points, kind).map_err(|e| FrameworkError::Contour(name.clone(), e))
        })
        .collect()
}

/// Loose fit (\[frame\] sections 2.3 and 2.5): straightens the contours below ring `fixed`
/// (which stays: a virtual control point where each contour meets it) and deforms the rings
/// below it by the combined adjustment.
pub fn loosen(
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
        let points: Vec<DVec3> = part.iter().map(|(r, a)| point(rings, r, a)).collect::<Result<_, _>>()?;
        let outward: Vec<DVec3> = part
            .iter()
            .map(|(r, a)| {
                let ring = find(rings, r)?;
                let c = ring.stages.control.iter().copied().sum::<DVec3>() / ring.stages.control.len() as f64;
                let p = point(rings, r, a)?;
                Ok(DVec3::new(p.x - c.x, 0.0, p.z - c.z).normalize_or_zero())
            })
            .collect::<Result<_, FrameworkError>>()?;
        let after = straighten(&points, &outward);
        for ((r, a), (p, q)) in part.iter().zip(points.iter().zip(&after)).skip(1) {
            let anchor = find(rings, r)?
                .anchor(a)
                .map(|x| x.name)
                .ok_or_else(|| section_error(r, format!("anchor {a} missing")))?;
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
