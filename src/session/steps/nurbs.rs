//! `nurbs` and `move`: NURBS parts in the scene. Adding a part subdivides it and collides
//! it with the body and the other parts; moving one does the same where it would go, and is
//! refused (the part stays) when it would collide. The body's triangle hulls are built with
//! the first part, so a session without NURBS parts does none of this work.

use std::path::Path;

use crate::nurbs::{NurbsOptions, NurbsPart, file};
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::flow::nurbs::{contacts, record};
use crate::session::options::StepContext;
use crate::session::stage::{NurbsStage, Stage};
use crate::session::state::SessionState;

/// `nurbs FILE name=NAME`.
pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    name: &str,
    path: &Path,
) -> Result<(), StepError> {
    let fail = |message: String| StepError::NurbsFile {
        name: name.to_string(),
        path: path.to_path_buf(),
        message,
    };
    let limit = cx.options.input_limit();
    let text = crate::input::read_text(path, limit).map_err(|e| fail(e.to_string()))?;
    let surface = file::parse(&text).map_err(|e| fail(e.to_string()))?.surface;
    let options = NurbsOptions::default();
    let part = scope.timed("nurbs.subdivide", || NurbsPart::new(name, surface, options.level));
    let found = contacts(scope, state, cx, &part, &options);
    record(scope, &part, state.nurbs.len() + 1, &found);
    // Added where the file puts it; a collision there is reported (the figures, a warning in
    // the log), not refused: the file says where the part is.
    state.nurbs.push(part);
    scope.emit(
        "nurbs.collide",
        Stage::Nurbs(NurbsStage {
            parts: &state.nurbs,
            moved: name,
            contacts: &found,
            refused: None,
        }),
    );
    Ok(())
}
