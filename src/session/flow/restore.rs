//! A state restored from the undo history (by `undo`, or by a refused edit of a garment worn
//! under others): the M1 the history left out of it to keep it small (see
//! `GarmentState::for_history`) made again, as the step that made the state made it. M1
//! depends only on what the state keeps (its collided M0, cut lines and standard size), so
//! the state comes back the same, bit for bit, and logs the same data.
//!
//! (M0's collision is kept: its detection's figures, which the log shows, count the work
//! detection's memory spared, and that memory has moved on since.)

use crate::body::Body;
use crate::collision::BodyIndex;
use crate::m1::M1Options;
use crate::session::emit::StepScope;
use crate::session::options::RunOptions;
use crate::session::state::GarmentState;

use super::m1::build_m1;

/// Makes `state`, restored from the history in place of `dropped` (the state it replaces,
/// when there is one), whole again: it takes `dropped`'s M1 caches
/// ([`GarmentState::take_caches`]: each answers only for its own inputs, which it checks),
/// then makes again the M1 the history left out of it (nothing when it left none out), with
/// the scene's M1 settings (`m1_options`). Its timings and work go into the step's metrics;
/// its figures do not (the step restores the state, it does not make it).
pub(in crate::session) fn restore_m1(
    scope: &mut StepScope<'_, '_, '_>,
    (body, index): (&Body, &BodyIndex),
    (state, dropped): (&mut GarmentState, Option<&mut GarmentState>),
    options: &RunOptions,
    m1_options: Option<&M1Options>,
) {
    if let Some(dropped) = dropped {
        state.take_caches(dropped);
    }
    if let (true, Some(m1_options)) = (std::mem::take(&mut state.m1_left_out), m1_options) {
        let figures = scope.metrics.figures.clone();
        let quiet = RunOptions {
            verify: false,
            ..options.clone()
        };
        build_m1(scope, body, index, state, &quiet, m1_options);
        scope.metrics.figures = figures;
    }
}
