//! Parametric cubic splines in 3D on accumulated chord length (\[spline\] section 4):
//! `x(l)`, `y(l)`, `z(l)` each interpolate the points against `l_i = sum |P_k - P_{k-1}|`.
//! Closed curves use periodic ends; open ones, given end tangents (clamped) or natural ends.

use glam::DVec3;

use super::spline::{CubicSpline, EndCondition, SplineError};

/// How a parametric curve ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CurveEnds {
    /// A closed loop: the last point joins the first, periodic ends.
    Closed,
    /// An open curve; `Some(direction)` clamps `dP/dl` there (normalized here: a
    /// chord-length parametrization has unit speed), `None` leaves that end natural.
    Open {
        /// Tangent direction at the first point.
        start: Option<DVec3>,
        /// Tangent direction at the last point.
        end: Option<DVec3>,
    },
}

/// A 3D curve through points, parametrized by accumulated chord length.
#[derive(Clone, Debug, PartialEq)]
pub struct ChordSpline3 {
    axes: [CubicSpline; 3],
    length: f64,
}

impl ChordSpline3 {
    /// Builds the curve through `points`.
    ///
    /// # Failures
    /// Two consecutive points that coincide give a zero chord: [`SplineError::NotIncreasing`]
    /// with the index of the second one. Fewer than 2 points (3 closed) or non-finite input
    /// fail as for [`CubicSpline::try_new`].
    pub fn try_new(points: &[DVec3], ends: CurveEnds) -> Result<Self, SplineError> {
        let mut pts = points.to_vec();
        if ends == CurveEnds::Closed
            && let Some(&first) = points.first()
        {
            pts.push(first);
        }
        let mut l = Vec::with_capacity(pts.len());
        let mut acc = 0.0;
        for (i, p) in pts.iter().enumerate() {
            if i > 0 {
                acc += p.distance(pts[i - 1]);
            }
            l.push(acc);
        }
        let ends_for = |axis: usize| match ends {
            CurveEnds::Closed => EndCondition::Periodic,
            CurveEnds::Open { start: None, end: None } => EndCondition::Natural,
            CurveEnds::Open { start, end } => {
                // One natural end with one clamped end is not offered by CubicSpline: a
                // missing tangent becomes the chord direction there.
                let first_chord = pts.get(1).map_or(DVec3::ZERO, |p| (*p - pts[0]).normalize_or_zero());
                let n = pts.len();
                let last_chord = (pts[n - 1] - pts[n.saturating_sub(2)]).normalize_or_zero();
                let s = start.map_or(first_chord, DVec3::normalize_or_zero);
                let e = end.map_or(last_chord, DVec3::normalize_or_zero);
                EndCondition::Clamped {
                    start_slope: s[axis],
                    end_slope: e[axis],
                }
            }
        };
        let column = |axis: usize| -> Vec<f64> { pts.iter().map(|p| p[axis]).collect() };
        let axes = [
            CubicSpline::try_new(&l, &column(0), ends_for(0))?,
            CubicSpline::try_new(&l, &column(1), ends_for(1))?,
            CubicSpline::try_new(&l, &column(2), ends_for(2))?,
        ];
        Ok(Self { axes, length: acc })
    }

    /// Total chord length (the parameter range is `[0, length]`).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The parameters of the interpolated points (accumulated chord lengths).
    pub fn knots(&self) -> &[f64] {
        self.axes[0].knots()
    }

    /// `P(l)`, at accumulated chord length `l` (both in the input's units, m in drape).
    pub fn sample(&self, l: f64) -> DVec3 {
        DVec3::new(self.axes[0].sample(l), self.axes[1].sample(l), self.axes[2].sample(l))
    }

    /// `dP/dl`, unitless (close to unit length: `l` is close to arc length).
    pub fn derivative(&self, l: f64) -> DVec3 {
        DVec3::new(
            self.axes[0].derivative(l),
            self.axes[1].derivative(l),
            self.axes[2].derivative(l),
        )
    }

    /// Each knot interval split into `k` equal parameter steps: `k * intervals (+1 if open)` points.
    pub fn subdivide(&self, k: usize, closed: bool) -> Vec<DVec3> {
        let knots = self.knots();
        let mut out = Vec::with_capacity(knots.len() * k);
        for w in knots.windows(2) {
            for s in 0..k {
                out.push(self.sample(w[0] + (w[1] - w[0]) * s as f64 / k as f64));
            }
        }
        if !closed {
            out.push(self.sample(self.length));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_circle_is_close_to_round() {
        let n = 24;
        let pts: Vec<DVec3> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                DVec3::new(a.cos(), 0.5, a.sin())
            })
            .collect();
        let c = ChordSpline3::try_new(&pts, CurveEnds::Closed).unwrap();
        for p in c.subdivide(5, true) {
            assert!((DVec3::new(p.x, 0.0, p.z).length() - 1.0).abs() < 2e-5 && (p.y - 0.5).abs() < 1e-14);
        }
    }

    #[test]
    fn coincident_points_are_refused() {
        let pts = [DVec3::ZERO, DVec3::X, DVec3::X];
        assert!(matches!(
            ChordSpline3::try_new(&pts, CurveEnds::Open { start: None, end: None }),
            Err(SplineError::NotIncreasing { index: 2, .. })
        ));
    }
}
