//! A drag solved and re-surfaced, shared by the `drag` step and by `set`, which makes the
//! garment's drags again on its re-solved framework.

use crate::constraint::{self, ConstraintNet, Edit, Solution, SolverOptions};
use crate::garment::assemble::assemble_among;
use crate::garment::{BodyProbe, Framework};
use crate::session::emit::StepScope;
use crate::session::error::{DragRefusal, StepError};
use crate::session::state::GarmentState;
use serde::Serialize;

/// The figures of a solve.
#[derive(Serialize)]
struct SolveFigures<'a> {
    /// Passes over the network.
    passes: usize,
    /// Curve solves, over all passes.
    solver_iterations: usize,
    /// Whether the last pass broke nothing.
    converged: bool,
    /// The curves solved, by name.
    curves_solved: Vec<&'a str>,
    /// The largest residual at the end, m or rad.
    max_residual: f64,
    /// The constraints left violated.
    violations: Vec<Violation<'a>>,
    /// Control points moved by the node layer.
    node_hits: usize,
    /// The collision gap used, m.
    collision_gap_m: f64,
    /// Largest shortfall of the gap left on a solved planar curve, m.
    clearance_deficit_m: f64,
    /// Patches surfaced anew and kept.
    resurfaced_patches: usize,
    kept_patches: usize,
    /// Where the dragged point ended, m (a point drag).
    #[serde(skip_serializing_if = "Option::is_none")]
    dragged_to: Option<[f64; 3]>,
}

/// A constraint left violated.
#[derive(Serialize)]
struct Violation<'a> {
    /// Its index in the network.
    constraint: usize,
    /// Its kind.
    kind: &'static str,
    /// The two curves it joins (the same curve twice for a self constraint).
    curves: [&'a str; 2],
    /// Its residual, in `unit`.
    residual: f64,
    /// `m` or `rad`.
    unit: &'static str,
}

impl<'a> SolveFigures<'a> {
    fn new(net: &'a ConstraintNet, s: &Solution, resurfaced: usize, patches: usize) -> Self {
        Self {
            passes: s.passes,
            solver_iterations: s.iterations.len(),
            converged: s.converged,
            curves_solved: s.solved.iter().map(|&c| net.curves[c].name.as_str()).collect(),
            max_residual: s.max_residual(),
            violations: s
                .violations
                .iter()
                .map(|&(k, r)| {
                    let c = &net.constraints[k];
                    Violation {
                        constraint: k,
                        kind: c.kind.name(),
                        curves: [&net.curves[c.i].name, &net.curves[c.j].name],
                        residual: r,
                        unit: c.kind.unit(),
                    }
                })
                .collect(),
            node_hits: s.iterations.iter().map(|it| it.node.len()).sum(),
            collision_gap_m: s.gap,
            clearance_deficit_m: s.clearance_deficit,
            resurfaced_patches: resurfaced,
            kept_patches: patches - resurfaced,
            dragged_to: s.path.last().map(|p| [p.x, p.y, p.z]),
        }
    }
}

/// Drags replayed after a dimension change.
#[derive(Serialize)]
struct ReplayFigures {
    /// How many.
    replayed_drags: usize,
}

/// Solves a drag on `before` (the framework of `state`) and re-surfaces the changed
/// patches, taking the others from `before` or else from `earlier` (a replayed drag: the
/// garment before the dimension edit, which this drag left as it leaves the new one where
/// the edit did not reach). The state is not touched; the new state is returned with the
/// solution.
pub(in crate::session) fn drag(
    scope: &mut StepScope<'_, '_, '_>,
    state: &GarmentState,
    (before, earlier): (&Framework, Option<&Framework>),
    net: &ConstraintNet,
    edit: &Edit,
    probe: &BodyProbe,
    solver: &SolverOptions,
) -> Result<(GarmentState, Solution), DragRefusal> {
    let solution = scope.timed("constraints.solve", || {
        constraint::solve(before, net, edit, probe, solver)
    })?;
    let previous: Vec<&Framework> = std::iter::once(before).chain(earlier).collect();
    let mut built = scope
        .timed("garment.assemble", || {
            assemble_among(&solution.framework, probe, &previous)
        })
        .map_err(|e| unmet(net, &solution).unwrap_or(DragRefusal::Surface(e)))?;
    scope.record(&SolveFigures::new(
        net,
        &solution,
        built.resurfaced.len(),
        built.patches.len(),
    ));
    let mut next = scope.timed("garment.state", || {
        let mut after = solution.framework.clone();
        built.place_on(&mut after);
        let next = state.on_framework(after);
        if let Some(fw) = &next.framework {
            next.detect_memory()
                .remember_nearest(probe.index(), &fw.m0.mesh.positions, &built.measured);
        }
        next
    });
    next.edits.push(edit.clone());
    Ok((next, solution))
}

/// Makes the drags of `state` again on its re-solved framework (after a dimension
/// change), recording the last one's figures. `earlier` is the garment's framework before
/// the change: the patches the change did not reach are taken from there.
pub(in crate::session) fn replay_edits(
    scope: &mut StepScope<'_, '_, '_>,
    mut state: GarmentState,
    (probe, earlier): (Option<&BodyProbe>, Option<&Framework>),
    solver: &SolverOptions,
) -> Result<GarmentState, StepError> {
    let edits = std::mem::take(&mut state.edits);
    let Some(probe) = probe else {
        return Ok(state);
    };
    for (k, edit) in edits.iter().enumerate() {
        let replayed = match (&state.framework, &state.net) {
            (Some(before), Some(net)) => drag(scope, &state, (before, earlier), net, edit, probe, solver),
            _ => return Err(StepError::NoGarment { verb: "drag" }),
        };
        let (next, _) = replayed.map_err(|source| StepError::Replay {
            index: k + 1,
            count: edits.len(),
            source: Box::new(source),
        })?;
        state = next;
    }
    scope.record(&ReplayFigures {
        replayed_drags: edits.len(),
    });
    Ok(state)
}

/// A solve that ended with constraints unmet, as the limit of the user's drag: its largest
/// violation (`None` when the solve met every constraint).
fn unmet(net: &ConstraintNet, solution: &Solution) -> Option<DragRefusal> {
    if solution.converged {
        return None;
    }
    let &(k, residual) = solution.violations.iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
    let c = &net.constraints[k];
    let (a, b) = (&net.curves[c.i].name, &net.curves[c.j].name);
    Some(DragRefusal::Unmet {
        kind: c.kind.name(),
        curves: if a == b {
            format!("'{a}'")
        } else {
            format!("'{a}' and '{b}'")
        },
        residual,
        unit: c.kind.unit(),
    })
}
