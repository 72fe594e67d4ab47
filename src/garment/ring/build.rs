//! Building one ring through its sub-steps: the body's section loop (several wrapped by
//! their hull), convexified, resampled; then each try at an extra ease (eased, anchors
//! located, control points, the spline fitted); and the girth target met by a secant on the
//! extra ease.

use glam::{DVec2, DVec3};

use super::{
    Anchor, GarmentRing, RingBuildError, RingInput, RingOptions, RingStages, closed_length, fit, spline_length,
};
use crate::convergence::{Stop, record};
use crate::garment::anchors::locate;
use crate::garment::convexify::convex_ring;
use crate::garment::ease::{Ease, ease_ring};
use crate::garment::resample::resample_closed;
use crate::geom::{ChordSpline3, Plane, polygon};

/// Most secant steps fitting a ring's girth to its target.
const GIRTH_STEPS: usize = 40;

/// One try at the ring with a given extra ease: every sub-step from easing on, and the
/// fitted spline's girth (m).
struct Attempt {
    eased: Vec<DVec3>,
    control: Vec<DVec3>,
    at: Vec<usize>,
    spline: ChordSpline3,
    params: Vec<f64>,
    fitted: Vec<DVec3>,
    girth: f64,
}

/// The signed area of `points` around `plane`'s normal: positive counter-clockwise about
/// it (for a horizontal plane, counter-clockwise seen from above, in `(z, x)`; a sleeve's
/// ring, whose normal points up the sleeve, counter-clockwise seen from the hand).
fn flat_area(points: &[DVec3], plane: &Plane) -> f64 {
    let flat: Vec<DVec2> = points.iter().map(|p| plane.project(*p)).collect();
    polygon::signed_area(&flat)
}

fn offset_ease(ease: Ease, extra: f64) -> Ease {
    match ease {
        Ease::Uniform(e) => Ease::Uniform(e + extra),
        Ease::PerDirection {
            front,
            left,
            back,
            right,
        } => Ease::PerDirection {
            front: front + extra,
            left: left + extra,
            back: back + extra,
            right: right + extra,
        },
    }
}

fn least_ease(ease: Ease) -> f64 {
    match ease {
        Ease::Uniform(e) => e,
        Ease::PerDirection {
            front,
            left,
            back,
            right,
        } => front.min(left).min(back).min(right),
    }
}

/// Control points on the closed polyline: the anchors plus evenly spaced points (by length)
/// on the arcs between them, the longest arcs served first; anchor positions returned.
fn control_points(points: &[DVec3], located: &[(usize, f64, DVec3)], total: usize) -> (Vec<DVec3>, Vec<usize>) {
    let n = points.len();
    // Position of each anchor along the ring: (segment + t).
    let m = located.len();
    // Polyline of each arc from anchor k to k + 1.
    let arcs: Vec<Vec<DVec3>> = (0..m)
        .map(|k| {
            let (a, b) = (located[k], located[(k + 1) % m]);
            let mut arc = vec![a.2];
            let mut i = (a.0 + 1) % n;
            // Vertices strictly between the two anchors.
            let last = if b.1 > 0.0 { b.0 } else { b.0 + n - 1 };
            let steps = if m == 1 { n - 1 } else { (last + n - a.0) % n };
            for _ in 0..steps {
                arc.push(points[i]);
                i = (i + 1) % n;
            }
            arc.push(b.2);
            arc
        })
        .collect();
    let lengths: Vec<f64> = arcs
        .iter()
        .map(|a| a.windows(2).map(|w| w[0].distance(w[1])).sum())
        .collect();
    let mut extra = vec![0usize; m];
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&a, &b| lengths[b].total_cmp(&lengths[a]).then(a.cmp(&b)));
    let mut left = total.saturating_sub(m);
    while left > 0 {
        for &k in &order {
            if left == 0 {
                break;
            }
            extra[k] += 1;
            left -= 1;
        }
    }
    let mut out = Vec::with_capacity(total.max(m));
    let mut at = Vec::with_capacity(m);
    for k in 0..m {
        at.push(out.len());
        out.push(located[k].2);
        let arc = &arcs[k];
        for e in 1..=extra[k] {
            let goal = lengths[k] * e as f64 / (extra[k] + 1) as f64;
            let mut walked = 0.0;
            for w in arc.windows(2) {
                let d = w[0].distance(w[1]);
                if walked + d >= goal && d > 0.0 {
                    out.push(w[0].lerp(w[1], (goal - walked) / d));
                    break;
                }
                walked += d;
            }
        }
    }
    (out, at)
}

impl GarmentRing {
    /// Runs every sub-step for one ring.
    pub fn build(input: &RingInput<'_>, options: &RingOptions) -> Result<Self, RingBuildError> {
        let name = input.name.to_string();
        let plane = input.plane;
        let (raw, source) = section_loop(input, &name)?;
        let convex = convex_ring(&source, &plane);
        let resampled = resample_closed(&convex.points, &convex.anchors, options.resample_per_arc)
            .map_err(|e| RingBuildError::Resample(name.clone(), e))?;
        let body_girth = closed_length(&convex.points);
        let attempt = |extra: f64| try_ring(input, options, (&name, &plane), (&resampled, &convex.points), extra);
        let mut extra = 0.0;
        let mut result = attempt(0.0)?;
        if let Some(target) = input.target {
            (extra, result) = meet_girth(&attempt, result, target, (input, options), body_girth)?;
        }
        let Attempt {
            eased,
            control,
            at,
            spline,
            params,
            fitted,
            girth,
        } = result;
        let anchors = input
            .anchors
            .iter()
            .zip(at.iter().zip(&params))
            .map(|(spec, (&i, &param))| Anchor {
                name: spec.name,
                control: i,
                param,
                point: control[i],
            })
            .collect();
        Ok(Self {
            name,
            plane,
            stages: RingStages {
                raw,
                convex: convex.points,
                resampled,
                eased,
                control,
                fitted,
            },
            spline,
            anchors,
            ease: offset_ease(input.ease, extra),
            girth,
            target: input.target,
            body_girth,
        })
    }
}

/// The ring's section loops (those of 3 points or more, each counter-clockwise about the
/// plane's normal: from above for a horizontal ring)
/// and the loop the ring is made from: the one loop, or the common convex hull of several
/// in the plane (a skirt around both legs).
fn section_loop(input: &RingInput<'_>, name: &str) -> Result<(Vec<Vec<DVec3>>, Vec<DVec3>), RingBuildError> {
    let plane = input.plane;
    let mut raw: Vec<Vec<DVec3>> = input.raw.iter().filter(|l| l.len() >= 3).cloned().collect();
    for l in &mut raw {
        if flat_area(l, &plane) < 0.0 {
            l.reverse();
        }
    }
    let source: Vec<DVec3> = match raw.len() {
        0 => return Err(RingBuildError::NoSection(name.to_string())),
        1 => raw[0].clone(),
        _ => {
            // Several loops (a skirt around both legs): their common convex hull, in the plane.
            let all: Vec<DVec3> = raw.iter().flatten().copied().collect();
            let flat: Vec<DVec2> = all.iter().map(|p| plane.project(*p)).collect();
            let hull = polygon::convex_hull(&flat);
            let mut ring: Vec<DVec3> = hull
                .iter()
                .filter_map(|h| flat.iter().position(|f| f == h).map(|i| all[i]))
                .collect();
            if flat_area(&ring, &plane) < 0.0 {
                ring.reverse();
            }
            ring
        }
    };
    Ok((raw, source))
}

/// One try at the ring with `extra` ease over the input's: eased off the convex loop
/// `(resampled, convex)`, anchors located (in ring order, each once), control points taken,
/// the spline fitted and measured.
fn try_ring(
    input: &RingInput<'_>,
    options: &RingOptions,
    (name, plane): (&str, &Plane),
    (resampled, convex): (&[DVec3], &[DVec3]),
    extra: f64,
) -> Result<Attempt, RingBuildError> {
    let eased = ease_ring(resampled, convex, plane, offset_ease(input.ease, extra))
        .map_err(|e| RingBuildError::Ease(name.to_string(), e))?;
    let located = locate(&eased, input.anchors, input.mid_x).map_err(|anchor| RingBuildError::Anchor {
        ring: name.to_string(),
        anchor,
    })?;
    let pos: Vec<f64> = located.iter().map(|&(i, t, _)| i as f64 + t).collect();
    let turns: f64 = (0..pos.len())
        .map(|k| (pos[(k + 1) % pos.len()] - pos[k]).rem_euclid(eased.len() as f64))
        .sum();
    let distinct = (0..pos.len()).all(|k| pos[(k + 1) % pos.len()] != pos[k]);
    if pos.len() > 1 && (!distinct || (turns - eased.len() as f64).abs() > 1e-9) {
        return Err(RingBuildError::AnchorOrder(name.to_string()));
    }
    let (control, at) = control_points(&eased, &located, options.control_points);
    let (spline, params, fitted) =
        fit(&control, &at, options.per_arc(at.len())).map_err(|e| RingBuildError::Fit(name.to_string(), e))?;
    let girth = spline_length(&spline, true);
    Ok(Attempt {
        eased,
        control,
        at,
        spline,
        params,
        fitted,
        girth,
    })
}

/// The extra ease that brings the ring's girth to `target` (a secant on girth(extra); the
/// girth grows by about 2 pi per metre of ease), from the try `first` with none: the extra
/// and its try. Refused when the target is beyond the body's girth times the allowed ratio,
/// or below the girth with the least ease taken away.
fn meet_girth(
    attempt: &dyn Fn(f64) -> Result<Attempt, RingBuildError>,
    first: Attempt,
    target: f64,
    (input, options): (&RingInput<'_>, &RingOptions),
    body_girth: f64,
) -> Result<(f64, Attempt), RingBuildError> {
    let name = input.name.to_string();
    let mut extra = 0.0;
    let mut result = first;
    let floor = -least_ease(input.ease);
    let maximum = options.max_girth_ratio * body_girth;
    if target > maximum {
        return Err(RingBuildError::GirthTooLarge {
            ring: name,
            target,
            body: body_girth,
            ratio: options.max_girth_ratio,
            maximum,
        });
    }
    let minimum = attempt(floor)?.girth;
    if !(target.is_finite() && target >= minimum) {
        return Err(RingBuildError::GirthTooSmall {
            ring: name,
            target,
            minimum,
        });
    }
    let (mut x0, mut g0) = (0.0, result.girth);
    let mut x1 = ((target - g0) / std::f64::consts::TAU).max(floor);
    let mut stop = (Stop::IterationLimit, GIRTH_STEPS);
    for step in 0..GIRTH_STEPS {
        let r = attempt(x1)?;
        let g1 = r.girth;
        extra = x1;
        result = r;
        if (g1 - target).abs() <= options.girth_tolerance * target {
            stop = (Stop::Converged, step + 1);
            break;
        }
        if step > 0 && x1 == x0 {
            // The step changed nothing (pinned at the floor).
            stop = (Stop::Stalled, step + 1);
            break;
        }
        let slope = if (x1 - x0).abs() > 0.0 {
            (g1 - g0) / (x1 - x0)
        } else {
            std::f64::consts::TAU
        };
        let slope = if slope > 0.5 { slope } else { std::f64::consts::TAU };
        (x0, g0) = (x1, g1);
        x1 = (x1 + (target - g1) / slope).max(floor);
    }
    record("garment.ring.girth_secant", stop.0, stop.1, result.girth - target);
    Ok((extra, result))
}
