//! A curve's ease and design region applied point by point in its plane, as joint pushes
//! of its mirrored pairs so that a symmetry already made is kept.

use std::collections::BTreeSet;

use glam::{DVec2, DVec3};

use crate::constraint::kinds::{Kind, nearest_on_polygon, signed_gap};
use crate::constraint::network::ConstraintNet;
use crate::convergence::{Stop, record};
use crate::garment::{Ease, ease_ring};

/// A curve's ease and design region, ready to apply point by point in its plane.
pub(super) struct SelfLimits<'a> {
    plane: crate::geom::Plane,
    /// Section, the section in the plane's frame, least gap per control point.
    ease: Vec<(&'a [DVec3], Vec<DVec2>, &'a [f64])>,
    regions: Vec<&'a [DVec2]>,
}

impl<'a> SelfLimits<'a> {
    /// The ease of the curve's self constraints, and its design regions when `regions`.
    pub(super) fn of(net: &'a ConstraintNet, touching: &[usize], plane: &crate::geom::Plane, regions: bool) -> Self {
        let mut out = Self {
            plane: *plane,
            ease: Vec::new(),
            regions: Vec::new(),
        };
        for &k in touching {
            let con = &net.constraints[k];
            match &con.kind {
                Kind::OutsideBody { section, need } if con.is_self() => {
                    let flat = section.iter().map(|p| plane.project(*p)).collect();
                    out.ease.push((section, flat, need));
                }
                Kind::InsidePolygon { polygon } if con.is_self() && regions => out.regions.push(polygon),
                _ => {}
            }
        }
        out
    }

    /// Control point `i` at `p` moved out of its section by the ease, then into the region
    /// (the region wins where they conflict).
    pub(super) fn apply(&self, i: usize, mut p: DVec3, tol: f64) -> DVec3 {
        let plane = &self.plane;
        for (section, flat, need) in &self.ease {
            let n = need[i];
            if signed_gap(plane.project(p), flat) < n - tol
                && let Ok(q) = ease_ring(&[p], section, plane, Ease::Uniform(n))
            {
                p = q[0];
            }
        }
        for polygon in &self.regions {
            let q = plane.project(p);
            if signed_gap(q, polygon) > 0.0 {
                p = plane.lift(nearest_on_polygon(q, polygon).0) + plane.normal * plane.signed_distance(p);
            }
        }
        p
    }

    /// Applies the limits to every point as joint pushes of the mirrored `pairs` (so they
    /// keep a symmetry already made), for up to [`JOINT_ROUNDS`] rounds. Pinned points stay.
    pub(super) fn hold(&self, pairs: &[(usize, usize)], keep: &BTreeSet<usize>, control: &mut [DVec3], tol: f64) {
        if self.ease.is_empty() && self.regions.is_empty() {
            return;
        }
        let (mut rounds, mut last, mut idle) = (0, 0.0, false);
        // At the limit, the residual is the longest push of the last round (which still
        // moved something).
        for round in 0..JOINT_ROUNDS {
            let mut push: Vec<DVec3> = control
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    if keep.contains(&i) {
                        DVec3::ZERO
                    } else {
                        self.apply(i, *p, tol) - *p
                    }
                })
                .collect();
            idle = push.iter().all(|d| *d == DVec3::ZERO);
            if idle {
                break;
            }
            last = push.iter().map(|d| d.length()).fold(0.0, f64::max);
            rounds = round + 1;
            mirror_pushes(pairs, &mut push, keep);
            for (p, d) in control.iter_mut().zip(&push) {
                *p += *d;
            }
        }
        let stop = if idle { Stop::Converged } else { Stop::IterationLimit };
        record("constraint.limits.hold", stop, rounds, if idle { 0.0 } else { last });
    }
}

/// Most rounds of joint pushes, in the node layer and when holding the ease and region (a
/// joint push of a mirrored pair can move the partner where the body is closer; a round or
/// two settles it).
pub(super) const JOINT_ROUNDS: usize = 8;

/// Makes collision pushes symmetric: each mirrored pair `(i, j)` moves by the longer of
/// `push[i]` and the mirror image of `push[j]` (and the partner by its image); a point on
/// the mirror plane moves only along it. Pinned points stay.
pub(super) fn mirror_pushes(pairs: &[(usize, usize)], push: &mut [DVec3], keep: &BTreeSet<usize>) {
    let flip = |d: DVec3| DVec3::new(-d.x, d.y, d.z);
    for &(i, j) in pairs {
        if i == j {
            push[i].x = 0.0;
            continue;
        }
        if keep.contains(&i) || keep.contains(&j) {
            continue;
        }
        let (a, b) = (push[i], flip(push[j]));
        let d = if a.length_squared() >= b.length_squared() { a } else { b };
        push[i] = d;
        push[j] = flip(d);
    }
}
