//! Easing (\[frame\] section 2.2, step 3): every garment ring point slides along the ray from
//! the deformation centre `O` until its gap to the body ring equals the ease.
//!
//! `O` is the middle of the body ring's extremes. The gap is measured to the convexified
//! body ring (the tape line): across a concavity (between the legs at the crotch ring) the
//! tape already stands off the skin, and along a ray leaving a convex ring the distance to
//! it grows monotonically, so the point is found by bisection to `1e-12` m.

use glam::{DVec2, DVec3};
use thiserror::Error;

use super::convexify::extremes;
use crate::convergence::Bisection;
use crate::geom::Plane;

/// How much room the garment leaves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ease {
    /// The same gap all round, m.
    Uniform(f64),
    /// Gaps at the front, left, back and right extremes, m; in between, linear in the angle
    /// about `O`.
    PerDirection {
        /// At the front extreme.
        front: f64,
        /// At the left extreme.
        left: f64,
        /// At the back extreme.
        back: f64,
        /// At the right extreme.
        right: f64,
    },
}

/// Why a ring cannot be eased.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum EaseError {
    /// Negative or non-finite ease.
    #[error("ease must be finite and not negative (got {0} m)")]
    BadEase(f64),
    /// Too few points.
    #[error("the body ring needs at least 3 points")]
    TooSmall,
    /// A ray from O misses the body ring (O outside it).
    #[error("the ray from the deformation centre through point {0} does not leave the body ring")]
    RayMissed(usize),
}

/// The deformation centre `O` of a ring given in a plane's 2D frame (m): the middle of its
/// extremes' box (\[frame\] section 2.2, step 3).
pub fn deformation_centre(flat: &[DVec2]) -> DVec2 {
    let [front, left, back, right] = extremes(flat).map(|i| flat[i]);
    DVec2::new(0.5 * (front.x + back.x), 0.5 * (left.y + right.y))
}

fn distance_to_ring(p: DVec2, ring: &[DVec2]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            let d = b - a;
            let t = if d.length_squared() > 0.0 {
                ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            p.distance(a + d * t)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Where the ray `o + t dir` (t > 0) leaves the closed ring: the largest crossing `t`.
fn ray_exit(o: DVec2, dir: DVec2, ring: &[DVec2]) -> Option<f64> {
    let n = ring.len();
    (0..n)
        .filter_map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            let e = b - a;
            let denom = dir.perp_dot(e);
            if denom == 0.0 {
                return None;
            }
            let t = (a - o).perp_dot(e) / denom;
            let s = (a - o).perp_dot(dir) / denom;
            // A ray through a vertex must hit one of its two edges despite rounding.
            (t > 0.0 && (-1e-9..=1.0 + 1e-9).contains(&s)).then_some(t)
        })
        .max_by(f64::total_cmp)
}

impl Ease {
    fn at(&self, angle: f64, axes: [f64; 4]) -> f64 {
        match *self {
            Self::Uniform(e) => e,
            Self::PerDirection {
                front,
                left,
                back,
                right,
            } => {
                // Angles of the extremes' directions, increasing around the ring.
                let values = [front, left, back, right];
                let tau = std::f64::consts::TAU;
                let rel = |a: f64| (a - axes[0]).rem_euclid(tau);
                let x = rel(angle);
                let mut marks: Vec<(f64, f64)> = (0..4).map(|k| (rel(axes[k]), values[k])).collect();
                marks.push((tau, front));
                let k = marks.windows(2).position(|w| x >= w[0].0 && x <= w[1].0).unwrap_or(0);
                let (a, b) = (marks[k], marks[k + 1]);
                if b.0 > a.0 {
                    a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)
                } else {
                    a.1
                }
            }
        }
    }

    fn check(&self) -> Result<(), EaseError> {
        let values = match *self {
            Self::Uniform(e) => vec![e],
            Self::PerDirection {
                front,
                left,
                back,
                right,
            } => vec![front, left, back, right],
        };
        match values.into_iter().find(|v| !(v.is_finite() && *v >= 0.0)) {
            Some(bad) => Err(EaseError::BadEase(bad)),
            None => Ok(()),
        }
    }
}

/// Eases `garment` (points in `plane`, m; e.g. a resampled ring) against the convexified
/// body ring `body` (same plane), \[frame\] section 2.2 step 3: every point slides along the
/// ray from `O` until its gap to the body ring is the ease (m). Returns the moved points, in
/// the same order.
pub fn ease_ring(garment: &[DVec3], body: &[DVec3], plane: &Plane, ease: Ease) -> Result<Vec<DVec3>, EaseError> {
    ease.check()?;
    if body.len() < 3 {
        return Err(EaseError::TooSmall);
    }
    let (u, v) = plane.frame();
    let flat: Vec<DVec2> = body.iter().map(|p| plane.project(*p)).collect();
    let o = deformation_centre(&flat);
    let angle = |p: DVec2| (p.y - o.y).atan2(p.x - o.x);
    let axes = extremes(&flat).map(|i| angle(flat[i]));
    let origin = plane.normal * plane.offset;
    garment
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let q = plane.project(*p);
            let dir = (q - o).normalize_or_zero();
            let exit = ray_exit(o, dir, &flat).ok_or(EaseError::RayMissed(i))?;
            let target = ease.at(angle(q), axes);
            // Bisection on the monotone gap along the ray, beyond the exit (tolerances
            // relative to the ring's size: the exit's distance from the centre).
            let size = exit.max(f64::MIN_POSITIVE);
            let (lo, mut hi) = (exit, exit + target.max(1e-9 * size));
            while distance_to_ring(o + dir * hi, &flat) < target {
                hi = exit + 2.0 * (hi - exit);
            }
            let (lo, hi) = Bisection {
                name: "garment.ease.bisection",
                steps: 200,
                tolerance: 1e-13 * size,
                stop_at_tolerance: true,
            }
            .run(lo, hi, |mid| distance_to_ring(o + dir * mid, &flat) < target);
            let w = o + dir * (0.5 * (lo + hi));
            Ok(origin + u * w.x + v * w.y)
        })
        .collect()
}
