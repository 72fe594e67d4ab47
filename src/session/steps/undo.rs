//! `undo`: the garment back to its state before the last `set` or `drag` (a refused drag
//! counts: undoing it changes nothing). Its M1, when the history left it out, is made again
//! (the same, bit for bit). The restored curves, patches, M0, collision and M1 are emitted
//! again, so a viewer shows the state the session is now in.

use serde::Serialize;

use crate::session::Session;
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::flow::collide::emit_kept;
use crate::session::flow::restore::restore_m1;
use crate::session::options::RunOptions;
use crate::session::stage::{GarmentStage, Stage};
use crate::session::state::SessionState;

/// The state restored.
#[derive(Serialize)]
struct UndoFigures {
    /// M0 vertices of the restored garment.
    m0_vertices: usize,
}

pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    (session, options): (&Session, &RunOptions),
) -> Result<(), StepError> {
    let mut previous = state.history.pop()?;
    if let Some(probe) = &state.probe {
        let m1 = session.scene.m1.as_ref();
        let restored = (&mut previous, state.garment.as_mut());
        restore_m1(scope, (&state.body, probe.index()), restored, options, m1);
    }
    if let Some(fw) = &previous.framework {
        scope.record(&UndoFigures {
            m0_vertices: fw.m0.mesh.positions.len(),
        });
        scope.emit(
            "garment.undo",
            Stage::Garment(GarmentStage::Undone {
                framework: fw,
                net: previous.net.as_ref(),
            }),
        );
    }
    if let Some(probe) = &state.probe {
        emit_kept(scope, &previous, probe.index());
    }
    let had_sculpt = state.garment.as_ref().is_some_and(|g| g.sculpted.is_some());
    if had_sculpt && previous.sculpted.is_none() {
        crate::session::flow::sculpt::emit_cleared(scope);
    }
    state.garment = Some(previous);
    Ok(())
}
