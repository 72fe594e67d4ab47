//! `nurbs` and `move`: NURBS parts in the scene. Adding a part subdivides it and collides
//! it with the body and the other parts; moving one does the same where it would go, and is
//! refused (the part stays) when it would collide. The body's triangle hulls are built with
//! the first part, so a session without NURBS parts does none of this work.

use glam::DVec3;

use crate::nurbs::NurbsOptions;
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::flow::nurbs::{contacts, describe, record};
use crate::session::options::StepContext;
use crate::session::stage::{NurbsStage, Stage};
use crate::session::state::SessionState;

/// `move NAME by=x,y,z turn=DEG`.
pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    name: &str,
    by: DVec3,
    turn_deg: f64,
) -> Result<(), StepError> {
    let options = NurbsOptions::default();
    let Some(k) = state.nurbs.iter().position(|p| p.name == name) else {
        return Err(StepError::NoNurbsPart(name.to_string()));
    };
    let moved = scope.timed("nurbs.subdivide", || state.nurbs[k].moved(by, turn_deg, options.level));
    let found = contacts(scope, state, cx, &moved, &options);
    record(scope, &moved, state.nurbs.len(), &found);
    let refusal = found.iter().find(|c| c.colliding).map(|c| {
        format!(
            "move {name} refused: {}; the part stays where it was",
            describe(c, options.threshold_m)
        )
    });
    if refusal.is_none() {
        state.nurbs[k] = moved;
    }
    let stage = Stage::Nurbs(NurbsStage {
        parts: &state.nurbs,
        moved: name,
        contacts: &found,
        refused: refusal.as_deref(),
    });
    match &refusal {
        Some(message) => scope.refuse(message, "nurbs.refused", stage),
        None => scope.emit("nurbs.collide", stage),
    }
    Ok(())
}
