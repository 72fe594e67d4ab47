//! Fixed-direction hulls (k-DOPs) with the paper's 14 directions: the three axes and the
//! four diagonals `(1,1,1)`, `(1,-1,1)`, `(1,1,-1)`, `(1,-1,-1)`, each with both signs, so
//! a hull is an interval on each of 7 unit axes. By the convex hull property a NURBS
//! surface lies in the hull of its control points, so the hull of the control points
//! bounds the surface. Two hulls overlap iff their intervals overlap on all 7 axes; the
//! largest separation of the intervals is a lower bound on the distance between anything
//! inside them (the axes are unit vectors).

use glam::DVec3;

const D: f64 = 0.577_350_269_189_625_8; // 1 / sqrt(3)

/// The 7 unit axes.
pub const AXES: [DVec3; 7] = [
    DVec3::X,
    DVec3::Y,
    DVec3::Z,
    DVec3::new(D, D, D),
    DVec3::new(D, -D, D),
    DVec3::new(D, D, -D),
    DVec3::new(D, -D, -D),
];

/// A 14-direction hull: an interval `[min, max]` of projections on each of [`AXES`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kdop {
    /// Least projection per axis.
    pub min: [f64; 7],
    /// Greatest projection per axis.
    pub max: [f64; 7],
}

impl Kdop {
    /// The empty hull (contains nothing; the identity of [`Kdop::merge`]).
    pub const EMPTY: Self = Self {
        min: [f64::INFINITY; 7],
        max: [f64::NEG_INFINITY; 7],
    };

    /// The hull of `points`.
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Self {
        let mut hull = Self::EMPTY;
        for p in points {
            hull.add(p);
        }
        hull
    }

    /// Grows the hull to contain `p`.
    pub fn add(&mut self, p: DVec3) {
        for (k, axis) in AXES.iter().enumerate() {
            let d = axis.dot(p);
            self.min[k] = self.min[k].min(d);
            self.max[k] = self.max[k].max(d);
        }
    }

    /// The hull of both.
    pub fn merge(&self, other: &Self) -> Self {
        let mut out = *self;
        for k in 0..7 {
            out.min[k] = out.min[k].min(other.min[k]);
            out.max[k] = out.max[k].max(other.max[k]);
        }
        out
    }

    /// The largest separation of the two hulls' intervals over the axes: positive when
    /// they are apart on some axis (a lower bound on the distance between their contents),
    /// zero or negative when they overlap on every axis.
    pub fn gap(&self, other: &Self) -> f64 {
        let mut gap = f64::NEG_INFINITY;
        for k in 0..7 {
            gap = gap.max(self.min[k] - other.max[k]).max(other.min[k] - self.max[k]);
        }
        gap
    }

    /// Whether the intervals overlap on all 7 axes.
    pub fn overlaps(&self, other: &Self) -> bool {
        self.gap(other) <= 0.0
    }

    /// Whether `p` projects into every interval, with slack `tolerance`.
    pub fn contains(&self, p: DVec3, tolerance: f64) -> bool {
        AXES.iter()
            .enumerate()
            .all(|(k, axis)| (self.min[k] - tolerance..=self.max[k] + tolerance).contains(&axis.dot(p)))
    }

    /// The largest interval width (the hull's size).
    pub fn extent(&self) -> f64 {
        (0..7).map(|k| self.max[k] - self.min[k]).fold(0.0, f64::max)
    }

    /// The edges of the hull as a polyhedron (the intersection of its 14 half-spaces), for
    /// drawing: each corner is where three face planes meet inside every other half-space,
    /// and two corners are joined when they share two planes with a face of the hull.
    pub fn edges(&self) -> Vec<[DVec3; 2]> {
        // Planes as (normal, offset): n . x <= offset.
        let planes: Vec<(DVec3, f64)> = AXES
            .iter()
            .enumerate()
            .flat_map(|(k, &a)| [(a, self.max[k]), (-a, -self.min[k])])
            .collect();
        let scale = self.extent().max(f64::MIN_POSITIVE);
        let tolerance = 1e-9 * scale;
        // Corners with the set of planes they lie on.
        let mut corners: Vec<(DVec3, u16)> = Vec::new();
        for i in 0..planes.len() {
            for j in i + 1..planes.len() {
                for k in j + 1..planes.len() {
                    let (a, b, c) = (planes[i], planes[j], planes[k]);
                    let det = a.0.dot(b.0.cross(c.0));
                    if det.abs() < 1e-9 {
                        continue;
                    }
                    let x = (b.0.cross(c.0) * a.1 + c.0.cross(a.0) * b.1 + a.0.cross(b.0) * c.1) / det;
                    if planes.iter().any(|&(n, d)| n.dot(x) > d + tolerance) {
                        continue;
                    }
                    let on = planes
                        .iter()
                        .enumerate()
                        .filter(|(_, (n, d))| (n.dot(x) - d).abs() <= tolerance)
                        .fold(0u16, |m, (q, _)| m | (1 << q));
                    if !corners.iter().any(|&(y, _)| (y - x).length() <= tolerance) {
                        corners.push((x, on));
                    }
                }
            }
        }
        let mut edges = Vec::new();
        for (i, &(p, a)) in corners.iter().enumerate() {
            for &(q, b) in &corners[i + 1..] {
                let shared = a & b;
                // Two shared planes that are not parallel make an edge line; a segment
                // of it with no third corner between is an edge.
                if shared.count_ones() >= 2
                    && !corners.iter().any(|&(r, c)| {
                        c & shared == shared && (r - p).length() > tolerance && (r - q).length() > tolerance && {
                            let t = (r - p).dot(q - p) / (q - p).length_squared();
                            t > 0.0 && t < 1.0 && (p + (q - p) * t - r).length() <= tolerance
                        }
                    })
                {
                    edges.push([p, q]);
                }
            }
        }
        edges
    }
}
