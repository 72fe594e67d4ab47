//! `drag`: a control point or a whole curve of the current garment moved. The constraint
//! solver brings the framework back to a valid state (\[frame\] section 3, \[collide\] section
//! 2.3), the patches along the changed curves are re-surfaced, and M0 is collided. A drag
//! the solver refuses leaves the garment as it was; the session goes on.

use crate::constraint::Edit;
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::flow::collide::{collide_and_emit, unclear};
use crate::session::flow::drag::drag;
use crate::session::options::StepContext;
use crate::session::stage::{ConstraintStage, GarmentPart, GarmentStage, Stage};
use crate::session::state::{GarmentState, History, SessionState};

pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    edit: &Edit,
) -> Result<(), StepError> {
    let (Some(current), Some(probe)) = (state.garment.as_ref(), state.probe.as_ref()) else {
        return Err(StepError::NoGarment { verb: "drag" });
    };
    if current.file.is_some() {
        return Err(StepError::FileGarment {
            name: current.name(),
            verb: "drag",
            what: "control points",
        });
    }
    let (Some(before), Some(net)) = (&current.framework, &current.net) else {
        return Err(StepError::NoGarment { verb: "drag" });
    };
    match drag(
        scope,
        current,
        (before, None),
        net,
        edit,
        probe,
        &cx.session.scene.solver,
    ) {
        Ok((mut next, solution)) => {
            if let Some(after) = &next.framework {
                scope.emit(
                    "constraints.solve",
                    Stage::Constraints(ConstraintStage::Solve {
                        edit,
                        net,
                        before,
                        solution: &solution,
                    }),
                );
                for part in GarmentPart::RESURFACED {
                    scope.emit(part.stage_name(), Stage::Garment(GarmentStage::Part(after, part)));
                }
            }
            if let Some(unmet) = collide_and_emit(scope, &state.body, probe.index(), &mut next, cx) {
                // The response could not clear the new M0: refused like a drag the solver
                // cannot honour.
                let message = unclear(scope, current, probe.index(), &unmet);
                refuse(scope, &mut state.history, current, edit, &message);
                return Ok(());
            }
            state.advance(next);
        }
        Err(refusal) => refuse(scope, &mut state.history, current, edit, &refusal.to_string()),
    }
    Ok(())
}

/// Refuses the drag: the garment stays as it was (an `undo` of this step changes nothing),
/// the refusal is recorded and emitted, and the session goes on.
fn refuse(scope: &mut StepScope<'_, '_, '_>, history: &mut History, kept: &GarmentState, edit: &Edit, message: &str) {
    history.push(kept.clone());
    scope.refuse(
        message,
        "constraints.refused",
        Stage::Constraints(ConstraintStage::Refused { edit, message }),
    );
}
