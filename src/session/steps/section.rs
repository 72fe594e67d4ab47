//! `section`: the body cut by a horizontal plane.

use serde::Serialize;

use crate::geom::{Plane, SectionLoop};
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::stage::{SectionCut, Stage};
use crate::session::state::SessionState;

/// The figures of a section step.
#[derive(Serialize)]
struct SectionFigures {
    /// Loops cut.
    loops: usize,
    /// Their lengths, m.
    lengths_m: Vec<f64>,
}

pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &SessionState,
    name: &str,
    y: f64,
) -> Result<(), StepError> {
    let body = &state.body.mesh;
    let loops = scope.timed("section.cut", || body.section(&Plane::horizontal(y)));
    if loops.is_empty() {
        let (lo, hi) = body.mesh.bounds().map_or((0.0, 0.0), |(l, h)| (l.y, h.y));
        return Err(StepError::SectionMisses {
            name: name.to_string(),
            y,
            lo,
            hi,
        });
    }
    scope.record(&SectionFigures {
        loops: loops.len(),
        lengths_m: loops.iter().map(SectionLoop::length).collect(),
    });
    scope.emit("section.cut", Stage::Section(SectionCut { name, y, loops: &loops }));
    Ok(())
}
