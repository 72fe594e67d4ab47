//! `sculpt at=x,y,z radius=R peak=H [dir=...]`: a push or pull on the garment's latest
//! mesh (the last sculpt's result, else M1, else M0), refined adaptively where it
//! stretched, then collided with the body by M1's machinery (only the new and moved
//! vertices are tested and may move). A sculpt that would leave the garment in the body
//! is refused and the garment stays as it was. Undoable.
//!
//! The sculpts are stored with the garment and made again, in order, on the new mesh after
//! every later rebuild (`set`, `drag`): the pick point snaps to the nearest point of the
//! new surface.

use crate::mesh::topology::undirected_edges;
use crate::sculpt::{Drag, SculptOptions};
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::flow::sculpt::{SculptVerify, apply, base, emit, record, resolve};
use crate::session::format::SculptAt;
use crate::session::options::StepContext;
use crate::session::stage::{SculptStage, Stage};
use crate::session::state::SessionState;

/// The `sculpt` step.
pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    at: &SculptAt,
    drag: &Drag,
    options: &SculptOptions,
) -> Result<(), StepError> {
    let (Some(current), Some(probe)) = (state.garment.as_ref(), state.probe.as_ref()) else {
        return Err(StepError::NoGarment { verb: "sculpt" });
    };
    let drag = &Drag {
        at: resolve(current, at)?,
        ..*drag
    };
    let (Some(ease), Some(base)) = (current.ease(), base(current)) else {
        return Err(StepError::NoGarment { verb: "sculpt" });
    };
    let index = probe.index();
    let (before_inside, before_crossing, before_pierced) = (base.inside.len(), base.crossing.len(), base.pierced.len());
    let outcome = apply(
        scope,
        base,
        (drag, options),
        index,
        ease,
        &cx.options.collision,
        current.sculpts.len() + 1,
    )
    .map_err(StepError::Sculpt)?;
    let mut next = current.clone();
    next.sculpts.push((at.clone(), *drag, *options));
    next.sculpted = Some(outcome);
    // Worn over other garments: the sculpted surface pushed out in front of theirs.
    let layers = (!cx.below.is_empty()).then(|| {
        let m0 = current
            .layered
            .as_ref()
            .map(|l| l.pairs.iter().map(|p| p.m0.clone()).collect())
            .unwrap_or_default();
        scope.timed("layers.push_latest", || {
            crate::session::flow::layers::finish(
                index,
                &mut next,
                cx.below,
                m0,
                crate::layers::PushOptions::default().ease,
            )
        })
    });
    let Some(outcome) = next.sculpted.as_ref() else {
        return Err(StepError::NoGarment { verb: "sculpt" });
    };
    let verify = cx.options.verify.then(|| {
        scope.timed("sculpt.verify", || {
            let mesh = outcome.mesh();
            let truth =
                crate::collision::ground_truth(&state.body.mesh.mesh, &mesh.positions, &undirected_edges(&mesh))
                    .with_faces(&state.body.mesh.mesh, &mesh.positions, &mesh.triangles);
            SculptVerify {
                inside: truth.inside_count(),
                crossing: truth.crossing_count(),
                pierced: truth.pierced_count(),
            }
        })
    });
    record(scope, outcome, verify);
    let q = &outcome.collision.quality;
    let unmet = if q.penetrating_vertices > before_inside
        || q.crossing_edges > before_crossing
        || q.pierced_faces > before_pierced
    {
        Some(format!(
            "the garment cannot be kept clear of the body after this sculpt: {} vertices inside, {} edges \
             crossing it and {} faces pierced by it after the response",
            q.penetrating_vertices, q.crossing_edges, q.pierced_faces
        ))
    } else {
        match &layers {
            Some(Err(e)) => Some(format!("the garment cannot be layered: {e}")),
            _ => crate::session::flow::layers::out_of_order(&next).map(|(under, c)| {
                format!(
                    "the garment cannot be kept in front of '{under}' after this sculpt: {} vertices behind it, {} \
                     edges through it and {} faces pierced by it after the push",
                    c.behind, c.outer_edges_through_inner, c.outer_faces_pierced
                )
            }),
        }
    };
    if let Some(message) = unmet {
        scope.refuse(
            &message,
            "garment.sculpt",
            Stage::Sculpt(SculptStage {
                outcome: Some(outcome),
                refused: Some(&message),
            }),
        );
        state.history.push(current.clone());
        return Ok(());
    }
    emit(scope, &next);
    if let Some(layered) = next.layered.as_ref().filter(|_| layers.is_some()) {
        crate::session::flow::collide::record_layers(scope, &next);
        scope.emit("layers.push", Stage::Layers(layered));
    }
    state.advance(next);
    Ok(())
}
