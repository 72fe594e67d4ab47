//! Distances between subdivided surfaces. The paper's test: at level `L`, the least
//! distance between the control points of leaf pairs whose hulls come within the threshold
//! (collision when it is below `T`). Beyond the paper: the true least distance between the
//! surfaces, found by branch and bound over leaf pairs (the hulls' gap is a lower bound) with
//! each candidate pair refined by damped Newton on the closest-point conditions inside its
//! parameter boxes; and the two measures of how far a level's control points stand from
//! their surface, which bound the error of the control-point distance.

use glam::DVec3;
use nalgebra::{Matrix4, Vector4};

use super::surface::{Direction, NurbsSurface};
use super::tree::{PairVisitor, Patch, PatchTree, descend};
use crate::convergence::{Stop, record};

/// The Greville abscissae of the control points of `s` in `dir`.
pub fn greville(s: &NurbsSurface, dir: Direction) -> Vec<f64> {
    let d = dir.index();
    let p = s.degree()[d];
    let knots = &s.knots()[d];
    (0..s.count()[d])
        .map(|i| knots[i + 1..=i + p].iter().sum::<f64>() / p as f64)
        .collect()
}

/// The nearest pair of control points of two patches: distance and indices.
fn nearest_points(a: &Patch, b: &Patch) -> (f64, usize, usize) {
    let mut best = (f64::INFINITY, 0, 0);
    for (i, p) in a.points.iter().enumerate() {
        for (j, q) in b.points.iter().enumerate() {
            let d = p.distance_squared(*q);
            if d < best.0 {
                best = (d, i, j);
            }
        }
    }
    (best.0.sqrt(), best.1, best.2)
}

/// The least control-point distance between two subdivided surfaces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlDistance {
    /// Least distance between a control point of `a`'s leaves and one of `b`'s, m.
    pub distance: f64,
    /// The leaves it was found in.
    pub patches: [u32; 2],
    /// The two control points.
    pub points: [DVec3; 2],
    /// Hull pairs tested.
    pub hull_tests: u64,
    /// Leaf pairs whose control points were compared.
    pub leaf_pairs: u64,
}

struct NearestControl<'a> {
    a: &'a PatchTree,
    b: &'a PatchTree,
    best: ControlDistance,
}

impl PairVisitor for NearestControl<'_> {
    fn bound(&self) -> f64 {
        self.best.distance
    }

    fn leaves(&mut self, i: u32, j: u32, _gap: f64) {
        let (pa, pb) = (&self.a.patches[i as usize], &self.b.patches[j as usize]);
        self.best.leaf_pairs += 1;
        let (d, k, l) = nearest_points(pa, pb);
        if d < self.best.distance {
            self.best.distance = d;
            self.best.patches = [i, j];
            self.best.points = [pa.points[k], pb.points[l]];
        }
    }

    fn done(&self) -> bool {
        self.best.distance == 0.0
    }
}

/// The least distance between the control points of `a`'s and `b`'s leaves, by branch and
/// bound: a pair of hulls farther apart than the best distance so far is discarded.
pub fn nearest_control_points(a: &PatchTree, b: &PatchTree) -> ControlDistance {
    let mut v = NearestControl {
        a,
        b,
        best: ControlDistance {
            distance: f64::INFINITY,
            patches: [0, 0],
            points: [DVec3::ZERO; 2],
            hull_tests: 0,
            leaf_pairs: 0,
        },
    };
    v.best.hull_tests = descend(&a.tree, &b.tree, &mut v);
    v.best
}

/// A pair of leaves whose hulls come within a threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LeafPair {
    /// The leaves.
    pub patches: [u32; 2],
    /// Their hulls' gap (negative: overlapping), m.
    pub gap: f64,
    /// Least distance between their control points, m.
    pub control_distance: f64,
}

struct Within<'a> {
    a: &'a PatchTree,
    b: &'a PatchTree,
    threshold: f64,
    pairs: Vec<LeafPair>,
}

impl PairVisitor for Within<'_> {
    fn bound(&self) -> f64 {
        self.threshold
    }

    fn leaves(&mut self, i: u32, j: u32, gap: f64) {
        let (d, _, _) = nearest_points(&self.a.patches[i as usize], &self.b.patches[j as usize]);
        self.pairs.push(LeafPair {
            patches: [i, j],
            gap,
            control_distance: d,
        });
    }
}

/// Every pair of leaves whose hulls come within `threshold` of each other (the paper's
/// overlapping leaf pairs, with the hulls grown by the threshold so that surfaces nearer
/// than it cannot slip between two hulls), in leaf order; and the hull pairs tested.
pub fn pairs_within(a: &PatchTree, b: &PatchTree, threshold: f64) -> (Vec<LeafPair>, u64) {
    let mut v = Within {
        a,
        b,
        threshold,
        pairs: Vec::new(),
    };
    let tests = descend(&a.tree, &b.tree, &mut v);
    v.pairs.sort_by_key(|p| p.patches);
    (v.pairs, tests)
}

/// A local least distance between two patches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refined {
    /// Distance, m.
    pub distance: f64,
    /// `(u, v)` on the first surface, then `(u, v)` on the second.
    pub params: [f64; 4],
    /// The two surface points.
    pub points: [DVec3; 2],
    /// Newton iterations.
    pub iterations: usize,
}

/// Newton iterations at most per refinement.
pub const NEWTON_STEPS: usize = 60;

/// The least distance between the patches `a` and `b` near `start`: damped Newton
/// (Levenberg-Marquardt on the full Hessian of half the squared distance) on the
/// closest-point conditions, each step projected into the patches' parameter boxes, with
/// the coordinates held at a bound that the gradient pushes out of it. Reports its stop as
/// `nurbs.distance.newton`.
pub fn refine(a: &Patch, b: &Patch, start: [f64; 4]) -> Refined {
    let lo = [a.range[0].0, a.range[1].0, b.range[0].0, b.range[1].0];
    let hi = [a.range[0].1, a.range[1].1, b.range[0].1, b.range[1].1];
    let span = (0..4).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let clamp = |x: Vector4<f64>| Vector4::from_fn(|k, _| x[k].clamp(lo[k], hi[k]));
    let eval = |x: &Vector4<f64>| (a.surface.jet(x[0], x[1]), b.surface.jet(x[2], x[3]));
    let mut x = clamp(Vector4::from(start));
    let (mut ja, mut jb) = eval(&x);
    let mut f = 0.5 * (ja.point - jb.point).length_squared();
    let mut lambda = 0.0f64;
    let (mut stop, mut iterations, mut last_step) = (Stop::IterationLimit, 0, f64::INFINITY);
    while iterations < NEWTON_STEPS {
        if f == 0.0 {
            stop = Stop::Converged;
            break;
        }
        iterations += 1;
        let r = ja.point - jb.point;
        let cols = [ja.du, ja.dv, -jb.du, -jb.dv];
        let g = Vector4::from_fn(|k, _| cols[k].dot(r));
        let mut h = Matrix4::from_fn(|i, j| cols[i].dot(cols[j]));
        h[(0, 0)] += r.dot(ja.duu);
        h[(0, 1)] += r.dot(ja.duv);
        h[(1, 0)] += r.dot(ja.duv);
        h[(1, 1)] += r.dot(ja.dvv);
        h[(2, 2)] -= r.dot(jb.duu);
        h[(2, 3)] -= r.dot(jb.duv);
        h[(3, 2)] -= r.dot(jb.duv);
        h[(3, 3)] -= r.dot(jb.dvv);
        let held = |k: usize| (x[k] <= lo[k] && g[k] > 0.0) || (x[k] >= hi[k] && g[k] < 0.0);
        let scale = (0..4).map(|k| h[(k, k)].abs()).fold(f64::MIN_POSITIVE, f64::max);
        let mut accepted = None;
        for _ in 0..40 {
            let mut m = h;
            for k in 0..4 {
                m[(k, k)] += lambda * h[(k, k)].abs().max(1e-12 * scale);
                if held(k) {
                    for l in 0..4 {
                        m[(k, l)] = 0.0;
                        m[(l, k)] = 0.0;
                    }
                    m[(k, k)] = 1.0;
                }
            }
            let rhs = Vector4::from_fn(|k, _| if held(k) { 0.0 } else { -g[k] });
            if let Some(chol) = m.cholesky() {
                let next = clamp(x + chol.solve(&rhs));
                let (na, nb) = eval(&next);
                let fn_ = 0.5 * (na.point - nb.point).length_squared();
                if fn_ <= f {
                    accepted = Some((next, na, nb, fn_));
                    break;
                }
            }
            lambda = (lambda * 10.0).max(1e-9);
        }
        let Some((next, na, nb, fn_)) = accepted else {
            stop = Stop::Stalled;
            break;
        };
        last_step = (next - x).norm();
        lambda *= 0.1;
        (x, ja, jb, f) = (next, na, nb, fn_);
        if last_step <= 1e-13 * span {
            stop = Stop::Converged;
            break;
        }
    }
    record(
        "nurbs.distance.newton",
        stop,
        iterations,
        if f == 0.0 { 0.0 } else { last_step },
    );
    Refined {
        distance: (2.0 * f).sqrt(),
        params: [x[0], x[1], x[2], x[3]],
        points: [ja.point, jb.point],
        iterations,
    }
}

/// [`refine`] started from the patches' nearest control points (at their Greville
/// abscissae).
pub fn refine_from_controls(a: &Patch, b: &Patch) -> Refined {
    let (_, k, l) = nearest_points(a, b);
    let at = |p: &Patch, k: usize| {
        let nv = p.surface.count()[1];
        [
            greville(&p.surface, Direction::U)[k / nv],
            greville(&p.surface, Direction::V)[k % nv],
        ]
    };
    let (s, t) = (at(a, k), at(b, l));
    refine(a, b, [s[0], s[1], t[0], t[1]])
}

/// The least refined distance among candidate leaf `pairs` of `a` and `b`: each refined
/// from its nearest control points, nearest hulls first, until one touches (within
/// [`TOUCH`] of `a`'s size); `None` when there are no pairs.
pub fn nearest_among(a: &PatchTree, b: &PatchTree, pairs: &[LeafPair]) -> Option<Refined> {
    let mut order: Vec<&LeafPair> = pairs.iter().collect();
    order.sort_by(|x, y| x.gap.total_cmp(&y.gap).then(x.patches.cmp(&y.patches)));
    let touch = TOUCH * a.tree.nodes.first().map_or(0.0, |n| n.hull.extent());
    let mut best: Option<Refined> = None;
    for p in order {
        let r = refine_from_controls(&a.patches[p.patches[0] as usize], &b.patches[p.patches[1] as usize]);
        if best.is_none_or(|b| r.distance < b.distance) {
            best = Some(r);
        }
        if r.distance <= touch {
            break;
        }
    }
    best
}

/// Distances at most this fraction of the scene's size count as touching.
pub const TOUCH: f64 = 1e-12;

/// The true least distance between two subdivided surfaces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceDistance {
    /// The refinement that found it.
    pub best: Refined,
    /// The leaves it lies in.
    pub patches: [u32; 2],
    /// Leaf pairs refined.
    pub refined: u64,
    /// Hull pairs tested.
    pub hull_tests: u64,
}

struct NearestSurface<'a> {
    a: &'a PatchTree,
    b: &'a PatchTree,
    best: SurfaceDistance,
    /// Distances at most this count as touching (the search ends).
    touch: f64,
}

impl PairVisitor for NearestSurface<'_> {
    fn bound(&self) -> f64 {
        self.best.best.distance
    }

    fn leaves(&mut self, i: u32, j: u32, _gap: f64) {
        let r = refine_from_controls(&self.a.patches[i as usize], &self.b.patches[j as usize]);
        self.best.refined += 1;
        if r.distance < self.best.best.distance {
            self.best.best = r;
            self.best.patches = [i, j];
        }
    }

    fn done(&self) -> bool {
        self.best.best.distance <= self.touch
    }
}

/// The true least distance between the surfaces of `a` and `b`: branch and bound over leaf
/// pairs, each pair whose hulls come nearer than the best distance so far refined by
/// [`refine_from_controls`]. Exact up to the refinement finding the least distance within
/// a pair of leaves (their patches are nearly flat at the levels used). It ends at the
/// first distance within [`TOUCH`] of the scene's size: the surfaces touch or cross.
pub fn surface_distance(a: &PatchTree, b: &PatchTree) -> SurfaceDistance {
    let size = [a, b]
        .iter()
        .filter_map(|t| t.tree.nodes.first())
        .map(|n| n.hull.extent())
        .fold(0.0, f64::max);
    let mut v = NearestSurface {
        a,
        b,
        touch: TOUCH * size,
        best: SurfaceDistance {
            best: Refined {
                distance: f64::INFINITY,
                params: [0.0; 4],
                points: [DVec3::ZERO; 2],
                iterations: 0,
            },
            patches: [0, 0],
            refined: 0,
            hull_tests: 0,
        },
    };
    v.best.hull_tests = descend(&a.tree, &b.tree, &mut v);
    v.best
}

/// How far a level's control points stand from their surface, the greatest over the leaves
/// of the distance from a control point to the point of its sub-surface at the point's
/// Greville abscissae (an upper bound on its distance from the surface). The control net
/// converges to the surface quadratically, so this shrinks about fourfold per level.
pub fn net_deviation(t: &PatchTree) -> f64 {
    let mut worst = 0.0f64;
    for p in &t.patches {
        let (gu, gv) = (greville(&p.surface, Direction::U), greville(&p.surface, Direction::V));
        for (i, &u) in gu.iter().enumerate() {
            for (j, &v) in gv.iter().enumerate() {
                worst = worst.max(p.points[i * gv.len() + j].distance(p.surface.point(u, v)));
            }
        }
    }
    worst
}

/// How far a point of the surface can be from the nearest control point of its leaf: the
/// greatest over the leaves and an `n x n` grid of samples of each leaf's box. It bounds
/// how much the control-point distance can exceed the true distance; the control points'
/// spacing halves per level, so this shrinks about twofold per level.
pub fn coverage(t: &PatchTree, n: usize) -> f64 {
    let n = n.max(2);
    let mut worst = 0.0f64;
    for p in &t.patches {
        for a in 0..n {
            for b in 0..n {
                let u = p.range[0].0 + (p.range[0].1 - p.range[0].0) * a as f64 / (n - 1) as f64;
                let v = p.range[1].0 + (p.range[1].1 - p.range[1].0) * b as f64 / (n - 1) as f64;
                let s = p.surface.point(u, v);
                let near = p.points.iter().map(|q| q.distance(s)).fold(f64::INFINITY, f64::min);
                worst = worst.max(near);
            }
        }
    }
    worst
}
