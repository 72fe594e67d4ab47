//! The constraint kinds (\[frame\] section 3) and their residuals, in metres or radians.
//!
//! Self constraints of a curve: left-right symmetry, coplanarity of its control points,
//! control points inside a polygon, a ring outside the body section plus ease, no
//! self-crossing. Between curves: a coincident point (a ring and a contour meet, a strap
//! ends on the chest ring) and tangency at such a point. A constraint is met when its
//! residual is at most the solver's tolerance.

use glam::{DVec2, DVec3};

use super::crossing::self_crossings;
use super::curves::{self, CurveKind, CurveNode};
use crate::garment::Framework;
use crate::geom::polygon;

/// What a constraint asks.
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    /// Left-right symmetry about the body's mid-plane `x = mid_x`: control point `b` of
    /// curve `j` mirrors point `a` of curve `i` (the same curve for a self constraint), up
    /// to the offset `rest` it had when built. The body is not exactly symmetric, so the
    /// built garment keeps the body's asymmetry and edits are mirrored; with `rest = 0` it is
    /// plain mirror symmetry. The image is taken in `j`'s plane (projected onto it), so
    /// symmetry and coplanarity agree. Residual: the largest `|p_b - P_j(M(p_a) + rest)|`, m.
    Symmetry {
        /// The mirror plane's `x`.
        mid_x: f64,
        /// Pairs `(a on i, b on j)`.
        pairs: Vec<(usize, usize)>,
        /// Offsets at rest, one per pair.
        rest: Vec<DVec3>,
    },
    /// The control points lie in the curve's plane. Residual: the largest distance off it, m.
    Coplanar,
    /// The control points lie inside a polygon given in the curve plane's frame (the design
    /// region). Residual: the largest distance outside it, m.
    InsidePolygon {
        /// Polygon vertices, counter-clockwise, in `Plane::project` coordinates.
        polygon: Vec<DVec2>,
    },
    /// A ring stands outside its body section by the ease: each control point at least
    /// `need[k]` off the section's tape line, in the ring's plane. Residual: the largest
    /// shortfall, m.
    OutsideBody {
        /// The section (the convexified body ring), in the ring's plane.
        section: Vec<DVec3>,
        /// Least gap per control point, m.
        need: Vec<f64>,
    },
    /// The fitted curve does not cross itself. Residual: the length of the shorter loop
    /// the worst crossing cuts off, m (0 without crossings).
    NoSelfCrossing,
    /// Control point `a` of curve `i` and point `b` of curve `j` coincide. Residual: their
    /// distance, m.
    Coincident {
        /// Point of `i`.
        a: usize,
        /// Point of `j`.
        b: usize,
    },
    /// At the point where they meet, contour `j`'s highest end continues open curve `i`
    /// from its front (or back) end. Residual: the angle between the tangents, rad.
    Tangent {
        /// Which end of the open curve.
        front: bool,
    },
}

impl Kind {
    /// Short name.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Symmetry { .. } => "symmetry",
            Self::Coplanar => "coplanar",
            Self::InsidePolygon { .. } => "inside_polygon",
            Self::OutsideBody { .. } => "outside_body",
            Self::NoSelfCrossing => "no_self_crossing",
            Self::Coincident { .. } => "coincident",
            Self::Tangent { .. } => "tangent",
        }
    }

    /// The unit of the residual.
    pub fn unit(&self) -> &'static str {
        if matches!(self, Self::Tangent { .. }) {
            "rad"
        } else {
            "m"
        }
    }

    /// The priority (hierarchy): lower is stronger and is solved first. Coplanarity and
    /// self-crossing are hard (0), then the design region (1), where curves meet (2),
    /// symmetry (3), tangency (4) and the ease against the section (5).
    pub fn priority(&self) -> u8 {
        match self {
            Self::Coplanar | Self::NoSelfCrossing => 0,
            Self::InsidePolygon { .. } => 1,
            Self::Coincident { .. } => 2,
            Self::Symmetry { .. } => 3,
            Self::Tangent { .. } => 4,
            Self::OutsideBody { .. } => 5,
        }
    }
}

/// One constraint between curves `i` and `j` (`i == j` for a self constraint).
#[derive(Clone, Debug, PartialEq)]
pub struct Constraint {
    /// What it asks.
    pub kind: Kind,
    /// First curve (the driver of a directed constraint).
    pub i: usize,
    /// Second curve.
    pub j: usize,
    /// Directed: only `i` drives `j`; otherwise either drives the other.
    pub directed: bool,
}

/// The mirror image of `p` about the plane `x = mid_x`: `(2 mid_x - x, y, z)`, m.
pub fn mirror(p: DVec3, mid_x: f64) -> DVec3 {
    DVec3::new(2.0 * mid_x - p.x, p.y, p.z)
}

/// The nearest point of a closed polygon's boundary to `q`, and its distance.
pub fn nearest_on_polygon(q: DVec2, polygon: &[DVec2]) -> (DVec2, f64) {
    let n = polygon.len();
    let mut best = (q, f64::INFINITY);
    for k in 0..n {
        let (a, b) = (polygon[k], polygon[(k + 1) % n]);
        let ab = b - a;
        let t = if ab.length_squared() > 0.0 {
            ((q - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let p = a + ab * t;
        if q.distance(p) < best.1 {
            best = (p, q.distance(p));
        }
    }
    best
}

/// Signed distance (m) of `q` from a closed polygon's boundary: negative inside.
pub fn signed_gap(q: DVec2, polygon: &[DVec2]) -> f64 {
    let d = nearest_on_polygon(q, polygon).1;
    if polygon::contains(polygon, q) { -d } else { d }
}

/// Samples per control span for the self-crossing check and the curve-layer collision.
pub const SAMPLES_PER_SPAN: usize = 6;

impl Constraint {
    /// `kind curve[-other] by residual unit`, for messages.
    pub fn describe(&self, nodes: &[CurveNode], residual: f64) -> String {
        let other = if self.is_self() {
            String::new()
        } else {
            format!("-{}", nodes[self.j].name)
        };
        format!(
            "{} {}{other} by {residual:.3e} {}",
            self.kind.name(),
            nodes[self.i].name,
            self.kind.unit()
        )
    }

    /// Whether the constraint ties a curve to itself.
    pub fn is_self(&self) -> bool {
        self.i == self.j
    }

    /// The other curve of the constraint, seen from `c`.
    pub fn other(&self, c: usize) -> usize {
        if self.i == c { self.j } else { self.i }
    }

    /// Whether curve `from` may drive curve `to` through this constraint.
    pub fn drives(&self, from: usize, to: usize) -> bool {
        (self.i == from && self.j == to) || (!self.directed && self.j == from && self.i == to)
    }

    /// The residual on `fw` (m or rad, see [`Kind`]).
    pub fn residual(&self, fw: &Framework, nodes: &[CurveNode]) -> f64 {
        let (ci, cj) = (&nodes[self.i], &nodes[self.j]);
        let (pi, pj) = (curves::points(fw, ci), curves::points(fw, cj));
        match &self.kind {
            Kind::Symmetry { mid_x, pairs, rest } => {
                let plane = curves::plane(fw, cj);
                pairs
                    .iter()
                    .zip(rest)
                    .map(|(&(a, b), r)| {
                        let want = mirror(pi[a], *mid_x) + *r;
                        (pj[b] - plane.map_or(want, |pl| pl.snap(want))).length()
                    })
                    .fold(0.0, f64::max)
            }
            Kind::Coplanar => curves::plane(fw, ci).map_or(0.0, |plane| {
                pi.iter().map(|p| plane.signed_distance(*p).abs()).fold(0.0, f64::max)
            }),
            Kind::InsidePolygon { polygon } => curves::plane(fw, ci).map_or(0.0, |plane| {
                pi.iter()
                    .map(|p| signed_gap(plane.project(*p), polygon).max(0.0))
                    .fold(0.0, f64::max)
            }),
            Kind::OutsideBody { section, need } => curves::plane(fw, ci).map_or(0.0, |plane| {
                let flat: Vec<DVec2> = section.iter().map(|p| plane.project(*p)).collect();
                pi.iter()
                    .zip(need)
                    .map(|(p, n)| (n - signed_gap(plane.project(*p), &flat)).max(0.0))
                    .fold(0.0, f64::max)
            }),
            Kind::NoSelfCrossing => crossing_residual(fw, ci),
            Kind::Coincident { a, b } => pi[*a].distance(pj[*b]),
            Kind::Tangent { front } => {
                if ci.kind != CurveKind::Open || cj.kind != CurveKind::Contour {
                    return 0.0;
                }
                let t_open = fw.open_curves[ci.index].end_tangent(*front);
                let t_contour = fw.contours[cj.index].end_tangent(1);
                t_open.angle_between(t_contour)
            }
        }
    }

    /// Where to draw the constraint: a point on each curve (the constrained points, or the
    /// curves' centres for a whole-curve constraint).
    pub fn anchor_points(&self, fw: &Framework, nodes: &[CurveNode]) -> (DVec3, DVec3) {
        let (pi, pj) = (curves::points(fw, &nodes[self.i]), curves::points(fw, &nodes[self.j]));
        let centre = |p: &[DVec3]| p.iter().sum::<DVec3>() / p.len().max(1) as f64;
        match &self.kind {
            Kind::Coincident { a, b } => (pi[*a], pj[*b]),
            Kind::Tangent { front } => {
                let a = if *front { pi[0] } else { pi[pi.len() - 1] };
                (a, pj[pj.len() - 1])
            }
            Kind::Symmetry { pairs, .. } if !pairs.is_empty() && !self.is_self() => (pi[pairs[0].0], pj[pairs[0].1]),
            _ => (centre(pi), centre(pj)),
        }
    }
}

/// The worst self-crossing's loop length of a planar curve's fitted samples, m.
pub fn crossing_residual(fw: &Framework, c: &CurveNode) -> f64 {
    let Some(plane) = curves::plane(fw, c) else {
        return 0.0;
    };
    let flat: Vec<DVec2> = curves::samples(fw, c, SAMPLES_PER_SPAN)
        .iter()
        .map(|(_, p)| plane.project(*p))
        .collect();
    self_crossings(&flat, curves::closed(c))
        .iter()
        .map(|x| x.loop_length)
        .fold(0.0, f64::max)
}
