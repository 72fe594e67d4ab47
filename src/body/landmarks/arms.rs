//! The arm rules: each arm followed down from the armpit level, section by section, to the
//! hand; the **wrist** is the narrowest tape girth above the hand's widest, the **elbow** the
//! bend of the line through the sections' centroids down to the wrist (the corner of the
//! two-segment polyline that fits it best), and the centre line itself (the sleeve's axis)
//! runs from the shoulder point through the sections' centroids to the wrist.
//!
//! A horizontal section of an arm hanging at an angle is an oblique cut: its centroid still
//! lies on the arm's axis, and its girth is the true girth over the cosine of the angle,
//! so girth minima along one arm stay where they are. The girths reported are measured
//! across the axis instead ([`girth_across`]).

use glam::{DVec2, DVec3};

use super::scan::Scan;
use crate::body::mesh::BodyMesh;
use crate::body::profile::MeasuredLoop;
use crate::geom::{Plane, polygon};

/// One arm as scanned, top (the armpit level) to bottom (the hand).
#[derive(Clone, Debug)]
pub(super) struct ArmScan {
    /// `(y, section)` per level, top to bottom.
    pub(super) chain: Vec<(f64, MeasuredLoop)>,
    /// The wrist's level (index into `chain`).
    pub(super) wrist: usize,
    /// The elbow's level (index into `chain`).
    pub(super) elbow: usize,
}

impl ArmScan {
    /// The centroid of level `k` as a point, m.
    pub(super) fn centre(&self, k: usize) -> DVec3 {
        let (y, l) = &self.chain[k];
        DVec3::new(l.centroid.x, *y, l.centroid.y)
    }
}

/// Follows one arm down from its section `start` at height `start_y`, a level
/// (`step` high) at a time: the next section is the one holding the centroid the last two
/// predict, and the arm ends where none does or where the section holding it is more than
/// twice as large as the last (the hand meeting the thigh). `None` for an arm of fewer than
/// 12 levels (nothing to find an elbow on).
pub(super) fn follow_arm(
    scan: &Scan<'_>,
    (start_y, start): (f64, &MeasuredLoop),
    step: f64,
) -> Option<Vec<(f64, MeasuredLoop)>> {
    let mut chain = vec![(start_y, start.clone())];
    let mut y = start_y - step;
    while y > scan.floor {
        let (last, before) = (
            &chain[chain.len() - 1].1,
            chain.len().checked_sub(2).map(|k| &chain[k].1),
        );
        let predicted = before.map_or(last.centroid, |b| 2.0 * last.centroid - b.centroid);
        let loops = scan.loops(y);
        let Some(next) = loops
            .iter()
            .filter(|l| l.contains(predicted) || l.contains(last.centroid))
            .min_by(|a, b| a.area.total_cmp(&b.area))
        else {
            break;
        };
        if next.area > 2.0 * last.area {
            break;
        }
        chain.push((y, next.clone()));
        y -= step;
    }
    (chain.len() >= 12).then_some(chain)
}

/// The wrist, from each level's girth across the arm: the hand is the widest level of the
/// arm's lower third, the wrist the narrowest between the arm's upper third and the hand.
/// (Across, not horizontally: an oblique cut through a flat hand is no wider than one
/// through the wrist.)
pub fn wrist(girths: &[f64]) -> usize {
    let n = girths.len();
    if n == 0 {
        return 0;
    }
    let hand = (2 * n / 3..n)
        .max_by(|&a, &b| girths[a].total_cmp(&girths[b]))
        .unwrap_or(n - 1);
    (n / 3..hand.max(n / 3 + 1))
        .min_by(|&a, &b| girths[a].total_cmp(&girths[b]))
        .unwrap_or(hand)
}

/// The elbow: the corner `k` of the two-segment polyline `points[0] -> points[k] ->
/// points[last]` nearest (least squares) to every point, among the inner points. On a
/// straight line every corner fits and the middle one is taken.
pub fn bend(points: &[DVec3]) -> usize {
    let n = points.len();
    if n < 3 {
        return 0;
    }
    let off_line = |p: DVec3, a: DVec3, b: DVec3| {
        let d = b - a;
        let t = if d.length_squared() > 0.0 {
            ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p - (a + d * t)).length_squared()
    };
    let cost = |k: usize| -> f64 {
        let upper: f64 = points[..=k].iter().map(|p| off_line(*p, points[0], points[k])).sum();
        let lower: f64 = points[k..].iter().map(|p| off_line(*p, points[k], points[n - 1])).sum();
        upper + lower
    };
    let straight = cost(n / 2);
    let (best, least) = (1..n - 1)
        .map(|k| (k, cost(k)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((n / 2, straight));
    // A line within rounding of its chord, or a corner that fits no better than the chord
    // (within 1%): a straight arm, whose middle is taken.
    let chord: f64 = points.iter().map(|p| off_line(*p, points[0], points[n - 1])).sum();
    let span = points[0].distance_squared(points[n - 1]);
    if chord <= 1e-12 * span * n as f64 || chord - least <= 0.01 * chord {
        n / 2
    } else {
        best
    }
}

/// The scan of one arm: followed down from `start`, its wrist and its elbow (the bend of the
/// line through the sections' centroids down to the wrist).
pub(super) fn scan_arm(scan: &Scan<'_>, start: (f64, &MeasuredLoop), step: f64) -> Option<ArmScan> {
    let chain = follow_arm(scan, start, step)?;
    let centres: Vec<DVec3> = chain
        .iter()
        .map(|(y, l)| DVec3::new(l.centroid.x, *y, l.centroid.y))
        .collect();
    let across: Vec<f64> = (0..chain.len())
        .map(|k| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(chain.len() - 1));
            girth_across(scan.body, centres[k], centres[b] - centres[a]).unwrap_or(chain[k].1.tape_girth)
        })
        .collect();
    let wrist = wrist(&across);
    // The bend of the sections' centroids alone: the shoulder point is on the skin above
    // the joint, and a segment to it would bend the line where the arm does not.
    let elbow = bend(&centres[..=wrist]);
    Some(ArmScan { chain, wrist, elbow })
}

/// The girth of the body across a line at `at` along `direction` (the tape around the
/// section by the plane through `at` perpendicular to it, the loop nearest `at`), m; `None`
/// where the plane cuts no closed loop.
pub fn girth_across(body: &BodyMesh, at: DVec3, direction: DVec3) -> Option<f64> {
    let normal = direction.try_normalize()?;
    let plane = Plane::from_point_normal(at, normal);
    body.section(&plane)
        .into_iter()
        .filter(|l| l.closed && l.points.len() >= 3)
        .map(|l| {
            let flat: Vec<DVec2> = l.points.iter().map(|p| plane.project(*p)).collect();
            let centre = l.points.iter().sum::<DVec3>() / l.points.len() as f64;
            (centre.distance(at), polygon::hull_perimeter(&flat))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, girth)| girth)
}
