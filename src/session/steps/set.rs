//! `set`: one dimension of the current garment changed. The framework is solved again
//! with it, the drags made since the last change are replayed on it, and M0 is rebuilt
//! with the same topology and collided.

use serde::Serialize;

use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::flow::collide::{collide_and_emit, unclear};
use crate::session::flow::drag::replay_edits;
use crate::session::flow::garment::solve_garment;
use crate::session::format::Change;
use crate::session::options::StepContext;
use crate::session::stage::{GarmentPart, GarmentStage, Stage};
use crate::session::state::{GarmentState, History, SessionState};

/// The change asked for.
#[derive(Serialize)]
struct SetFigures<'a> {
    /// Dimension name.
    dimension: &'a str,
    /// Its value before (m, or a fraction for `strap_position`).
    before: f64,
    /// The value set.
    value: f64,
}

/// How far the change moved M0.
#[derive(Serialize)]
struct MoveFigures {
    /// Largest distance between a vertex of M0 before and after, m.
    max_vertex_move_m: f64,
}

/// Whether a failure of the re-solve means the change cannot be honoured (refused, the
/// session goes on) rather than that the step failed: any failure to build the framework
/// with the new value (a dimension out of its range, a ring too small or too large, a
/// section the new shape no longer cuts, ...) leaves the garment before it intact, so the
/// change is refused with the reason; what remains a failure is a step with no garment.
fn refuses(e: &StepError) -> bool {
    matches!(e, StepError::Framework(_) | StepError::Replay { .. })
}

pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    name: &str,
    change: Change,
) -> Result<(), StepError> {
    if let Some(g) = state.garment.as_ref().filter(|g| g.file.is_some()) {
        return Err(StepError::FileGarment {
            name: g.name(),
            verb: "set",
            what: "dimensions",
        });
    }
    let Some((current_state, before)) = state
        .garment
        .as_ref()
        .and_then(|g| g.framework.as_ref().map(|f| (g, f)))
    else {
        return Err(StepError::NoGarment { verb: "change" });
    };
    let current = before.dimension(name).unwrap_or(0.0);
    let value = change.apply(current);
    scope.record(&SetFigures {
        dimension: name,
        before: current,
        value,
    });
    let mut next = current_state.unsolved();
    next.dims.values.insert(name.to_string(), value);
    let solved = solve_garment(scope, &state.body, &mut state.probe, cx, next, Some(before)).and_then(|next| {
        replay_edits(
            scope,
            next,
            (state.probe.as_ref(), Some(before)),
            &cx.session.scene.solver,
        )
    });
    let mut next = match solved {
        Ok(next) => next,
        Err(e) if refuses(&e) => {
            refuse(scope, &mut state.history, current_state, name, value, &e.to_string());
            return Ok(());
        }
        Err(e) => return Err(e),
    };
    if let Some(after) = &next.framework {
        let moved = before
            .m0
            .mesh
            .positions
            .iter()
            .zip(&after.m0.mesh.positions)
            .map(|(a, b)| a.distance(*b))
            .fold(0.0, f64::max);
        scope.record(&MoveFigures {
            max_vertex_move_m: moved,
        });
        scope.emit(
            "garment.edit",
            Stage::Garment(GarmentStage::Edit { name, before, after }),
        );
        for part in GarmentPart::all() {
            scope.emit(part.stage_name(), Stage::Garment(GarmentStage::Part(after, part)));
        }
    }
    if let Some(probe) = &state.probe
        && let Some(unmet) = collide_and_emit(scope, &state.body, probe.index(), &mut next, cx)
    {
        // The response could not clear the new M0: refused like a change the framework
        // cannot take.
        let message = unclear(scope, current_state, probe.index(), &unmet);
        refuse(scope, &mut state.history, current_state, name, value, &message);
        return Ok(());
    }
    state.advance(next);
    Ok(())
}

/// Refuses the change: the garment stays as it was (an `undo` of this step changes
/// nothing), the refusal is recorded and emitted, and the session goes on.
fn refuse(
    scope: &mut StepScope<'_, '_, '_>,
    history: &mut History,
    kept: &GarmentState,
    name: &str,
    value: f64,
    message: &str,
) {
    history.push(kept.clone());
    scope.refuse(
        message,
        "garment.refused",
        Stage::Garment(GarmentStage::Refused { name, value, message }),
    );
}
