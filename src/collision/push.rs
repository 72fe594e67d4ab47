//! The push of one vertex out of the body along a given direction, to the gap it should
//! stand at (\[collide\] 5.2): the exit along the ray, then secant steps on the exact
//! distance to the body, bracketed, until the distance is the gap; where another part of
//! the body leaves no room for the gap, the middle of the free space.

use glam::DVec3;

use crate::body::index::BodyIndex;
use crate::convergence::{Bisection, Stop, record};

/// Where a push ends: the point, the gap it aimed at (m; the ease, or less where the body
/// leaves no room), and its distance to the body minus that gap (m).
#[derive(Clone, Copy, Debug)]
pub(super) struct Pushed {
    pub(super) to: DVec3,
    pub(super) target: f64,
    pub(super) error: f64,
}

/// How far from its gap a pushed vertex may stand, either way, as a fraction of the gap.
pub const EASE_TOLERANCE: f64 = 1e-3;

/// Moves `p` along unit `d` out of the body and on until it stands `ease` (m) off it, within
/// [`EASE_TOLERANCE`] of it either way; `None` if no ray leaves the body.
///
/// From the exit point the vertex first jumps one ease further along `d` (where its
/// distance is at most the ease: the exit point lies on the surface), then takes secant
/// steps on the distance along the ray, `t += (gap - distance) / slope`, kept inside the
/// bracket of a point short of the gap and one beyond it (bisecting when a step would leave
/// it), until the distance is the gap.
///
/// Where another part of the body lies within two eases beyond the exit along `d` (the
/// other thigh under the crotch, an arm against the torso), there is no room for the ease:
/// the vertex stands in the middle of the free space, as far from both as it can be.
pub(super) fn push_out(index: &BodyIndex, p: DVec3, d: DVec3, ease: f64) -> Option<Pushed> {
    let far = 2.0 * index.height;
    let reach = 0.2 * index.height;
    // Past a surface along the ray before looking for the next one.
    let skip = 1e-6 * index.height;
    let mut q = p;
    for round in 0..8 {
        let outside = round == 0 && index.signed_distance(p, reach).is_none_or(|s| s >= 0.0);
        let mut s = if outside {
            // From outside (an edge's end) the direction must lead away from the body.
            let near = index.nearest(p, reach)?;
            let away = near.way_out(p, index.resolved());
            if d.dot(away) < 0.2 {
                return None;
            }
            // Another part of the body ahead before the ease is reached: the best point
            // between.
            if near.distance < ease
                && let Some((ahead, _)) = index.cast_ray(p, d, skip, 2.0 * ease)
            {
                return Some(best_along(index, p, d, ahead, ease));
            }
            p
        } else {
            let (t, _) = index.cast_ray(q, d, 0.0, far)?;
            let exit = q + d * t;
            if let Some((free, _)) = index.cast_ray(exit, d, skip, 2.0 * ease) {
                return Some(best_along(index, exit, d, free, ease));
            }
            exit + d * ease
        };
        let start = s;
        // Offsets along `d` from `start` known short of the gap and beyond it: a secant step
        // that would leave that bracket bisects it instead.
        let (mut short, mut beyond): (Option<f64>, Option<f64>) = (None, None);
        let mut t = 0.0;
        let mut inside = false;
        for step in 0..PUSH_STEPS {
            s = start + d * t;
            let Some(near) = index.nearest(s, reach) else {
                return Some(Pushed {
                    to: s,
                    target: ease,
                    error: 0.0,
                });
            };
            let signed = near.signed(s);
            if signed < 0.0 {
                inside = true;
                break;
            }
            let err = ease - signed;
            if err.abs() <= EASE_TOLERANCE * ease {
                record("collision.push.secant", Stop::Converged, step + 1, err);
                return Some(Pushed {
                    to: s,
                    target: ease,
                    error: signed - ease,
                });
            }
            if err > 0.0 {
                short = Some(short.map_or(t, |x: f64| x.max(t)));
            } else {
                beyond = Some(beyond.map_or(t, |x: f64| x.min(t)));
            }
            let slope = if signed > 0.0 {
                d.dot(s - near.foot) / signed
            } else {
                1.0
            };
            let mut next = t + err / slope.max(0.2);
            if let (Some(a), Some(b)) = (short, beyond)
                && !(next > a.min(b) && next < a.max(b))
            {
                next = 0.5 * (a + b);
            }
            t = next;
        }
        if !inside {
            // The steps ran out: the nearest point known beyond the gap, else the last.
            let s = start + d * beyond.unwrap_or(t);
            let signed = index.signed_distance(s, reach).unwrap_or(reach);
            record("collision.push.secant", Stop::IterationLimit, PUSH_STEPS, signed - ease);
            return Some(Pushed {
                to: s,
                target: ease,
                error: signed - ease,
            });
        }
        // The point entered another part of the body (an arm, the other leg): go on.
        q = s;
    }
    None
}

/// The point of the segment `from + d t`, `t` in `0..len`, farthest from the body (the free
/// space between two parts of the body along `d`), by a coarse scan of 16 steps and a golden
/// section around the best one; it aims at that distance. Where the distance reaches the
/// ease after all, the first point at the ease instead.
fn best_along(index: &BodyIndex, from: DVec3, d: DVec3, len: f64, ease: f64) -> Pushed {
    let reach = 0.2 * index.height;
    let dist = |t: f64| index.signed_distance(from + d * t, reach).unwrap_or(reach);
    let steps = 16;
    let (mut best_t, mut best) = (0.0, dist(0.0));
    for k in 1..steps {
        let t = len * k as f64 / steps as f64;
        let v = dist(t);
        if v > best {
            (best_t, best) = (t, v);
        }
    }
    // Golden section on the bracket around the best sample.
    let h = len / steps as f64;
    let (mut a, mut b) = ((best_t - h).max(0.0), (best_t + h).min(len));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..30 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if dist(x1) >= dist(x2) {
            b = x2;
        } else {
            a = x1;
        }
    }
    let t = 0.5 * (a + b);
    let v = dist(t);
    let (mut t, v) = if v >= best { (t, v) } else { (best_t, best) };
    if v > ease {
        // Room enough after all: where the distance first reaches the ease (bisection from
        // the start, which stands nearer).
        let (_, hi) = Bisection {
            name: "collision.push.bisection",
            steps: 60,
            tolerance: EASE_TOLERANCE * ease,
            stop_at_tolerance: false,
        }
        .run(0.0, t, |mid| dist(mid) < ease);
        t = hi;
    }
    let v = dist(t);
    let target = v.min(ease);
    Pushed {
        to: from + d * t,
        target,
        error: v - target,
    }
}

/// From `q`, steps out from the nearest surface point to the ease again and again (a point
/// in a concave corner, where the surface it left is no longer the nearest), until it stands
/// the ease off the body or stops gaining: then it aims at what it reached.
pub(super) fn settle(index: &BodyIndex, mut q: DVec3, ease: f64) -> Pushed {
    let reach = 0.2 * index.height;
    let mut reached = index.signed_distance(q, reach).unwrap_or(reach);
    let mut stop = (Stop::IterationLimit, PUSH_STEPS);
    for step in 0..PUSH_STEPS {
        if (reached - ease).abs() <= EASE_TOLERANCE * ease {
            stop = (Stop::Converged, step);
            break;
        }
        let Some(near) = index.nearest(q, reach) else {
            // Nothing of the body within reach: as free as it gets.
            stop = (Stop::Converged, step);
            break;
        };
        let out = near.way_out(q, index.resolved());
        let next = near.foot + out * ease;
        let now = index.signed_distance(next, reach).unwrap_or(reach);
        if now <= reached {
            stop = (Stop::Stalled, step);
            break;
        }
        (q, reached) = (next, now);
    }
    record("collision.push.settle", stop.0, stop.1, reached - ease);
    let target = reached.min(ease);
    Pushed {
        to: q,
        target,
        error: reached - target,
    }
}

/// Most secant steps of one push. Each step closes most of the shortfall; where `d` runs
/// nearly along the surface it closes less, so the steps are many enough for that.
const PUSH_STEPS: usize = 40;
