//! The node and curve layers (\[collide\] section 2.3): a curve's control points collided with
//! the body (moved out in the curve's plane until they stand the collision gap off it), then
//! its refitted samples (each sample short of the gap pushes the two control points around
//! it out, for a few rounds). A symmetric curve is pushed jointly, pair by pair.

use std::collections::BTreeSet;

use glam::DVec3;

use super::limits::{JOINT_ROUNDS, SelfLimits, mirror_pushes};
use super::{CurveHits, EditError, NodeHit, Run, refit_error};
use crate::constraint::curves::{self, CurveKind, CurveNode};
use crate::constraint::kinds::SAMPLES_PER_SPAN;
use crate::convergence::{Bisection, Stop, record};

impl Run<'_> {
    /// Moves `p` out of the body until it stands `gap` off it: along the body normal, kept
    /// in `plane` when given (found by bisection to 1e-12 m).
    fn push_out(&self, p: DVec3, plane: crate::geom::Plane, centre: DVec3, gap: f64) -> DVec3 {
        let Some((_, d, normal)) = self.probe.nearest(p) else {
            return p;
        };
        if d >= gap * (1.0 - 1e-9) {
            return p;
        }
        let mut u = normal - plane.normal * plane.normal.dot(normal);
        if u.length_squared() < 1e-12 {
            u = plane.snap(p) - plane.snap(centre);
        }
        let u = u.normalize_or_zero();
        if u == DVec3::ZERO {
            return p;
        }
        let sd = |t: f64| self.probe.signed_distance(p + u * t);
        let (mut lo, mut hi) = (0.0, (gap - d).max(1e-6 * self.net.scale));
        let mut grow = 0;
        while sd(hi) < gap && grow < 40 {
            lo = hi;
            hi *= 2.0;
            grow += 1;
        }
        // The bisection's points lie within half the bracket of its middle: their searches
        // scan the triangles gathered for that ball (the same answers).
        let ball = self
            .probe
            .ball(p + u * (0.5 * (lo + hi)), 0.5 * (hi - lo) * (1.0 + 1e-9));
        let sd = |t: f64| self.probe.signed_distance_near(p + u * t, ball.as_ref());
        let (_, hi) = Bisection {
            name: "constraint.layers.push_out",
            steps: 80,
            tolerance: 1e-12 * self.net.scale,
            stop_at_tolerance: true,
        }
        .run(lo, hi, |mid| sd(mid) < gap);
        p + u * hi
    }

    /// Collides every control point of a planar curve (a contour's points belong to the
    /// rings and open curves, which collide them). A symmetric curve is pushed jointly: each
    /// pair moves by the larger of its two pushes, mirrored, so the response keeps the
    /// symmetry the self constraints just made; rounds repeat until every point clears.
    pub(super) fn node_layer(&mut self, c: usize, keep: &BTreeSet<usize>) -> Result<Vec<NodeHit>, EditError> {
        let node = self.net.curves[c].clone();
        let Some(plane) = curves::plane(&self.fw, &node) else {
            return Ok(Vec::new());
        };
        let gaps = self.point_gaps(c);
        let pairs = self.mirror_pairs(c);
        let ease = SelfLimits::of(self.net, &self.net.touching(c), &plane, false);
        let start = curves::points(&self.fw, &node).to_vec();
        let centre = start.iter().sum::<DVec3>() / start.len().max(1) as f64;
        let mut now = start.clone();
        let (mut rounds, mut last, mut idle) = (0, 0.0, false);
        // At the limit, the residual is the longest push of the last round (which still
        // moved something).
        for round in 0..JOINT_ROUNDS {
            let mut push = vec![DVec3::ZERO; now.len()];
            for (i, p) in now.iter().enumerate() {
                if !keep.contains(&i) && self.probe.signed_distance(*p) < gaps[i] * (1.0 - 1e-9) {
                    push[i] = self.push_out(*p, plane, centre, gaps[i]) - *p;
                }
            }
            idle = push.iter().all(|d| *d == DVec3::ZERO);
            if idle {
                break;
            }
            last = push.iter().map(|d| d.length()).fold(0.0, f64::max);
            rounds = round + 1;
            mirror_pushes(&pairs, &mut push, keep);
            for (p, d) in now.iter_mut().zip(&push) {
                if *d != DVec3::ZERO {
                    *p = plane.snap(*p + *d);
                }
            }
            ease.hold(&pairs, keep, &mut now, self.options.tolerance * self.net.scale);
        }
        let stop = if idle { Stop::Converged } else { Stop::IterationLimit };
        record(
            "constraint.layers.joint_rounds",
            stop,
            rounds,
            if idle { 0.0 } else { last },
        );
        let out: Vec<NodeHit> = (0..start.len())
            .filter(|&i| now[i] != start[i])
            .map(|i| NodeHit {
                point: i,
                distance: self.probe.signed_distance(start[i]),
                before: start[i],
                after: now[i],
            })
            .collect();
        if !out.is_empty() {
            curves::set_points(&mut self.fw, &node, now, &self.options.ring).map_err(|m| refit_error(&node, m))?;
        }
        Ok(out)
    }

    /// Samples short of the gap. The gap along a span eases linearly between its two
    /// control points' gaps (see [`Self::point_gaps`]).
    pub(super) fn deficits(&self, c: usize) -> Vec<Short> {
        let node = self.node(c);
        let Some(plane) = curves::plane(&self.fw, node) else {
            return Vec::new();
        };
        let control = curves::points(&self.fw, node);
        let knots = curves::knots(&self.fw, node);
        let (m, spans) = (control.len(), knots.len().saturating_sub(1));
        if m == 0 || spans == 0 {
            return Vec::new();
        }
        let centre = control.iter().sum::<DVec3>() / m as f64;
        let gaps = self.point_gaps(c);
        let mut out = Vec::new();
        for (l, s) in curves::samples(&self.fw, node, SAMPLES_PER_SPAN) {
            let Some((_, d, normal)) = self.probe.nearest(s) else {
                continue;
            };
            let k = knots.partition_point(|&x| x <= l).saturating_sub(1).min(spans - 1);
            let t = ((l - knots[k]) / (knots[k + 1] - knots[k]).max(1e-300)).clamp(0.0, 1.0);
            let (a, b) = (k % m, (k + 1) % m);
            let gap = (1.0 - t) * gaps[a] + t * gaps[b];
            if d < gap * (1.0 - 1e-9) {
                let mut u = normal - plane.normal * plane.normal.dot(normal);
                if u.length_squared() < 1e-12 {
                    u = plane.snap(s) - plane.snap(centre);
                }
                out.push(Short {
                    a,
                    b,
                    t,
                    gap,
                    deficit: gap - d,
                    out: u.normalize_or_zero(),
                });
            }
        }
        out
    }

    pub(super) fn curve_layer(&mut self, c: usize, keep: &BTreeSet<usize>) -> Result<CurveHits, EditError> {
        let node = self.node(c).clone();
        let mut hits = CurveHits {
            samples: curves::samples(&self.fw, &node, SAMPLES_PER_SPAN).len(),
            pinned: keep.iter().copied().collect(),
            ..CurveHits::default()
        };
        if node.kind == CurveKind::Contour {
            // A contour's points are all shared with rings: its samples are cleared off the
            // body where the patches sample it; nothing moves here.
            let (n, worst) = self.deficits_any(&node);
            hits.short_before = n;
            hits.deficit_before = worst;
            hits.deficit_after = worst;
            return Ok(hits);
        }
        let Some(plane) = curves::plane(&self.fw, &node) else {
            return Ok(hits);
        };
        let pairs = self.mirror_pairs(c);
        let touching = self.net.touching(c);
        let ease = SelfLimits::of(self.net, &touching, &plane, false);
        let mut moved: BTreeSet<usize> = BTreeSet::new();
        for round in 0..=self.options.response_rounds {
            let short = self.deficits(c);
            let worst = short.iter().map(|s| s.deficit).fold(0.0, f64::max);
            if round == 0 {
                hits.short_before = short.len();
                hits.deficit_before = worst;
            }
            hits.deficit_after = worst;
            if short.is_empty() || round == self.options.response_rounds {
                break;
            }
            hits.rounds = round + 1;
            let control = curves::points(&self.fw, &node).to_vec();
            let mut push: Vec<DVec3> = vec![DVec3::ZERO; control.len()];
            for s in short {
                let (wa, wb) = (
                    if keep.contains(&s.a) { 0.0 } else { 1.0 - s.t },
                    if keep.contains(&s.b) { 0.0 } else { s.t },
                );
                let norm = wa * wa + wb * wb;
                if norm < 1e-6 {
                    continue;
                }
                let target = s.deficit + self.options.response_margin * s.gap;
                for (i, w) in [(s.a, wa), (s.b, wb)] {
                    let d = s.out * (target * w / norm);
                    if d.length() > push[i].length() {
                        push[i] = d;
                    }
                }
            }
            mirror_pushes(&pairs, &mut push, keep);
            let mut next = control.clone();
            for (i, d) in push.iter().enumerate() {
                if *d != DVec3::ZERO {
                    next[i] = plane.snap(next[i] + *d);
                    moved.insert(i);
                }
            }
            ease.hold(&pairs, keep, &mut next, self.options.tolerance * self.net.scale);
            curves::set_points(&mut self.fw, &node, next, &self.options.ring).map_err(|m| refit_error(&node, m))?;
        }
        hits.moved = moved.into_iter().collect();
        Ok(hits)
    }

    fn deficits_any(&self, node: &CurveNode) -> (usize, f64) {
        let mut n = 0;
        let mut worst: f64 = 0.0;
        for (_, s) in curves::samples(&self.fw, node, SAMPLES_PER_SPAN) {
            let d = self.probe.signed_distance(s);
            if d < self.gap * (1.0 - 1e-9) {
                n += 1;
                worst = worst.max(self.gap - d);
            }
        }
        (n, worst)
    }
}

/// A curve sample short of its collision gap, on the span from control point `a` to `b`.
pub(super) struct Short {
    /// The span's first control point.
    a: usize,
    /// Its last.
    b: usize,
    /// Where on the span, 0 at `a` and 1 at `b`.
    t: f64,
    /// The gap there, m.
    gap: f64,
    /// Shortfall, m.
    pub(super) deficit: f64,
    /// In-plane direction out of the body.
    out: DVec3,
}
