//! One file per step kind: each holds the step's compute, the stages it emits and the
//! figures it records. [`run_step`] is the table that sends a step to its file.
//!
//! A new step kind is a new file here with a `run` function, its [`super::Op`] variant and
//! parser arm, and one line in [`run_step`].

mod cut;
mod drag;
mod garment;
mod garment_mesh;
mod mannequin;
mod move_part;
mod nurbs;
pub(super) mod scene;
mod sculpt;
mod section;
mod set;
mod undo;

use super::emit::StepScope;
use super::error::StepError;
use super::format::Op;
use super::options::StepContext;
use super::state::SessionState;
use crate::garment::FrameworkOptions;

/// `undo` of the garment in the state's current slot.
pub(super) fn undo_step(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    run: (&super::Session, &super::RunOptions),
) -> Result<(), StepError> {
    undo::run(scope, state, run)
}

/// Runs one step of the session on `state`.
pub(super) fn run_step(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    op: &Op,
) -> Result<(), StepError> {
    match op {
        Op::Mannequin(options) => mannequin::run(scope, options),
        Op::Section { name, y } => section::run(scope, state, name, *y),
        Op::Garment {
            template,
            style,
            fit,
            contours,
            resolution,
            layer,
        } => {
            let options = FrameworkOptions::default()
                .with_style(*style)
                .with_fit(*fit)
                .with_contours(*contours)
                .with_resolution(*resolution);
            let label = (layer.name != template.name()).then(|| layer.name.clone());
            garment::run(scope, state, cx, *template, (options, label))
        }
        Op::GarmentMesh {
            path,
            name,
            ease,
            scale,
            ..
        } => garment_mesh::run(scope, state, cx, (path, name), *ease, *scale),
        Op::Set { name, change } => set::run(scope, state, cx, name, *change),
        Op::Drag(edit) => drag::run(scope, state, cx, edit),
        Op::Undo => undo::run(scope, state, (cx.session, cx.options)),
        Op::Cut { name, plane } => cut::run(scope, state, cx, name, *plane),
        Op::CutThrough { name, points } => cut::through(scope, state, cx, name, points),
        Op::Nurbs { name, path } => nurbs::run(scope, state, cx, name, path),
        Op::Move { name, by, turn_deg } => move_part::run(scope, state, cx, name, *by, *turn_deg),
        Op::Sculpt { at, drag, options } => sculpt::run(scope, state, cx, at, drag, options),
    }
}
