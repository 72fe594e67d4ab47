//! Contour lines (\[frame\] sections 2.3-2.4): open cubic curves through the rings' anchor
//! points (centre front, side, princess lines, the legs' front, outer, back and inner
//! lines), from the lowest ring up. Patches take their sides from the spans between rings.
//!
//! By default a contour has local support ([`LocalSpline3`], [`ContourKind::Local`]): a span
//! between two rings depends on the ring points at its ends and the one beyond each, so an
//! edit moves the contour (and the garment) only near the points it moves, and the patches
//! further off keep their samples. [`ContourKind::Natural`] fits the `C2` interpolating spline
//! instead ([`ChordSpline3`]), every span depending on every point.

use glam::DVec3;

use super::probe::BodyProbe;
use crate::geom::{ChordSpline3, CurveEnds, LocalSpline3, SplineError};

/// How contours pass through their points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub enum ContourKind {
    /// Cubic spans with local support ([`crate::geom::LocalSpline3`], `C1`): moving a ring
    /// point reshapes the contour only over the two spans on each side of it, so an edit
    /// re-surfaces only the patches near it.
    #[default]
    Local,
    /// The interpolating cubic spline with natural ends ([`crate::geom::ChordSpline3`],
    /// `C2`): the smoothest curve through the points, but every span depends on every
    /// point, so an edit re-surfaces every patch along the contours it moves.
    Natural,
}

impl ContourKind {
    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Local => "local",
            Self::Natural => "natural",
        }
    }

    /// From the session spelling.
    pub fn from_name(name: &str) -> Option<Self> {
        [Self::Local, Self::Natural].into_iter().find(|c| c.name() == name)
    }
}

/// A contour's curve, by [`ContourKind`].
#[derive(Clone, Debug, PartialEq)]
pub enum ContourCurve {
    /// [`ContourKind::Local`].
    Local(LocalSpline3),
    /// [`ContourKind::Natural`].
    Natural(ChordSpline3),
}

impl ContourCurve {
    /// Which kind it is.
    pub fn kind(&self) -> ContourKind {
        match self {
            Self::Local(_) => ContourKind::Local,
            Self::Natural(_) => ContourKind::Natural,
        }
    }

    /// Total chord length (the parameter range is `[0, length]`).
    pub fn length(&self) -> f64 {
        match self {
            Self::Local(c) => c.length(),
            Self::Natural(c) => c.length(),
        }
    }

    /// The parameters of the points (accumulated chord lengths).
    pub fn knots(&self) -> &[f64] {
        match self {
            Self::Local(c) => c.knots(),
            Self::Natural(c) => c.knots(),
        }
    }

    /// `P(l)`, at accumulated chord length `l`, m.
    pub fn sample(&self, l: f64) -> DVec3 {
        match self {
            Self::Local(c) => c.sample(l),
            Self::Natural(c) => c.sample(l),
        }
    }

    /// `dP/dl`.
    pub fn derivative(&self, l: f64) -> DVec3 {
        match self {
            Self::Local(c) => c.derivative(l),
            Self::Natural(c) => c.derivative(l),
        }
    }

    /// Sample `s` of `n` equal parameter steps along span `k`, `0 < s < n`. A local
    /// curve reads the span's own data only (the same samples wherever its points stay).
    fn span_sample(&self, k: usize, s: usize, n: usize) -> DVec3 {
        match self {
            Self::Local(c) => c.span_sample(k, s as f64 / n as f64),
            Self::Natural(c) => {
                let (a, b) = (c.knots()[k], c.knots()[k + 1]);
                c.sample(a + (b - a) * s as f64 / n as f64)
            }
        }
    }
}

/// A fitted contour.
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    /// Name (`centre_front`, `left_leg_inner`, ...).
    pub name: String,
    /// The control points it passes through, lowest first, each named `ring.anchor`.
    pub through: Vec<String>,
    /// Their positions, m (world frame).
    pub points: Vec<DVec3>,
    /// The curve.
    pub spline: ContourCurve,
    /// Clamped end tangents (lowest end, highest end); `None` leaves that end free.
    pub tangents: [Option<DVec3>; 2],
}

impl Contour {
    /// Fits the contour through `points` (m, lowest first) as a chord-length cubic curve
    /// of kind `kind` with free ends (\[frame\] section 2.3).
    pub fn fit(name: &str, through: Vec<String>, points: Vec<DVec3>, kind: ContourKind) -> Result<Self, SplineError> {
        Self::fit_with(name, through, points, [None, None], kind)
    }

    /// Fits the contour through `points` with the end tangents clamped where given.
    pub fn fit_with(
        name: &str,
        through: Vec<String>,
        points: Vec<DVec3>,
        tangents: [Option<DVec3>; 2],
        kind: ContourKind,
    ) -> Result<Self, SplineError> {
        let spline = match kind {
            ContourKind::Local => ContourCurve::Local(LocalSpline3::try_new(&points, tangents[0], tangents[1])?),
            ContourKind::Natural => ContourCurve::Natural(ChordSpline3::try_new(
                &points,
                CurveEnds::Open {
                    start: tangents[0],
                    end: tangents[1],
                },
            )?),
        };
        Ok(Self {
            name: name.to_string(),
            through,
            points,
            spline,
            tangents,
        })
    }

    /// Refits through new points and end tangents, keeping the name, what it passes and
    /// the kind of curve.
    pub fn refit(&mut self, points: Vec<DVec3>, tangents: [Option<DVec3>; 2]) -> Result<(), SplineError> {
        *self = Self::fit_with(&self.name, self.through.clone(), points, tangents, self.spline.kind())?;
        Ok(())
    }

    /// The unit tangent at the lowest (`0`) or highest (`1`) end, pointing up the contour.
    pub fn end_tangent(&self, end: usize) -> DVec3 {
        let l = if end == 0 { 0.0 } else { self.spline.length() };
        self.spline.derivative(l).normalize_or_zero()
    }

    /// `n + 1` samples (m) of the span from point `k` to point `k + 1`, ends exact. With a
    /// probe, the inner samples are pushed out to stand `gap` (m) off the body.
    pub fn span(&self, k: usize, n: usize, clearance: Option<(&BodyProbe, f64)>) -> Vec<DVec3> {
        let n = n.max(1);
        let raw: Vec<DVec3> = (0..=n)
            .map(|s| match s {
                0 => self.points[k],
                s if s == n => self.points[k + 1],
                s => self.spline.span_sample(k, s, n),
            })
            .collect();
        match clearance {
            Some((probe, gap)) => clear_inner(&raw, probe, gap),
            None => raw,
        }
    }

    /// Dense samples for display (16 per span), m.
    pub fn polyline(&self) -> Vec<DVec3> {
        match &self.spline {
            ContourCurve::Local(c) => c.subdivide(16),
            ContourCurve::Natural(c) => c.subdivide(16, false),
        }
    }
}

/// `samples` with the inner ones (all but the ends) pushed out to stand `gap` (m) off the
/// body.
pub fn clear_inner(samples: &[DVec3], probe: &BodyProbe, gap: f64) -> Vec<DVec3> {
    let last = samples.len().saturating_sub(1);
    samples
        .iter()
        .enumerate()
        .map(|(s, &p)| if s == 0 || s == last { p } else { probe.clear(p, gap) })
        .collect()
}

/// A short feature line between two control points that no section gives (a shoulder
/// seam, the crotch junction): `n + 1` samples of the straight line from `a` to `b` (m), its
/// inner samples pushed out to stand `gap` (m) off the body.
pub fn clear_line(a: DVec3, b: DVec3, n: usize, probe: &BodyProbe, gap: f64) -> Vec<DVec3> {
    let n = n.max(1);
    (0..=n)
        .map(|s| match s {
            0 => a,
            s if s == n => b,
            s => probe.clear(a.lerp(b, s as f64 / n as f64), gap),
        })
        .collect()
}
