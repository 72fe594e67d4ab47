//! The body's horizontal sections at a fixed spacing, cut once per body (\[collide\] 4.1:
//! "根据高度值进行切环", rings cut by height). Each slice keeps every outer loop (legs,
//! torso and arms: the line-line test must see them all) oriented counter-clockwise in
//! `(x, z)`, and the ring centres of the torso or leg loops for the response of legs,
//! crotch and hip (\[collide\] 5.2, figure 12):
//!
//! 1. the global centre is the midpoint of the ring's left and right extremes;
//! 2. it splits the ring into two halves, each with a local centre (the mean of its points);
//! 3. if a local centre lies farther than `W / 2` from the global one (`W` the ring's width)
//!    all centres are kept; otherwise a concave ring keeps its local centres and a convex
//!    ring its global centre.

use glam::{DVec2, DVec3};

use super::profile::{loop_at, outer_loops};
use super::{Body, LandmarkKind};
use crate::geom::polygon;

/// Slice settings.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SliceOptions {
    /// Spacing between slices, as a fraction of the body's height. Default value: 1/400
    /// (4 mm on a 1.6 m body).
    pub spacing_fraction: f64,
    /// A ring whose area is below this fraction of its convex hull's is concave.
    /// Default value: 0.95.
    pub concave_below: f64,
}

impl Default for SliceOptions {
    fn default() -> Self {
        Self {
            spacing_fraction: 1.0 / 400.0,
            concave_below: 0.95,
        }
    }
}

/// Which ring centres a slice keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CentreChoice {
    /// A local centre lies farther than `W / 2`: global and local centres.
    All,
    /// A concave ring: the two local centres.
    Local,
    /// A convex ring: the global centre.
    Global,
}

/// The centres of one ring.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Centres {
    /// Midpoint of the left and right extremes, `(x, z)`, m.
    pub global: DVec2,
    /// Mean of the points left (`x` below the global centre) and right of it.
    pub local: [DVec2; 2],
    /// Width `W` (right extreme minus left extreme in `x`), m.
    pub width: f64,
    /// Area over convex hull area (of all the ring's loops together), a ratio in 0..1.
    pub convexity: f64,
    /// What the rule keeps.
    pub choice: CentreChoice,
}

impl Centres {
    /// The local centre of the half `p` lies in.
    pub fn local_of(&self, p: DVec2) -> DVec2 {
        if p.x < self.global.x {
            self.local[0]
        } else {
            self.local[1]
        }
    }

    /// The centre whose ray a vertex at `p` is pushed along: the kept centre nearest to it
    /// (`All`), its half's local centre (`Local`), or the global centre.
    pub fn for_point(&self, p: DVec2) -> (DVec2, bool) {
        match self.choice {
            CentreChoice::Global => (self.global, true),
            CentreChoice::Local => (self.local_of(p), false),
            CentreChoice::All => {
                let l = self.local_of(p);
                if p.distance_squared(self.global) < p.distance_squared(l) {
                    (self.global, true)
                } else {
                    (l, false)
                }
            }
        }
    }
}

/// Edges per [`Loop2::chunks`] box.
pub const CHUNK: usize = 8;

/// One closed loop of a slice, counter-clockwise in `(x, z)`, with a bounding box over
/// every run of [`CHUNK`] consecutive edges, so that a query can pass by the runs that
/// lie far from it (the loop is a polyline: consecutive edges lie close together).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Loop2 {
    points: Vec<DVec2>,
    chunks: Vec<[DVec2; 2]>,
    bounds: [DVec2; 2],
}

impl Loop2 {
    /// The loop through `points` (not repeated at the end).
    ///
    /// Each box is grown by a billionth of the loop's extent plus a picometre, far above
    /// the rounding of any distance or side computed in it, so that a box test never
    /// passes by an edge whose own computed test would have counted.
    pub fn new(points: Vec<DVec2>) -> Self {
        let n = points.len();
        let (lo, hi) = points
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let pad = DVec2::splat(1e-12 + 1e-9 * (hi - lo).max_element().max(0.0));
        let bounds = [lo - pad, hi + pad];
        let chunks = (0..n)
            .step_by(CHUNK)
            .map(|first| {
                let (lo, hi) = (first..(first + CHUNK).min(n))
                    .flat_map(|i| [points[i], points[(i + 1) % n]])
                    .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                        (lo.min(p), hi.max(p))
                    });
                [lo - pad, hi + pad]
            })
            .collect();
        Self { points, chunks, bounds }
    }

    /// Box `[min, max]` of the whole loop, grown as told in [`Self::new`].
    pub fn bounds(&self) -> [DVec2; 2] {
        self.bounds
    }

    /// Points `(x, z)`, m, not repeated at the end.
    pub fn points(&self) -> &[DVec2] {
        &self.points
    }

    /// Box `[min, max]` of edges `k * CHUNK ..` up to `(k + 1) * CHUNK` (the last run may be
    /// shorter), grown as told in [`Self::new`].
    pub fn chunks(&self) -> &[[DVec2; 2]] {
        &self.chunks
    }

    /// Outward unit normal of edge `i` (from point `i` to `i + 1`).
    pub fn edge_normal(&self, i: usize) -> DVec2 {
        let n = self.points.len();
        let e = self.points[(i + 1) % n] - self.points[i];
        DVec2::new(e.y, -e.x).normalize_or_zero()
    }
}

/// The body's section at one height.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Slice {
    /// Height, m.
    pub y: f64,
    /// Every outer loop (arms included).
    pub loops: Vec<Loop2>,
    /// Centres of the torso (or the two legs) at this height; `None` if the section has
    /// no such loop.
    pub centres: Option<Centres>,
}

/// Slices from the floor to the top of the highest partition that needs them.
#[derive(Clone, Debug, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct SliceStack {
    /// Height of the first slice, m.
    pub y0: f64,
    /// Spacing between slices, m.
    pub dy: f64,
    /// Slices, bottom up.
    pub slices: Vec<Slice>,
}

fn centres(points: &[DVec2], area: f64, options: &SliceOptions) -> Option<Centres> {
    let left = points.iter().copied().min_by(|a, b| a.x.total_cmp(&b.x))?;
    let right = points.iter().copied().max_by(|a, b| a.x.total_cmp(&b.x))?;
    let global = (left + right) * 0.5;
    let width = right.x - left.x;
    let mean = |f: &dyn Fn(&DVec2) -> bool| {
        let (sum, n) = points
            .iter()
            .filter(|p| f(p))
            .fold((DVec2::ZERO, 0usize), |(s, n), p| (s + *p, n + 1));
        if n == 0 { global } else { sum / n as f64 }
    };
    let local = [mean(&|p| p.x < global.x), mean(&|p| p.x >= global.x)];
    let hull = polygon::signed_area(&polygon::convex_hull(points)).abs();
    let convexity = if hull > 0.0 { area / hull } else { 1.0 };
    let far = local.iter().any(|l| l.distance(global) > 0.5 * width);
    let choice = if far {
        CentreChoice::All
    } else if convexity < options.concave_below {
        CentreChoice::Local
    } else {
        CentreChoice::Global
    };
    Some(Centres {
        global,
        local,
        width,
        convexity,
        choice,
    })
}

impl SliceStack {
    /// Cuts the slices of `body` up to the top of the highest partition whose detection is
    /// line-line or whose response reads ring centres (plus one slice).
    pub fn new(body: &Body, options: &SliceOptions) -> Self {
        use super::{DetectionMethod, ResponseRule};
        let mesh = &body.mesh.mesh;
        let Some((lo, hi)) = mesh.bounds() else {
            return Self::default();
        };
        let height = hi.y - lo.y;
        let top = body
            .partitions
            .iter()
            .filter(|p| {
                p.method == DetectionMethod::LineLine
                    || matches!(p.response, ResponseRule::RingCentre | ResponseRule::BodyNormal)
            })
            .map(|p| p.upper_y)
            .fold(f64::NEG_INFINITY, f64::max);
        if !top.is_finite() || height <= 0.0 {
            return Self::default();
        }
        let dy = options.spacing_fraction * height;
        let y0 = lo.y + 0.5 * dy;
        let count = (((top.min(hi.y) - y0) / dy).ceil() as usize + 1).max(1);
        let crotch = body.landmarks.height(LandmarkKind::Crotch);
        let slices = (0..count)
            .map(|i| {
                let y = y0 + i as f64 * dy;
                let loops = outer_loops(&body.mesh, y, height);
                let picked: Vec<usize> = if y < crotch {
                    match body.landmarks.legs_at(y) {
                        Some((l, r)) => {
                            let mut v: Vec<usize> = [l, r].iter().filter_map(|a| loop_at(&loops, *a)).collect();
                            v.dedup();
                            v
                        }
                        None => Vec::new(),
                    }
                } else {
                    body.landmarks
                        .torso_at(y)
                        .and_then(|a| loop_at(&loops, a))
                        .into_iter()
                        .collect()
                };
                let points: Vec<DVec2> = picked.iter().flat_map(|&k| loops[k].flat.iter().copied()).collect();
                let area: f64 = picked.iter().map(|&k| loops[k].area).sum();
                let centres = centres(&points, area, options);
                let loops = loops
                    .into_iter()
                    .map(|l| {
                        let mut points = l.flat;
                        if polygon::signed_area(&points) < 0.0 {
                            points.reverse();
                        }
                        Loop2::new(points)
                    })
                    .collect();
                Slice { y, loops, centres }
            })
            .collect();
        Self { y0, dy, slices }
    }

    /// Number of slices.
    pub fn len(&self) -> usize {
        self.slices.len()
    }

    /// No slices.
    pub fn is_empty(&self) -> bool {
        self.slices.is_empty()
    }

    /// The slice nearest to height `y`, if `y` lies within half a spacing of the stack.
    pub fn at(&self, y: f64) -> Option<&Slice> {
        self.nearest(y).map(|(_, s)| s)
    }

    /// [`Self::at`], with the slice's index.
    pub fn nearest(&self, y: f64) -> Option<(usize, &Slice)> {
        if self.slices.is_empty() || self.dy <= 0.0 {
            return None;
        }
        let k = ((y - self.y0) / self.dy).round();
        if k < -0.5 || k > self.slices.len() as f64 - 0.5 {
            return None;
        }
        let k = k as usize;
        self.slices.get(k).map(|s| (k, s))
    }
}

/// `(x, z)` of a point.
pub fn flat(p: DVec3) -> DVec2 {
    DVec2::new(p.x, p.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(c: DVec2, r: f64, n: usize) -> Vec<DVec2> {
        (0..n)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / n as f64;
                c + DVec2::new(t.cos(), t.sin()) * r
            })
            .collect()
    }

    fn area(points: &[DVec2]) -> f64 {
        polygon::signed_area(points).abs()
    }

    #[test]
    fn a_convex_ring_keeps_its_global_centre() {
        let ring = circle(DVec2::new(0.1, -0.2), 0.15, 64);
        let c = centres(&ring, area(&ring), &SliceOptions::default()).expect("centres");
        assert_eq!(c.choice, CentreChoice::Global);
        assert!(c.global.distance(DVec2::new(0.1, -0.2)) < 1e-12);
        assert!((c.width - 0.3).abs() < 1e-12);
        // The half rings' means lie at 2r/pi... of a semicircle's points: inside W/2.
        assert!(c.local[0].x < 0.1 && c.local[1].x > 0.1);
    }

    #[test]
    fn two_legs_are_a_concave_ring_with_local_centres() {
        let (l, r) = (
            circle(DVec2::new(-0.1, 0.0), 0.07, 48),
            circle(DVec2::new(0.1, 0.0), 0.07, 48),
        );
        let points: Vec<DVec2> = l.iter().chain(&r).copied().collect();
        let c = centres(&points, area(&l) + area(&r), &SliceOptions::default()).expect("centres");
        assert_eq!(c.choice, CentreChoice::Local);
        assert!(c.local[0].distance(DVec2::new(-0.1, 0.0)) < 1e-12);
        assert!(c.local[1].distance(DVec2::new(0.1, 0.0)) < 1e-12);
        let (centre, global) = c.for_point(DVec2::new(0.15, 0.05));
        assert!(!global && centre.distance(DVec2::new(0.1, 0.0)) < 1e-12);
    }

    #[test]
    fn a_local_centre_beyond_half_the_width_keeps_all_centres() {
        // A narrow ring (W = 0.2 across x) with a long lobe towards +z on its right half:
        // that half's mean lies about 0.9 from the global centre, beyond W / 2.
        let mut points = vec![DVec2::new(-0.1, 0.0), DVec2::new(0.1, 0.0)];
        points.extend((0..100).map(|k| DVec2::new(0.05, 0.8 + 0.002 * k as f64)));
        let c = centres(&points, 0.01, &SliceOptions::default()).expect("centres");
        assert_eq!(c.choice, CentreChoice::All);
        let (centre, global) = c.for_point(DVec2::new(0.02, 0.0));
        assert!(global && centre == c.global);
    }
}
