//! The constraint solver of an edit (\[collide\] section 2.3, \[frame\] section 3).
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

mod chains;
mod curve;
mod edit;
mod layers;
mod limits;
mod limits_of_edit;
mod options;
mod propagate;
mod solution;

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use super::curves::{self, CurveKind, CurveNode};
use super::kinds::Kind;
use super::network::ConstraintNet;
use crate::convergence::{Stop, record};
use crate::garment::{BodyProbe, Framework};

pub use edit::{Edit, EditError, Target, point_names};
pub use options::{Chains, SolverOptions};
pub use solution::{CurveHits, Iteration, NodeHit, Solution};

/// The state of one solve: the framework being changed and what was done so far.
struct Run<'a> {
    fw: Framework,
    net: &'a ConstraintNet,
    probe: &'a BodyProbe,
    options: &'a SolverOptions,
    gap: f64,
    iterations: Vec<Iteration>,
}

pub(super) fn refit_error(c: &CurveNode, failure: curves::RefitFailure) -> EditError {
    match failure {
        curves::RefitFailure::Meet { points, at } => EditError::Folds {
            curve: c.name.clone(),
            points,
            at,
        },
        curves::RefitFailure::Fit(message) => EditError::Refit {
            curve: c.name.clone(),
            message,
        },
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
        fw: fw.without_surface(),
        net,
        probe,
        options,
        gap,
        iterations: Vec::new(),
    };
    // The edit as moves of the active curve's points.
    let asked = edit_moves(fw, net, edit)?;
    check_limits(fw, net, edit, &asked, probe)?;
    let (active, moves, dragged, whole) = asked;
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
    let mut stop = Stop::IterationLimit;
    let mut broken_before: Option<Vec<(usize, usize)>> = None;
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
            stop = Stop::Converged;
            break;
        }
        if options.chains == Chains::Split {
            break;
        }
        // The same constraints broken by the same curves in the last two passes: the
        // chains are not closing (reported as a stall when the passes run out so).
        stop = if broken_before.as_ref() == Some(&broken) {
            Stop::Stalled
        } else {
            Stop::IterationLimit
        };
        // Close the chain: move the element solved first (A) to meet the constraint the
        // later one (C) broke, and solve again from A.
        pending = run.close_chains(&broken);
        broken_before = Some(broken);
    }
    let residuals = net.residuals(&run.fw);
    let violations: Vec<(usize, f64)> = residuals
        .iter()
        .enumerate()
        .filter(|(k, r)| net.violated(*k, **r, options.tolerance))
        .map(|(k, r)| (k, *r))
        .collect();
    // A solve is converged only when every constraint meets the tolerance in its own unit
    // (the passes watch the constraints between the curves they solved; a constraint they
    // did not visit can still be off).
    if converged && !violations.is_empty() {
        converged = false;
        stop = Stop::Stalled;
    }
    let largest = residuals.iter().map(|r| r.abs()).fold(0.0, f64::max);
    record("constraint.passes", stop, passes, largest);
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

/// An edit as moves: `(the active curve, the moves of its points, the dragged point
/// (curve, point) of a point edit, the whole curve's move of a curve edit)`.
type EditMoves = (usize, Vec<(usize, DVec3)>, Option<(usize, usize)>, Option<DVec3>);

/// The edit as moves of the active curve's points.
fn edit_moves(fw: &Framework, net: &ConstraintNet, edit: &Edit) -> Result<EditMoves, EditError> {
    Ok(match edit {
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
    })
}

/// What a drag may not do: a whole curve moved out of its band, round the body or (an open
/// curve's apex) through it; an open curve's point dragged through the body.
fn check_limits(
    fw: &Framework,
    net: &ConstraintNet,
    edit: &Edit,
    asked: &EditMoves,
    probe: &BodyProbe,
) -> Result<(), EditError> {
    let (active, moves, dragged, whole) = (asked.0, &asked.1, asked.2, asked.3);
    if let Some(by) = whole {
        limits_of_edit::check_band(fw, &net.curves[active], by, probe)?;
        limits_of_edit::check_around(fw, &net.curves[active], by, probe)?;
        if net.curves[active].kind == CurveKind::Open {
            let node = &net.curves[active];
            let apex = curves::points(fw, node)[curves::points(fw, node).len() / 2];
            limits_of_edit::check_path(&node.name, apex, apex + by, probe)?;
        }
    }
    if let Some((c, p)) = dragged
        && net.curves[c].kind == CurveKind::Open
    {
        let at = curves::points(fw, &net.curves[c])[p];
        if let Edit::Point { name, .. } = edit {
            limits_of_edit::check_path(name, at, at + moves[0].1, probe)?;
        }
    }
    Ok(())
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
}
