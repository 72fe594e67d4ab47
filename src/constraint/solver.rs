//! The constraint solver of an edit ([collide] section 2.3, [frame] section 3).
//!
//! An edit moves control points of one curve (the active element). The solver then works
//! outward through the network: a curve is solved when a constraint with an already
//! solved curve is violated, and its neighbours are visited in priority order. Solving a
//! curve applies, in order:
//!
//! 1. the constraints from its solved neighbours (coincident points, mirrored points,
//!    tangents), with the curve's other control points following in proportion;
//! 2. its self constraints: symmetry, the ease against its body section, the design
//!    polygon, coplanarity;
//! 3. the node layer: every control point is collided with the body (moved out, within the
//!    curve's plane, until it stands the collision gap off the skin);
//! 4. the curve layer: the refitted curve's samples are collided, and each sample short of
//!    the gap pushes the two control points around it out, for a few rounds;
//! 5. the self-crossing check, which stops the edit with the curve's name.
//!
//! A collision response can break a constraint with a curve solved before (a closed chain
//! A -> B -> C -> A). With [`Chains::Iterate`] the solver moves A to meet the constraint
//! and solves again from A, until nothing breaks or the pass limit is reached (the
//! remaining violations are then reported). With [`Chains::Split`] each curve is split at
//! the points it shares with curves already solved: those points stay pinned during its
//! response, the chain is open, and one pass is made.

use std::collections::{BTreeMap, BTreeSet, VecDeque};

use glam::{DVec2, DVec3};
use thiserror::Error;

use super::crossing::self_crossings;
use super::curves::{self, CurveKind, CurveNode};
use super::kinds::{Kind, SAMPLES_PER_SPAN, mirror, nearest_on_polygon, signed_gap};
use super::network::ConstraintNet;
use crate::garment::{BodyProbe, Ease, Framework, RingOptions, ease_ring};

/// How closed chains are handled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Chains {
    /// Move the first element of the chain and solve again (the default).
    #[default]
    Iterate,
    /// Split the chain's curves at their shared points so it is open; one pass.
    Split,
}

impl Chains {
    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Iterate => "iterate",
            Self::Split => "split",
        }
    }

    /// From the session spelling.
    pub fn from_name(s: &str) -> Option<Self> {
        [Self::Iterate, Self::Split].into_iter().find(|c| c.name() == s)
    }
}

/// Solver settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverOptions {
    /// Closed chains (default iterate).
    pub chains: Chains,
    /// Most passes over the network (default 8).
    pub passes: usize,
    /// A constraint is met when its residual is at most this, m or rad (default 1e-6: a
    /// micrometre; coincident points are copied and meet exactly).
    pub tolerance: f64,
    /// Rounds of the curve-layer response per curve (default 4).
    pub response_rounds: usize,
    /// The curve-layer response aims this fraction of the gap beyond it (default 0.05), so
    /// that a closed chain is not re-broken by a shortfall of a few micrometres.
    pub response_margin: f64,
    /// The collision gap as a fraction of the garment's ease (default 0.5, as the mesh
    /// layer), at least `min_gap` of the body's height (default 0.002).
    pub gap_fraction: f64,
    /// Floor of the collision gap, as a fraction of the body's height (default 0.002).
    pub min_gap: f64,
    /// Ring refitting.
    pub ring: RingOptions,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            chains: Chains::Iterate,
            passes: 8,
            tolerance: 1e-6,
            response_rounds: 4,
            response_margin: 0.05,
            gap_fraction: 0.5,
            min_gap: 0.002,
            ring: RingOptions::default(),
        }
    }
}

/// Where a drag goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// Move by this vector, m.
    By(DVec3),
    /// Move to this point, m.
    To(DVec3),
}

/// An edit of the framework's curves.
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// Drag a named control point (`waist.front`, `crotch.point`, `left_strap.top`).
    Point {
        /// Point name.
        name: String,
        /// Where to.
        target: Target,
    },
    /// Drag a whole curve by a vector.
    Curve {
        /// Curve name.
        name: String,
        /// The move, m.
        by: DVec3,
    },
}

impl std::fmt::Display for Edit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = |d: DVec3| format!("({:.3}, {:.3}, {:.3})", d.x, d.y, d.z);
        match self {
            Self::Point {
                name,
                target: Target::By(d),
            } => write!(f, "drag {name} by {} m", v(*d)),
            Self::Point {
                name,
                target: Target::To(p),
            } => write!(f, "drag {name} to {} m", v(*p)),
            Self::Curve { name, by } => write!(f, "drag curve {name} by {} m", v(*by)),
        }
    }
}

/// Why an edit cannot be made. The framework is left as it was.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum EditError {
    /// No such control point.
    #[error("unknown control point '{name}': expected one of {known}")]
    UnknownPoint {
        /// Asked.
        name: String,
        /// What exists.
        known: String,
    },
    /// No such curve.
    #[error("unknown curve '{name}': expected one of {known}")]
    UnknownCurve {
        /// Asked.
        name: String,
        /// What exists.
        known: String,
    },
    /// A coordinate is not finite.
    #[error("the drag of '{0}' is not a finite vector")]
    NotFinite(String),
    /// The edit would make a curve cross itself.
    #[error(
        "curve '{curve}' would cross itself (segments {i} and {j} meet at ({x:.4}, {y:.4}, {z:.4}) m, cutting off a loop of {loop_length:.4} m): edit refused",
        x = at.x, y = at.y, z = at.z
    )]
    SelfCrossing {
        /// Curve.
        curve: String,
        /// First segment.
        i: usize,
        /// Second segment.
        j: usize,
        /// Where.
        at: DVec3,
        /// Loop length, m.
        loop_length: f64,
    },
    /// A curve cannot be refitted.
    #[error("curve '{curve}' cannot be refitted: {message}")]
    Refit {
        /// Curve.
        curve: String,
        /// Why.
        message: String,
    },
}

/// A control point moved by the node-layer collision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeHit {
    /// Control point index.
    pub point: usize,
    /// Signed distance to the body before, m.
    pub distance: f64,
    /// Before.
    pub before: DVec3,
    /// After.
    pub after: DVec3,
}

/// The curve-layer collision of one curve.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CurveHits {
    /// Samples tested.
    pub samples: usize,
    /// Samples short of the gap before the response.
    pub short_before: usize,
    /// Largest shortfall before, m.
    pub deficit_before: f64,
    /// Largest shortfall after, m.
    pub deficit_after: f64,
    /// Response rounds made.
    pub rounds: usize,
    /// Control points the response moved.
    pub moved: Vec<usize>,
    /// Control points kept still (shared with curves solved before, split chains).
    pub pinned: Vec<usize>,
}

/// One curve solved: what drove it, what the collision did, and the residuals of the
/// constraints it touches afterwards.
#[derive(Clone, Debug, PartialEq)]
pub struct Iteration {
    /// Pass (0-based).
    pub pass: usize,
    /// Curve index in the network.
    pub curve: usize,
    /// Constraints applied from solved neighbours.
    pub driven_by: Vec<usize>,
    /// Node layer.
    pub node: Vec<NodeHit>,
    /// Curve layer.
    pub curve_layer: CurveHits,
    /// `(constraint, residual)` of every constraint touching the curve.
    pub residuals: Vec<(usize, f64)>,
    /// Constraints with curves solved before that this solve left violated.
    pub broken: Vec<usize>,
    /// The curve's control points afterwards.
    pub control: Vec<DVec3>,
}

/// The result of an edit.
#[derive(Clone, Debug)]
pub struct Solution {
    /// The framework with its curves solved (lines, patches and M0 not yet rebuilt).
    pub framework: Framework,
    /// Every curve solve, in order.
    pub iterations: Vec<Iteration>,
    /// Passes made.
    pub passes: usize,
    /// Whether the last pass broke nothing.
    pub converged: bool,
    /// Every constraint's residual at the end.
    pub residuals: Vec<f64>,
    /// `(constraint, residual)` above the tolerance at the end.
    pub violations: Vec<(usize, f64)>,
    /// The dragged point (curve, control point), for a point drag.
    pub dragged: Option<(usize, usize)>,
    /// The dragged point: where it was, where it was asked to go, after the first pass's
    /// node layer, and after each pass.
    pub path: Vec<DVec3>,
    /// The curves solved.
    pub solved: Vec<usize>,
    /// The collision gap used, m.
    pub gap: f64,
    /// Largest shortfall of the gap left on a solved planar curve's samples, m.
    pub clearance_deficit: f64,
    /// The tolerance the constraints were solved to.
    pub tolerance: f64,
}

impl Solution {
    /// The largest residual at the end, m or rad.
    pub fn max_residual(&self) -> f64 {
        self.residuals.iter().copied().fold(0.0, f64::max)
    }

    /// One line per constraint left violated (`kind curve[-other] by residual unit`).
    pub fn violation_lines(&self, net: &ConstraintNet) -> Vec<String> {
        self.violations
            .iter()
            .map(|&(k, r)| net.constraints[k].describe(&net.curves, r))
            .collect()
    }
}

/// Every draggable point name with its (curve, control point).
pub fn point_names(fw: &Framework, net: &ConstraintNet) -> Vec<(String, usize, usize)> {
    let mut out = Vec::new();
    for (k, c) in net.curves.iter().enumerate() {
        match c.kind {
            CurveKind::Ring => {
                for a in &fw.rings[c.index].anchors {
                    out.push((format!("{}.{}", c.name, a.name), k, a.control));
                }
            }
            CurveKind::Open => {
                let apex = fw.open_curves[c.index].apex_name;
                out.push((format!("{}.{apex}", c.name), k, curves::points(fw, c).len() / 2));
            }
            CurveKind::Contour => {}
        }
    }
    out
}

struct Run<'a> {
    fw: Framework,
    net: &'a ConstraintNet,
    probe: &'a BodyProbe,
    options: &'a SolverOptions,
    gap: f64,
    iterations: Vec<Iteration>,
}

fn refit_error(c: &CurveNode, message: String) -> EditError {
    EditError::Refit {
        curve: c.name.clone(),
        message,
    }
}

/// Solves an edit on `fw`. The input is not changed; on error nothing is returned but the
/// error.
pub fn solve(
    fw: &Framework,
    net: &ConstraintNet,
    edit: &Edit,
    probe: &BodyProbe,
    options: &SolverOptions,
) -> Result<Solution, EditError> {
    let gap = (options.gap_fraction * fw.ease()).max(options.min_gap * fw.layout.height);
    let mut run = Run {
        fw: fw.clone(),
        net,
        probe,
        options,
        gap,
        iterations: Vec::new(),
    };
    // The edit as moves of the active curve's points.
    let (active, moves, dragged, whole) = match edit {
        Edit::Point { name, target } => {
            let names = point_names(fw, net);
            let Some((_, c, p)) = names.iter().find(|(n, _, _)| n == name) else {
                let known: Vec<&str> = names.iter().map(|(n, _, _)| n.as_str()).collect();
                return Err(EditError::UnknownPoint {
                    name: name.clone(),
                    known: known.join(", "),
                });
            };
            let at = curves::points(fw, &net.curves[*c])[*p];
            let d = match target {
                Target::By(v) => *v,
                Target::To(q) => *q - at,
            };
            if !d.is_finite() {
                return Err(EditError::NotFinite(name.clone()));
            }
            (*c, vec![(*p, d)], Some((*c, *p)), None)
        }
        Edit::Curve { name, by } => {
            let Some(c) = net.curve(name) else {
                let known: Vec<&str> = net.curves.iter().map(|c| c.name.as_str()).collect();
                return Err(EditError::UnknownCurve {
                    name: name.clone(),
                    known: known.join(", "),
                });
            };
            if !by.is_finite() {
                return Err(EditError::NotFinite(name.clone()));
            }
            let n = curves::points(fw, &net.curves[c]).len();
            (c, (0..n).map(|p| (p, *by)).collect(), None, Some(*by))
        }
    };
    let mut path = Vec::new();
    if let Some((c, p)) = dragged {
        let at = curves::points(fw, &net.curves[c])[p];
        path.push(at);
        path.push(at + moves[0].1);
    }
    if let Some(by) = whole {
        curves::shift_plane(&mut run.fw, &net.curves[active], by);
    }
    let mut pending: BTreeMap<usize, Vec<(usize, DVec3)>> = BTreeMap::new();
    pending.insert(active, moves);
    let mut solved_all: BTreeSet<usize> = BTreeSet::new();
    let mut passes = 0;
    let mut converged = false;
    for pass in 0..options.passes.max(1) {
        passes = pass + 1;
        let broken = run.pass(pass, &mut pending, &mut solved_all)?;
        if let Some((c, p)) = dragged {
            if pass == 0
                && let Some(first) = run.iterations.iter().find(|it| it.curve == c)
            {
                path.push(first.control[p]);
            }
            path.push(curves::points(&run.fw, &net.curves[c])[p]);
        }
        if broken.is_empty() {
            converged = true;
            break;
        }
        if options.chains == Chains::Split {
            break;
        }
        // Close the chain: move the element solved first (A) to meet the constraint the
        // later one (C) broke, and solve again from A.
        pending = run.close_chains(&broken);
    }
    let residuals = net.residuals(&run.fw);
    let violations = residuals
        .iter()
        .enumerate()
        .filter(|(_, r)| **r > options.tolerance)
        .map(|(k, r)| (k, *r))
        .collect();
    let solved: Vec<usize> = solved_all.into_iter().collect();
    let clearance_deficit = solved
        .iter()
        .filter(|&&c| net.curves[c].kind != CurveKind::Contour)
        .flat_map(|&c| run.deficits(c))
        .map(|s| s.deficit)
        .fold(0.0, f64::max);
    Ok(Solution {
        framework: run.fw,
        iterations: run.iterations,
        passes,
        converged,
        residuals,
        violations,
        dragged,
        path,
        solved,
        gap,
        clearance_deficit,
        tolerance: options.tolerance,
    })
}

impl Run<'_> {
    fn node(&self, c: usize) -> &CurveNode {
        &self.net.curves[c]
    }

    /// The collision gap of curve `c`: the solver's gap, or the least clearance the curve
    /// was built with where that is less (a ring whose ease is limited next to an arm).
    fn gap_of(&self, c: usize) -> f64 {
        self.gap.min(self.net.clearance[c]).max(0.0)
    }

    /// The collision gap of each control point of `c`: the curve's gap, or less where the
    /// point is shared with a curve held to a smaller one (a strap ending on the chest ring
    /// next to the arm). Curves meeting at a point agree on where it may stand, so one does
    /// not push it where the other pulls it back.
    fn point_gaps(&self, c: usize) -> Vec<f64> {
        let n = curves::points(&self.fw, self.node(c)).len();
        let mut gaps = vec![self.gap_of(c); n];
        for &k in &self.net.touching(c) {
            let con = &self.net.constraints[k];
            if let Kind::Coincident { a, b } = con.kind
                && !con.is_self()
            {
                let (on_c, o) = if con.i == c { (a, con.j) } else { (b, con.i) };
                gaps[on_c] = gaps[on_c].min(self.gap_of(o));
            }
        }
        gaps
    }

    /// The mirrored pairs of `c`'s self symmetry (a point on the mirror plane pairs with
    /// itself).
    fn mirror_pairs(&self, c: usize) -> Vec<(usize, usize)> {
        self.net
            .touching(c)
            .iter()
            .filter_map(|&k| match &self.net.constraints[k].kind {
                Kind::Symmetry { pairs, .. } if self.net.constraints[k].is_self() => Some(pairs.clone()),
                _ => None,
            })
            .flatten()
            .collect()
    }

    fn residual(&self, k: usize) -> f64 {
        self.net.constraints[k].residual(&self.fw, &self.net.curves)
    }

    /// One pass outward from the curves with pending moves. Returns the constraints left
    /// broken by a curve solved after the other end of the constraint.
    fn pass(
        &mut self,
        pass: usize,
        pending: &mut BTreeMap<usize, Vec<(usize, DVec3)>>,
        solved_all: &mut BTreeSet<usize>,
    ) -> Result<Vec<(usize, usize)>, EditError> {
        let tol = self.options.tolerance;
        let mut solved: BTreeSet<usize> = BTreeSet::new();
        let mut queue: VecDeque<usize> = pending.keys().copied().collect();
        let mut queued: BTreeSet<usize> = queue.iter().copied().collect();
        let mut broken: Vec<(usize, usize)> = Vec::new();
        let mut deferred: BTreeSet<usize> = BTreeSet::new();
        while let Some(c) = queue.pop_front() {
            // A curve waits (once) for a queued curve that drives it one way (a strap
            // before the contour that continues it).
            let waits = self.net.touching(c).iter().any(|&k| {
                let con = &self.net.constraints[k];
                con.directed && con.j == c && queue.contains(&con.i) && !solved.contains(&con.i)
            });
            if waits && deferred.insert(c) {
                queue.push_back(c);
                continue;
            }
            let moves = pending.remove(&c).unwrap_or_default();
            let mut it = self.solve_curve(pass, c, &moves, &solved)?;
            solved.insert(c);
            solved_all.insert(c);
            let touching = self.net.touching(c);
            for &k in &touching {
                let r = self.residual(k);
                it.residuals.push((k, r));
                let o = self.net.constraints[k].other(c);
                if r > tol && solved.contains(&o) {
                    it.broken.push(k);
                    broken.push((k, c));
                }
            }
            self.iterations.push(it);
            // Outward, in priority order: neighbours whose constraint with c is violated.
            for &k in &touching {
                let con = &self.net.constraints[k];
                let o = con.other(c);
                if o == c || solved.contains(&o) || queued.contains(&o) || !con.drives(c, o) {
                    continue;
                }
                if self.residual(k) > tol {
                    queue.push_back(o);
                    queued.insert(o);
                }
            }
        }
        Ok(broken)
    }

    /// Moves for the next pass: for each broken constraint (k, by curve c), the other
    /// curve A takes c's point (or c itself is solved again for a self constraint).
    fn close_chains(&mut self, broken: &[(usize, usize)]) -> BTreeMap<usize, Vec<(usize, DVec3)>> {
        let mut out: BTreeMap<usize, Vec<(usize, DVec3)>> = BTreeMap::new();
        for &(k, c) in broken {
            let con = &self.net.constraints[k];
            let a = con.other(c);
            let entry = out.entry(a).or_default();
            if a == c {
                continue;
            }
            if let Kind::Tangent { front } = con.kind {
                let (open, contour) = (self.net.curves[con.i].index, self.net.curves[con.j].index);
                let t = self.fw.open_curves[open].end_tangent(front);
                self.fw.contours[contour].tangents[1] = Some(t);
                continue;
            }
            let (pa, pc) = (
                curves::points(&self.fw, self.node(a)),
                curves::points(&self.fw, self.node(c)),
            );
            match &con.kind {
                Kind::Coincident { a: ia, b: ib } => {
                    let (on_a, on_c) = if con.i == a { (*ia, *ib) } else { (*ib, *ia) };
                    entry.push((on_a, pc[on_c] - pa[on_a]));
                }
                Kind::Symmetry { mid_x, pairs, rest } => {
                    let plane = curves::plane(&self.fw, &self.net.curves[a]);
                    for (&(i, j), r) in pairs.iter().zip(rest) {
                        let (on_a, want) = if con.i == a {
                            (i, mirror(pc[j] - *r, *mid_x))
                        } else {
                            (j, mirror(pc[i], *mid_x) + *r)
                        };
                        let want = plane.map_or(want, |p| p.snap(want));
                        entry.push((on_a, want - pa[on_a]));
                    }
                }
                _ => {}
            }
        }
        out
    }

    fn solve_curve(
        &mut self,
        pass: usize,
        c: usize,
        moves: &[(usize, DVec3)],
        solved: &BTreeSet<usize>,
    ) -> Result<Iteration, EditError> {
        let tol = self.options.tolerance;
        let node = self.node(c).clone();
        let mut driven_by = Vec::new();
        let mut moved: Vec<(usize, DVec3)> = moves.to_vec();
        let mut pinned: BTreeSet<usize> = BTreeSet::new();
        let touching = self.net.touching(c);
        // 1. From the solved neighbours.
        let mut tangents = match node.kind {
            CurveKind::Contour => self.fw.contours[node.index].tangents,
            _ => [None, None],
        };
        for &k in &touching {
            let con = &self.net.constraints[k];
            let o = con.other(c);
            if o == c || !solved.contains(&o) {
                continue;
            }
            // Shared points stay where the solved curve put them (split chains).
            if let Kind::Coincident { a, b } = con.kind {
                pinned.insert(if con.i == c { a } else { b });
            }
            if !con.drives(o, c) || con.residual(&self.fw, &self.net.curves) <= tol {
                continue;
            }
            driven_by.push(k);
            let (po, pc) = (curves::points(&self.fw, self.node(o)), curves::points(&self.fw, &node));
            match &con.kind {
                Kind::Coincident { a, b } => {
                    let (on_c, on_o) = if con.i == c { (*a, *b) } else { (*b, *a) };
                    set_move(&mut moved, on_c, po[on_o] - pc[on_c]);
                }
                Kind::Symmetry { mid_x, pairs, rest } => {
                    let plane = curves::plane(&self.fw, &node);
                    for (&(i, j), r) in pairs.iter().zip(rest) {
                        let (on_c, want) = if con.i == c {
                            (i, mirror(po[j] - *r, *mid_x))
                        } else {
                            (j, mirror(po[i], *mid_x) + *r)
                        };
                        let want = plane.map_or(want, |p| p.snap(want));
                        set_move(&mut moved, on_c, want - pc[on_c]);
                    }
                }
                Kind::Tangent { front } => {
                    let t = self.fw.open_curves[self.node(o).index].end_tangent(*front);
                    tangents[1] = Some(t);
                }
                _ => {}
            }
        }
        if node.kind == CurveKind::Contour {
            self.fw.contours[node.index].tangents = tangents;
        }
        let mut control = curves::spread(&self.fw, &node, &moved);
        if node.kind == CurveKind::Open {
            // An open curve's plane is the vertical plane through its ends.
            let (a, b) = (control[0], control[control.len() - 1]);
            let n = (b - a).cross(DVec3::Y).normalize_or_zero();
            if n != DVec3::ZERO {
                let old = self.fw.open_curves[node.index].plane.normal;
                let n = if n.dot(old) < 0.0 { -n } else { n };
                self.fw.open_curves[node.index].plane = crate::geom::Plane::from_point_normal(a, n);
            }
        }
        // 2. Self constraints: the plane; symmetry (each pair takes its driven side, or the
        // side whose pair stands further off the body); then the ease and the design region,
        // applied as joint pushes of each mirrored pair so that they keep the symmetry; the
        // plane again.
        if let Some(plane) = curves::plane(&self.fw, &node) {
            // Into the plane first, so the choices below are made where the points will be.
            for p in control.iter_mut() {
                *p = plane.snap(*p);
            }
            let driven: BTreeSet<usize> = moved.iter().map(|m| m.0).collect();
            let limits = SelfLimits::of(self.net, &touching, &plane, true);
            for &k in &touching {
                let con = &self.net.constraints[k];
                if !con.is_self() {
                    continue;
                }
                if let Kind::Symmetry { mid_x, pairs, rest } = &con.kind {
                    for (&(i, j), r) in pairs.iter().zip(rest) {
                        if i == j {
                            // A point on the mirror plane stays there (up to its rest offset).
                            control[i].x = *mid_x + 0.5 * r.x;
                            continue;
                        }
                        let from_i = plane.snap(mirror(control[i], *mid_x) + *r);
                        let from_j = plane.snap(mirror(control[j] - *r, *mid_x));
                        let take_i = match (driven.contains(&i), driven.contains(&j)) {
                            (true, false) => true,
                            (false, true) => false,
                            // Both or neither driven: keep the side that leaves the control
                            // polygon uncrossed, else the side the ease and region need to
                            // move less, else the side whose pair stands further off the body
                            // (the nearer of its two points).
                            _ => {
                                let crosses = |k: usize, p: DVec3| {
                                    let flat: Vec<DVec2> = (0..control.len())
                                        .map(|m| plane.project(if m == k { p } else { control[m] }))
                                        .collect();
                                    !self_crossings(&flat, curves::closed(&node)).is_empty()
                                };
                                let fix = |k: usize, p: DVec3| (limits.apply(k, p, tol) - p).length();
                                let sd = |p: DVec3| self.probe.signed_distance(p);
                                let (fix_i, fix_j) =
                                    (fix(i, control[i]) + fix(j, from_i), fix(i, from_j) + fix(j, control[j]));
                                match (crosses(j, from_i), crosses(i, from_j)) {
                                    (false, true) => true,
                                    (true, false) => false,
                                    _ if (fix_i - fix_j).abs() > tol => fix_i < fix_j,
                                    _ => sd(control[i]).min(sd(from_i)) >= sd(from_j).min(sd(control[j])),
                                }
                            }
                        };
                        if take_i {
                            control[j] = from_i;
                        } else {
                            control[i] = from_j;
                        }
                    }
                }
            }
            limits.hold(&self.mirror_pairs(c), &BTreeSet::new(), &mut control, tol);
            for p in control.iter_mut() {
                *p = plane.snap(*p);
            }
        }
        curves::set_points(&mut self.fw, &node, control, &self.options.ring).map_err(|m| refit_error(&node, m))?;
        self.check_crossing(&node)?;
        // 3. Node layer.
        let keep: BTreeSet<usize> = if self.options.chains == Chains::Split {
            pinned
        } else {
            BTreeSet::new()
        };
        let node_hits = self.node_layer(c, &keep)?;
        // 4. Curve layer.
        let curve_layer = self.curve_layer(c, &keep)?;
        self.check_crossing(&node)?;
        Ok(Iteration {
            pass,
            curve: c,
            driven_by,
            node: node_hits,
            curve_layer,
            residuals: Vec::new(),
            broken: Vec::new(),
            control: curves::points(&self.fw, &node).to_vec(),
        })
    }

    fn check_crossing(&self, node: &CurveNode) -> Result<(), EditError> {
        let Some(plane) = curves::plane(&self.fw, node) else {
            return Ok(());
        };
        let samples = curves::samples(&self.fw, node, SAMPLES_PER_SPAN);
        let flat: Vec<DVec2> = samples.iter().map(|(_, p)| plane.project(*p)).collect();
        if let Some(x) = self_crossings(&flat, curves::closed(node)).first() {
            return Err(EditError::SelfCrossing {
                curve: node.name.clone(),
                i: x.i,
                j: x.j,
                at: plane.lift(x.at),
                loop_length: x.loop_length,
            });
        }
        Ok(())
    }

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
        let (mut lo, mut hi) = (0.0, (gap - d).max(1e-6));
        let mut grow = 0;
        while sd(hi) < gap && grow < 40 {
            lo = hi;
            hi *= 2.0;
            grow += 1;
        }
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if sd(mid) < gap {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-12 {
                break;
            }
        }
        p + u * hi
    }

    /// Collides every control point of a planar curve (a contour's points belong to the
    /// rings and open curves, which collide them). A symmetric curve is pushed jointly: each
    /// pair moves by the larger of its two pushes, mirrored, so the response keeps the
    /// symmetry the self constraints just made; rounds repeat until every point clears.
    fn node_layer(&mut self, c: usize, keep: &BTreeSet<usize>) -> Result<Vec<NodeHit>, EditError> {
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
        for _ in 0..JOINT_ROUNDS {
            let mut push = vec![DVec3::ZERO; now.len()];
            for (i, p) in now.iter().enumerate() {
                if !keep.contains(&i) && self.probe.signed_distance(*p) < gaps[i] * (1.0 - 1e-9) {
                    push[i] = self.push_out(*p, plane, centre, gaps[i]) - *p;
                }
            }
            if push.iter().all(|d| *d == DVec3::ZERO) {
                break;
            }
            mirror_pushes(&pairs, &mut push, keep);
            for (p, d) in now.iter_mut().zip(&push) {
                if *d != DVec3::ZERO {
                    *p = plane.snap(*p + *d);
                }
            }
            ease.hold(&pairs, keep, &mut now, self.options.tolerance);
        }
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
    fn deficits(&self, c: usize) -> Vec<Short> {
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

    fn curve_layer(&mut self, c: usize, keep: &BTreeSet<usize>) -> Result<CurveHits, EditError> {
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
            ease.hold(&pairs, keep, &mut next, self.options.tolerance);
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

/// A curve's ease and design region, ready to apply point by point in its plane.
struct SelfLimits<'a> {
    plane: crate::geom::Plane,
    /// Section, the section in the plane's frame, least gap per control point.
    ease: Vec<(&'a [DVec3], Vec<DVec2>, &'a [f64])>,
    regions: Vec<&'a [DVec2]>,
}

impl<'a> SelfLimits<'a> {
    /// The ease of the curve's self constraints, and its design regions when `regions`.
    fn of(net: &'a ConstraintNet, touching: &[usize], plane: &crate::geom::Plane, regions: bool) -> Self {
        let mut out = Self {
            plane: *plane,
            ease: Vec::new(),
            regions: Vec::new(),
        };
        for &k in touching {
            let con = &net.constraints[k];
            match &con.kind {
                Kind::OutsideBody { section, need } if con.is_self() => {
                    let flat = section.iter().map(|p| plane.project(*p)).collect();
                    out.ease.push((section, flat, need));
                }
                Kind::InsidePolygon { polygon } if con.is_self() && regions => out.regions.push(polygon),
                _ => {}
            }
        }
        out
    }

    /// Control point `i` at `p` moved out of its section by the ease, then into the region
    /// (the region wins where they conflict).
    fn apply(&self, i: usize, mut p: DVec3, tol: f64) -> DVec3 {
        let plane = &self.plane;
        for (section, flat, need) in &self.ease {
            let n = need[i];
            if signed_gap(plane.project(p), flat) < n - tol
                && let Ok(q) = ease_ring(&[p], section, plane, Ease::Uniform(n))
            {
                p = q[0];
            }
        }
        for polygon in &self.regions {
            let q = plane.project(p);
            if signed_gap(q, polygon) > 0.0 {
                p = plane.lift(nearest_on_polygon(q, polygon).0) + plane.normal * plane.signed_distance(p);
            }
        }
        p
    }

    /// Applies the limits to every point as joint pushes of the mirrored `pairs` (so they
    /// keep a symmetry already made), for up to [`JOINT_ROUNDS`] rounds. Pinned points stay.
    fn hold(&self, pairs: &[(usize, usize)], keep: &BTreeSet<usize>, control: &mut [DVec3], tol: f64) {
        if self.ease.is_empty() && self.regions.is_empty() {
            return;
        }
        for _ in 0..JOINT_ROUNDS {
            let mut push: Vec<DVec3> = control
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    if keep.contains(&i) {
                        DVec3::ZERO
                    } else {
                        self.apply(i, *p, tol) - *p
                    }
                })
                .collect();
            if push.iter().all(|d| *d == DVec3::ZERO) {
                break;
            }
            mirror_pushes(pairs, &mut push, keep);
            for (p, d) in control.iter_mut().zip(&push) {
                *p += *d;
            }
        }
    }
}

/// A curve sample short of its collision gap, on the span from control point `a` to `b`.
struct Short {
    a: usize,
    b: usize,
    /// Where on the span, 0 at `a` and 1 at `b`.
    t: f64,
    /// The gap there, m.
    gap: f64,
    /// Shortfall, m.
    deficit: f64,
    /// In-plane direction out of the body.
    out: DVec3,
}

/// Most rounds of joint pushes, in the node layer and when holding the ease and region (a
/// joint push of a mirrored pair can move the partner where the body is closer; a round or
/// two settles it).
const JOINT_ROUNDS: usize = 8;

/// Makes collision pushes symmetric: each mirrored pair `(i, j)` moves by the longer of
/// `push[i]` and the mirror image of `push[j]` (and the partner by its image); a point on
/// the mirror plane moves only along it. Pinned points stay.
fn mirror_pushes(pairs: &[(usize, usize)], push: &mut [DVec3], keep: &BTreeSet<usize>) {
    let flip = |d: DVec3| DVec3::new(-d.x, d.y, d.z);
    for &(i, j) in pairs {
        if i == j {
            push[i].x = 0.0;
            continue;
        }
        if keep.contains(&i) || keep.contains(&j) {
            continue;
        }
        let (a, b) = (push[i], flip(push[j]));
        let d = if a.length_squared() >= b.length_squared() { a } else { b };
        push[i] = d;
        push[j] = flip(d);
    }
}

/// Records a driven move of point `i` unless a stronger constraint (seen earlier, in
/// priority order) or the edit itself already placed it.
fn set_move(moved: &mut Vec<(usize, DVec3)>, i: usize, d: DVec3) {
    if !moved.iter().any(|m| m.0 == i) {
        moved.push((i, d));
    }
}
