//! Contour lines (\[frame\] sections 2.3-2.4): open cubic splines through the rings' anchor
//! points (centre front, side, princess lines, the legs' front, outer, back and inner
//! lines), from the lowest ring up. Patches take their sides from the spans between rings.

use glam::DVec3;

use super::probe::BodyProbe;
use crate::geom::{ChordSpline3, CurveEnds, SplineError};

/// A fitted contour.
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    /// Name (`centre_front`, `left_leg_inner`, ...).
    pub name: String,
    /// The control points it passes through, lowest first, each named `ring.anchor`.
    pub through: Vec<String>,
    /// Their positions, m (world frame).
    pub points: Vec<DVec3>,
    /// The spline.
    pub spline: ChordSpline3,
    /// Clamped end tangents (lowest end, highest end); `None` leaves that end natural.
    pub tangents: [Option<DVec3>; 2],
}

impl Contour {
    /// Fits the contour through `points` (m, lowest first) as a chord-length cubic spline with
    /// natural ends (\[frame\] section 2.3).
    pub fn fit(name: &str, through: Vec<String>, points: Vec<DVec3>) -> Result<Self, SplineError> {
        Self::fit_with(name, through, points, [None, None])
    }

    /// Fits the contour through `points` with the end tangents clamped where given.
    pub fn fit_with(
        name: &str,
        through: Vec<String>,
        points: Vec<DVec3>,
        tangents: [Option<DVec3>; 2],
    ) -> Result<Self, SplineError> {
        let spline = ChordSpline3::try_new(
            &points,
            CurveEnds::Open {
                start: tangents[0],
                end: tangents[1],
            },
        )?;
        Ok(Self {
            name: name.to_string(),
            through,
            points,
            spline,
            tangents,
        })
    }

    /// Refits through new points and end tangents, keeping the name and what it passes.
    pub fn refit(&mut self, points: Vec<DVec3>, tangents: [Option<DVec3>; 2]) -> Result<(), SplineError> {
        *self = Self::fit_with(&self.name, self.through.clone(), points, tangents)?;
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
        let knots = self.spline.knots();
        let (a, b) = (knots[k], knots[k + 1]);
        let n = n.max(1);
        let raw: Vec<DVec3> = (0..=n)
            .map(|s| match s {
                0 => self.points[k],
                s if s == n => self.points[k + 1],
                s => self.spline.sample(a + (b - a) * s as f64 / n as f64),
            })
            .collect();
        match clearance {
            Some((probe, gap)) => clear_inner(&raw, probe, gap),
            None => raw,
        }
    }

    /// Dense samples for display (16 per span), m.
    pub fn polyline(&self) -> Vec<DVec3> {
        self.spline.subdivide(16, false)
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
