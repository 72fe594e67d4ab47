//! One garment ring through every sub-step of \[frame\] section 2.2: the raw body section,
//! convexified, resampled, eased, then a closed cubic spline fitted through 8-12 control
//! points (the anchors among them) and resampled. A girth target is met by solving for a
//! uniform extra ease (secant iteration on the fitted spline's length).

mod build;
mod kept;

pub use kept::{BuiltRing, build_or_keep};

use glam::DVec3;
use thiserror::Error;

use super::anchors::AnchorSpec;
use super::ease::{Ease, EaseError};
use super::resample::ResampleError;
use crate::geom::{ChordSpline3, CurveEnds, Plane, SplineError};

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
    /// The fitted closed spline (counter-clockwise about the plane's normal, from above for
    /// a horizontal ring, starting at the first anchor).
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
    /// The girth's error against its target, relative (`None` without a target): the one
    /// definition that the step's figures and the viewer's notes both read.
    pub fn girth_error(&self) -> Option<f64> {
        self.target.map(|t| (self.girth - t) / t)
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
