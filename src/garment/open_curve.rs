//! Open garment curves cut by a plane (a strap over the shoulder, the crotch curve in the
//! vertical crotch plane), through the same sub-steps as a ring: the raw section between
//! two cut heights, convexified with its ends and apex kept, resampled as two arcs about the
//! apex, eased (bridging gaps of the body narrower than twice the ease), its ends pinned to the rings they meet (virtual control points: the
//! difference fades linearly to zero at the apex), then fitted and resampled.

use glam::{DVec2, DVec3};

use super::bridge::{Bridging, bridge_all};
use super::convexify::convexify_open;
use super::ease::{Ease, ease_ring};
use super::probe::BodyProbe;
use super::resample::resample_open_at;
use super::ring::{RingBuildError, RingStages};
use crate::geom::{ChordSpline3, CurveEnds, Plane, SectionLoop};

/// Which way the curve bulges from its ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Apex {
    /// The curve hangs below its ends (the crotch curve); the apex is its lowest point.
    Lowest,
    /// The curve rises over its ends (a strap); the apex is its highest point.
    Highest,
}

/// A finished open curve, ordered from its front end to its back end.
#[derive(Clone, Debug, PartialEq)]
pub struct OpenCurve {
    /// Name (`crotch`, `left_strap`).
    pub name: String,
    /// Its plane.
    pub plane: Plane,
    /// Sub-steps (`raw` holds the section part used).
    pub stages: RingStages,
    /// The fitted spline (natural ends).
    pub spline: ChordSpline3,
    /// Spline parameter of the apex.
    pub apex_param: f64,
    /// Apex position, m (world frame).
    pub apex: DVec3,
    /// The name of the apex as a control point (`crotch.point`, `left_strap.top`).
    pub apex_name: &'static str,
}

/// The part of a closed section loop beyond height `cut` around its apex, from the end with
/// the larger `z` (front) to the other, cut ends interpolated; `(points, apex index)`.
/// `None` if the loop does not cross `cut` on both sides of the apex.
pub fn section_part(section: &SectionLoop, cut: f64, apex: Apex) -> Option<(Vec<DVec3>, usize)> {
    let pts = &section.points;
    let n = pts.len();
    if n < 3 || !section.closed {
        return None;
    }
    let beyond = |p: DVec3| match apex {
        Apex::Lowest => p.y < cut,
        Apex::Highest => p.y > cut,
    };
    let key = |p: DVec3| match apex {
        Apex::Lowest => -p.y,
        Apex::Highest => p.y,
    };
    let top = (0..n).fold(0, |b, i| if key(pts[i]) > key(pts[b]) { i } else { b });
    if !beyond(pts[top]) {
        return None;
    }
    let walk = |step: usize| -> Option<Vec<DVec3>> {
        let mut out = Vec::new();
        let mut i = top;
        for _ in 0..n {
            let j = (i + step) % n;
            if !beyond(pts[j]) {
                let (a, b) = (pts[i], pts[j]);
                let t = (cut - a.y) / (b.y - a.y);
                out.push(a.lerp(b, t.clamp(0.0, 1.0)));
                return Some(out);
            }
            out.push(pts[j]);
            i = j;
        }
        None
    };
    let forward = walk(1)?;
    let backward = walk(n - 1)?;
    let mut part: Vec<DVec3> = backward.into_iter().rev().collect();
    let apex_index = part.len();
    part.push(pts[top]);
    part.extend(forward);
    if part[0].z < part[part.len() - 1].z {
        part.reverse();
        let apex_index = part.len() - 1 - apex_index;
        return Some((part, apex_index));
    }
    Some((part, apex_index))
}

/// Inputs of one open curve.
#[derive(Clone, Debug)]
pub struct OpenInput<'a> {
    /// Name.
    pub name: &'a str,
    /// The apex's name as a control point (`point`, `top`).
    pub apex_name: &'static str,
    /// Plane (the curve lies in it).
    pub plane: Plane,
    /// The section part, front end first, and its apex index.
    pub raw: (Vec<DVec3>, usize),
    /// Ease.
    pub ease: Ease,
    /// Where the ends must land (the ring anchors they meet), m.
    pub ends: [DVec3; 2],
    /// Points per half when resampling.
    pub per_half: usize,
    /// Control points per half (ends and apex excluded).
    pub control_per_half: usize,
    /// Fitted samples per half.
    pub fitted_per_half: usize,
    /// The body and how eased points bridge its gaps ([`super::bridge`]).
    pub bridge: Option<(&'a BodyProbe, Bridging)>,
}

impl OpenCurve {
    /// Runs every sub-step.
    pub fn build(input: &OpenInput<'_>) -> Result<Self, RingBuildError> {
        let name = input.name.to_string();
        let plane = input.plane;
        let (raw, apex) = &input.raw;
        let flat: Vec<DVec2> = raw.iter().map(|p| plane.project(*p)).collect();
        let (kept, apex_at) = convexify_open(&flat, *apex);
        let convex: Vec<DVec3> = kept.iter().map(|&i| raw[i]).collect();
        let resampled = resample_open_at(&convex, apex_at, input.per_half)
            .map_err(|e| RingBuildError::Resample(name.clone(), e))?;
        let mut eased =
            ease_ring(&resampled, &convex, &plane, input.ease).map_err(|e| RingBuildError::Ease(name.clone(), e))?;
        if let Some((probe, b)) = &input.bridge {
            // On the way each point was eased (from the deformation centre, in the plane).
            let dirs: Vec<DVec3> = eased.iter().zip(&resampled).map(|(e, r)| *e - *r).collect();
            bridge_all(probe, &mut eased, &dirs, b, 1);
        }
        // Pin the ends; the correction fades to nothing at the apex.
        let h = input.per_half;
        let last = eased.len() - 1;
        let (d0, d1) = (input.ends[0] - eased[0], input.ends[1] - eased[last]);
        let pinned: Vec<DVec3> = eased
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if i < h {
                    *p + d0 * ((h - i) as f64 / h as f64)
                } else if i > h {
                    *p + d1 * ((i - h) as f64 / h as f64)
                } else {
                    *p
                }
            })
            .collect();
        let c = input.control_per_half.max(1);
        let control: Vec<DVec3> = (0..=2 * (c + 1))
            .map(|k| {
                // Even positions along each half of the pinned samples.
                let (half, j) = if k <= c + 1 { (0, k) } else { (1, k - (c + 1)) };
                let x = (half * h) as f64 + j as f64 * h as f64 / (c + 1) as f64;
                let i = x.floor() as usize;
                if i >= last {
                    pinned[last]
                } else {
                    pinned[i].lerp(pinned[i + 1], x - i as f64)
                }
            })
            .collect();
        let spline = ChordSpline3::try_new(&control, CurveEnds::Open { start: None, end: None })
            .map_err(|e| RingBuildError::Fit(name.clone(), e))?;
        let apex_param = spline.knots()[c + 1];
        let apex = control[c + 1];
        let mut curve = Self {
            name,
            apex_name: input.apex_name,
            plane,
            stages: RingStages {
                raw: vec![raw.clone()],
                convex,
                resampled,
                eased: pinned,
                control,
                fitted: Vec::new(),
            },
            spline,
            apex_param,
            apex,
        };
        let mut fitted = curve.half(true, input.fitted_per_half);
        fitted.pop();
        fitted.extend(curve.half(false, input.fitted_per_half));
        curve.stages.fitted = fitted;
        Ok(curve)
    }

    /// `n + 1` samples (m) of the front half (front end to apex) or the back half (apex to back
    /// end).
    pub fn half(&self, front: bool, n: usize) -> Vec<DVec3> {
        let n = n.max(1);
        let (a, b) = if front {
            (0.0, self.apex_param)
        } else {
            (self.apex_param, self.spline.length())
        };
        let control = &self.stages.control;
        let mut out: Vec<DVec3> = (0..=n)
            .map(|s| self.spline.sample(a + (b - a) * s as f64 / n as f64))
            .collect();
        let (first, last) = if front {
            (control[0], self.apex)
        } else {
            (self.apex, control[control.len() - 1])
        };
        out[0] = first;
        out[n] = last;
        out
    }

    /// The spline parameter on the front (or back) half where the curve is halfway up from
    /// that end to the apex (the height midway between them), by bisection on the half.
    pub fn midway(&self, front: bool) -> f64 {
        let (end, a, b) = if front {
            (self.front_end(), 0.0, self.apex_param)
        } else {
            (self.back_end(), self.apex_param, self.spline.length())
        };
        let y = 0.5 * (end.y + self.apex.y);
        // The front half rises from its end to the apex, the back half falls to its end.
        let (mut lo, mut hi) = (a, b);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if (self.spline.sample(mid).y < y) == front {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// `n + 1` samples (m) from parameter `a` to `b` (`b` may be below `a`), the ends
    /// exact where they are the curve's ends or its apex.
    pub fn between(&self, a: f64, b: f64, n: usize) -> Vec<DVec3> {
        let n = n.max(1);
        let exact = |l: f64| {
            if l == 0.0 {
                self.front_end()
            } else if l == self.apex_param {
                self.apex
            } else if l == self.spline.length() {
                self.back_end()
            } else {
                self.spline.sample(l)
            }
        };
        let mut out: Vec<DVec3> = (0..=n)
            .map(|s| self.spline.sample(a + (b - a) * s as f64 / n as f64))
            .collect();
        out[0] = exact(a);
        out[n] = exact(b);
        out
    }

    /// The unit tangent at the front (or back) end, pointing into the curve.
    pub fn end_tangent(&self, front: bool) -> DVec3 {
        if front {
            self.spline.derivative(0.0).normalize_or_zero()
        } else {
            -self.spline.derivative(self.spline.length()).normalize_or_zero()
        }
    }

    /// Refits the spline through new control points (the apex stays the middle one).
    pub fn refit(&mut self, control: Vec<DVec3>) -> Result<(), RingBuildError> {
        let spline = ChordSpline3::try_new(&control, CurveEnds::Open { start: None, end: None })
            .map_err(|e| RingBuildError::Fit(self.name.clone(), e))?;
        let c = control.len() / 2;
        let per_half = (self.stages.fitted.len().max(3) - 1) / 2;
        self.apex_param = spline.knots()[c];
        self.apex = control[c];
        self.spline = spline;
        self.stages.control = control;
        let mut fitted = self.half(true, per_half);
        fitted.pop();
        fitted.extend(self.half(false, per_half));
        self.stages.fitted = fitted;
        Ok(())
    }

    /// The front end, m.
    pub fn front_end(&self) -> DVec3 {
        self.stages.control[0]
    }

    /// The back end, m.
    pub fn back_end(&self) -> DVec3 {
        self.stages.control[self.stages.control.len() - 1]
    }
}
