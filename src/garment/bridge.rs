//! Gaps the garment does not enter. Where two parts of the body come nearer each other than
//! twice the ease (thighs that touch below the crotch, a belly over the groin), a curve
//! eased in its plane against one section (\[frame\] section 2.2) stands inside the gap,
//! nearer the other part than the ease; the patches between such a curve and the surface
//! outside the gap can then only reach it with edges that cut through the body. A garment
//! bridges such a gap instead: the point goes on, the way it was eased, until it has the
//! ease all round.
//!
//! A point is **in a gap** of width `w` when it stands nearer the body than `w / 2` and the
//! body is met again behind it (on the ray from its nearest skin point through it) within
//! `w`: two walls nearer each other than `w`. The width is twice the ease, or the garment
//! mesh's edge where that is longer: a patch cannot follow a gap narrower than its edges
//! without cutting through a wall. A point nearer the body for any other reason (its own
//! section's surface sloping towards the plane) is left where the paper's easing put it.
//! The march is sphere tracing on the body's distance, which changes by at most the step;
//! it stops at the first point out of every such gap with the ease.

use glam::DVec3;

use crate::convergence::Bisection;

use super::probe::BodyProbe;

/// Relative tolerance on a distance when deciding that a point has it.
const TOLERANCE: f64 = 1e-6;

/// Whether `p` stands in a gap of the body narrower than `width` (m): nearer the body than
/// half of it, with the body met again behind it within the width.
pub fn in_gap(probe: &BodyProbe, p: DVec3, width: f64) -> bool {
    let Some((foot, d, normal)) = probe.nearest(p) else {
        return false;
    };
    if d >= 0.5 * width * (1.0 - TOLERANCE) {
        return false;
    }
    let away = if d.abs() > 0.0 { (p - foot) * d.signum() } else { normal };
    let Some(away) = away.try_normalize() else {
        return false;
    };
    let index = probe.index();
    let start = if d < 0.0 { foot } else { p };
    let room = width - d.max(0.0);
    index.cast_ray(start, away, 1e-9 * index.height, room).is_some()
}

/// How a curve bridges gaps: the ease it needs all round and the narrowest gap it
/// enters, m; how far a point may go, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bridging {
    /// The ease, m.
    pub gap: f64,
    /// Gaps narrower than this are bridged, m: at least twice the ease, and at least the
    /// mesh's edge (a patch cannot follow a gap narrower than its edges without cutting
    /// through the walls).
    pub width: f64,
    /// Farthest a point goes, m.
    pub reach: f64,
}

/// `p` moved along `dir` until it stands out of every gap narrower than the width and
/// `gap` off the body, when it stands in such a gap; `p` itself otherwise, or when no
/// point within the reach along `dir` will do.
pub fn bridge(probe: &BodyProbe, p: DVec3, dir: DVec3, b: &Bridging) -> DVec3 {
    let Some(dir) = dir.try_normalize() else {
        return p;
    };
    if b.gap <= 0.0 || !in_gap(probe, p, b.width) {
        return p;
    }
    let floor_step = 1e-4 * b.gap;
    let done = |q: DVec3| probe.signed_distance(q) >= b.gap * (1.0 - TOLERANCE) && !in_gap(probe, q, b.width);
    let mut travelled = 0.0;
    let mut q = p;
    for _ in 0..10_000 {
        let d = probe.signed_distance(q);
        // Sphere tracing towards the half width (which also clears the ease): the distance
        // changes by at most the step, so no step passes over a point with the ease.
        let step = (0.5 * b.width.max(2.0 * b.gap) - d).max(floor_step);
        let next = q + dir * step;
        travelled += step;
        if travelled > b.reach {
            break;
        }
        if done(next) {
            // The first point that will do lies within the last step: bisection.
            let (_, hi) = Bisection {
                name: "bridge.bisection",
                steps: 60,
                tolerance: 1e-9 * b.gap,
                stop_at_tolerance: false,
            }
            .run(q, next, |mid| !done(mid));
            return hi;
        }
        q = next;
    }
    p
}

/// Bridges every point of `points` (m) in a gap along its own direction `dirs[i]`; the first
/// and last `keep` points stay (ends pinned elsewhere).
pub fn bridge_all(probe: &BodyProbe, points: &mut [DVec3], dirs: &[DVec3], b: &Bridging, keep: usize) {
    let n = points.len();
    for i in keep..n.saturating_sub(keep) {
        points[i] = bridge(probe, points[i], dirs[i], b);
    }
}
