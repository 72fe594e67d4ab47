//! One garment ring through every sub-step of \[frame\] section 2.2: the raw body section,
//! convexified, resampled, eased, then a closed cubic spline fitted through 8-12 control
//! points (the anchors among them) and resampled. A girth target is met by solving for a
//! uniform extra ease (secant iteration on the fitted spline's length).

use glam::{DVec2, DVec3};
use thiserror::Error;

use super::anchors::{AnchorSpec, locate};
use super::convexify::convex_ring;
use super::ease::{Ease, EaseError, ease_ring};
use super::resample::{ResampleError, resample_closed};
use crate::convergence::{Stop, record};
use crate::geom::{ChordSpline3, CurveEnds, Plane, SplineError, polygon};

/// Most secant steps fitting a ring's girth to its target.
const GIRTH_STEPS: usize = 40;

/// Settings of ring processing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RingOptions {
    /// Points per arc between the body ring's extremes when resampling (default 16: 64 points).
    pub resample_per_arc: usize,
    /// Control points of the fitted spline, anchors included (default 12; 8 to 12).
    pub control_points: usize,
    /// Points of the resampled fitted spline, spread evenly over the anchor arcs (default
    /// 48; 20 to 60).
    pub fitted_points: usize,
    /// Relative girth tolerance of the ease solve, a ratio (default 1e-9).
    pub girth_tolerance: f64,
    /// The largest girth a ring may be asked for, as a multiple of the body's tape girth
    /// there (default 4: a waist of 2.6 m on a 0.65 m waist; a ring any wider is no longer
    /// a garment on this body).
    pub max_girth_ratio: f64,
}

impl Default for RingOptions {
    fn default() -> Self {
        Self {
            resample_per_arc: 16,
            control_points: 12,
            fitted_points: 48,
            girth_tolerance: 1e-9,
            max_girth_ratio: 4.0,
        }
    }
}

impl RingOptions {
    /// Fitted points per arc for a ring with `anchors` anchors.
    pub fn per_arc(&self, anchors: usize) -> usize {
        (self.fitted_points / anchors.max(1)).max(1)
    }
}

/// Why a ring cannot be built.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum RingBuildError {
    /// No section to work from.
    #[error("ring '{0}': the body section is empty")]
    NoSection(String),
    /// Resampling failed.
    #[error("ring '{0}': {1}")]
    Resample(String, ResampleError),
    /// Easing failed.
    #[error("ring '{0}': {1}")]
    Ease(String, EaseError),
    /// The spline could not be fitted.
    #[error("ring '{0}': spline fit failed: {1}")]
    Fit(String, SplineError),
    /// An anchor could not be located.
    #[error("ring '{ring}': anchor '{anchor}' not found (the ring does not cross its plane)")]
    Anchor {
        /// Ring.
        ring: String,
        /// Anchor.
        anchor: &'static str,
    },
    /// The anchors are not in ring order.
    #[error("ring '{0}': its anchors are not in ring order (the ring is too narrow for them)")]
    AnchorOrder(String),
    /// The girth asked for is below the body's.
    #[error(
        "ring '{ring}': girth {target:.4} m is less than the least this ring can have ({minimum:.4} m: the body's tape girth with no ease)"
    )]
    GirthTooSmall {
        /// Ring.
        ring: String,
        /// Asked.
        target: f64,
        /// Least possible.
        minimum: f64,
    },
    /// A girth target above the largest a ring on this body may have.
    #[error(
        "ring '{ring}': girth {target:.4} m is more than {ratio} times the body's tape girth there ({body:.4} m): at most {maximum:.4} m"
    )]
    GirthTooLarge {
        /// Ring.
        ring: String,
        /// Asked.
        target: f64,
        /// The body's tape girth at the ring, m.
        body: f64,
        /// The ratio allowed.
        ratio: f64,
        /// Largest allowed, m.
        maximum: f64,
    },
}

/// The kept sub-steps of one ring (every point list lies in the ring's plane).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RingStages {
    /// The body section loop(s) the ring comes from.
    pub raw: Vec<Vec<DVec3>>,
    /// Convexified (the tape line around the body), m.
    pub convex: Vec<DVec3>,
    /// Resampled at equal chords on the arcs between the extremes, m.
    pub resampled: Vec<DVec3>,
    /// Eased out from the deformation centre, m.
    pub eased: Vec<DVec3>,
    /// The spline's control points (the anchors among them), m.
    pub control: Vec<DVec3>,
    /// The fitted spline resampled, m: `fitted_points` spread evenly over the anchor arcs.
    pub fitted: Vec<DVec3>,
}

/// A named point of a ring with its spline parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Anchor {
    /// Anchor name (`front`, `outer`, ...).
    pub name: &'static str,
    /// Index among the control points.
    pub control: usize,
    /// Spline parameter.
    pub param: f64,
    /// Position, m (world frame).
    pub point: DVec3,
}

/// A finished garment ring.
#[derive(Clone, Debug, PartialEq)]
pub struct GarmentRing {
    /// Ring name (`waist`, `left_knee`, ...).
    pub name: String,
    /// Its plane.
    pub plane: Plane,
    /// Every sub-step.
    pub stages: RingStages,
    /// The fitted closed spline (counter-clockwise seen from above, starting at the first anchor).
    pub spline: ChordSpline3,
    /// Anchors in ring order.
    pub anchors: Vec<Anchor>,
    /// The ease applied (including the extra solved for a girth target).
    pub ease: Ease,
    /// Girth of the fitted spline, m.
    pub girth: f64,
    /// The girth asked for, if any, m.
    pub target: Option<f64>,
    /// The body's tape girth at this ring, m.
    pub body_girth: f64,
}

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

/// Inputs of one ring.
#[derive(Clone, Debug)]
pub struct RingInput<'a> {
    /// Ring name.
    pub name: &'a str,
    /// Plane.
    pub plane: Plane,
    /// Body section loop(s); several are wrapped by their common convex hull.
    pub raw: Vec<Vec<DVec3>>,
    /// Anchors, in ring order starting at the front.
    pub anchors: &'a [AnchorSpec],
    /// Centre line `x` (the body's mid plane), m.
    pub mid_x: f64,
    /// Ease.
    pub ease: Ease,
    /// Girth target, m.
    pub target: Option<f64>,
}

fn flat_area(points: &[DVec3]) -> f64 {
    // Counter-clockwise seen from above is counter-clockwise in (z, x).
    let flat: Vec<DVec2> = points.iter().map(|p| DVec2::new(p.z, p.x)).collect();
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

/// Length of a closed polyline, m (the closing segment included).
pub fn closed_length(points: &[DVec3]) -> f64 {
    let n = points.len();
    (0..n).map(|i| points[i].distance(points[(i + 1) % n])).sum()
}

/// Arc length of a spline between two parameters, by 64-point Gauss-free dense sampling
/// per knot interval (relative error far below 1e-9 for these curves).
pub fn spline_length(spline: &ChordSpline3, closed: bool) -> f64 {
    let samples = spline.subdivide(64, closed);
    if closed {
        closed_length(&samples)
    } else {
        samples.windows(2).map(|w| w[0].distance(w[1])).sum()
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

/// Fits the closed spline through control points and samples it per anchor arc.
fn fit(control: &[DVec3], at: &[usize], per_arc: usize) -> Result<(ChordSpline3, Vec<f64>, Vec<DVec3>), SplineError> {
    let spline = ChordSpline3::try_new(control, CurveEnds::Closed)?;
    let knots = spline.knots().to_vec();
    let params: Vec<f64> = at.iter().map(|&i| knots[i]).collect();
    let length = spline.length();
    let mut fitted = Vec::with_capacity(params.len() * per_arc);
    for k in 0..params.len() {
        let a = params[k];
        let b = if k + 1 < params.len() {
            params[k + 1]
        } else {
            length + params[0]
        };
        for s in 0..per_arc {
            let l = a + (b - a) * s as f64 / per_arc as f64;
            fitted.push(spline.sample(l.rem_euclid(length)));
        }
    }
    Ok((spline, params, fitted))
}

impl GarmentRing {
    /// Runs every sub-step for one ring.
    pub fn build(input: &RingInput<'_>, options: &RingOptions) -> Result<Self, RingBuildError> {
        let name = input.name.to_string();
        let plane = input.plane;
        let mut raw: Vec<Vec<DVec3>> = input.raw.iter().filter(|l| l.len() >= 3).cloned().collect();
        for l in &mut raw {
            if flat_area(l) < 0.0 {
                l.reverse();
            }
        }
        let source: Vec<DVec3> = match raw.len() {
            0 => return Err(RingBuildError::NoSection(name)),
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
                if flat_area(&ring) < 0.0 {
                    ring.reverse();
                }
                ring
            }
        };
        let convex = convex_ring(&source, &plane);
        let resampled = resample_closed(&convex.points, &convex.anchors, options.resample_per_arc)
            .map_err(|e| RingBuildError::Resample(name.clone(), e))?;
        let body_girth = closed_length(&convex.points);
        let attempt = |extra: f64| -> Result<Attempt, RingBuildError> {
            let eased = ease_ring(&resampled, &convex.points, &plane, offset_ease(input.ease, extra))
                .map_err(|e| RingBuildError::Ease(name.clone(), e))?;
            let located = locate(&eased, input.anchors, input.mid_x).map_err(|anchor| RingBuildError::Anchor {
                ring: name.clone(),
                anchor,
            })?;
            let pos: Vec<f64> = located.iter().map(|&(i, t, _)| i as f64 + t).collect();
            let turns: f64 = (0..pos.len())
                .map(|k| (pos[(k + 1) % pos.len()] - pos[k]).rem_euclid(eased.len() as f64))
                .sum();
            let distinct = (0..pos.len()).all(|k| pos[(k + 1) % pos.len()] != pos[k]);
            if pos.len() > 1 && (!distinct || (turns - eased.len() as f64).abs() > 1e-9) {
                return Err(RingBuildError::AnchorOrder(name.clone()));
            }
            let (control, at) = control_points(&eased, &located, options.control_points);
            let (spline, params, fitted) =
                fit(&control, &at, options.per_arc(at.len())).map_err(|e| RingBuildError::Fit(name.clone(), e))?;
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
        };
        let mut extra = 0.0;
        let mut result = attempt(0.0)?;
        if let Some(target) = input.target {
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
            // Secant on girth(extra) = target; the girth grows by about 2 pi per metre of ease.
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

    /// The anchor of this name.
    pub fn anchor(&self, name: &str) -> Option<&Anchor> {
        self.anchors.iter().find(|a| a.name == name)
    }

    /// `n + 1` samples of the arc from anchor `from` to anchor `to` going round the ring in
    /// its direction (counter-clockwise from above), both anchors exact. `None` if either
    /// anchor is unknown.
    pub fn arc(&self, from: &str, to: &str, n: usize) -> Option<Vec<DVec3>> {
        let (a, b) = (self.anchor(from)?, self.anchor(to)?);
        let length = self.spline.length();
        let (la, mut lb) = (a.param, b.param);
        if lb <= la {
            lb += length;
        }
        let n = n.max(1);
        let mut out: Vec<DVec3> = (0..=n)
            .map(|s| {
                self.spline
                    .sample((la + (lb - la) * s as f64 / n as f64).rem_euclid(length))
            })
            .collect();
        out[0] = a.point;
        out[n] = b.point;
        Some(out)
    }

    /// Moves the control points by the combined adjustment and refits (anchors follow).
    pub fn refit(&mut self, control: Vec<DVec3>, options: &RingOptions) -> Result<(), RingBuildError> {
        let at: Vec<usize> = self.anchors.iter().map(|a| a.control).collect();
        let (spline, params, fitted) =
            fit(&control, &at, options.per_arc(at.len())).map_err(|e| RingBuildError::Fit(self.name.clone(), e))?;
        for (a, p) in self.anchors.iter_mut().zip(params) {
            a.param = p;
            a.point = control[a.control];
        }
        self.girth = spline_length(&spline, true);
        self.spline = spline;
        self.stages.fitted = fitted;
        self.stages.control = control;
        Ok(())
    }
}
