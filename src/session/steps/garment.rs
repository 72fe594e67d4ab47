//! `garment`: a garment built from its template: the framework solved against the body
//! (planes, rings through their sub-steps, open curves, contours, patches, M0), its
//! constraint network, and the collision of M0.

use crate::garment::{FrameworkOptions, TemplateKind};
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::flow::collide::collide_new;
use crate::session::flow::garment::solve_garment;
use crate::session::options::StepContext;
use crate::session::stage::{ConstraintStage, GarmentPart, GarmentStage, Stage};
use crate::session::state::{GarmentState, SessionState};

pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    template: TemplateKind,
    (options, label): (FrameworkOptions, Option<String>),
) -> Result<(), StepError> {
    state.history.clear();
    let mut garment = GarmentState::new(template, options);
    garment.label = label;
    let mut next = solve_garment(scope, &state.body, &mut state.probe, cx, garment, None)?;
    if let (Some(fw), Some(net)) = (&next.framework, &next.net) {
        for part in GarmentPart::all() {
            scope.emit(part.stage_name(), Stage::Garment(GarmentStage::Part(fw, part)));
        }
        scope.emit(
            "constraints.network",
            Stage::Constraints(ConstraintStage::Network(fw, net)),
        );
    }
    next.standard = next
        .framework
        .as_ref()
        .map(|fw| std::sync::Arc::new(fw.m0.mesh.positions.clone()));
    if let Some(probe) = &state.probe {
        collide_new(scope, &state.body, probe.index(), &mut next, cx);
    }
    state.garment = Some(next);
    Ok(())
}
