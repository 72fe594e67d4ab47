//! `nurbs` and `move`: NURBS parts in the scene. Adding a part subdivides it and collides
//! it with the body and the other parts; moving one does the same where it would go, and is
//! refused (the part stays) when it would collide. The body's triangle hulls are built with
//! the first part, so a session without NURBS parts does none of this work.

use std::path::Path;

use glam::DVec3;
use serde::Serialize;

use super::super::emit::StepScope;
use super::super::error::StepError;
use super::super::stage::{NurbsStage, Stage};
use super::super::state::SessionState;
use super::StepContext;
use crate::nurbs::{BodyHulls, Contact, NurbsOptions, NurbsPart, collide_body, collide_parts, file};

/// The figures of a NURBS step.
#[derive(Serialize)]
struct NurbsFigures<'a> {
    /// The part added or moved.
    part: &'a str,
    /// Parts in the scene.
    parts: usize,
    /// Leaves of its subdivision.
    leaves: usize,
    /// Least distance to the body within the threshold, m (absent: farther).
    body_distance_m: Option<f64>,
    /// Its leaf corners inside the body.
    inside_body: usize,
    /// Least distance to another part within the threshold, m (absent: farther).
    part_distance_m: Option<f64>,
    /// Whether it collides with anything.
    colliding: bool,
}

/// `part` against the body and every other part of `state`.
fn contacts(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    part: &NurbsPart,
    options: &NurbsOptions,
) -> Vec<Contact> {
    let body = &state.body;
    let probe = super::garment::body_probe(scope, body, &mut state.probe, cx);
    let hulls = match &mut state.nurbs_body {
        Some(h) => h,
        slot @ None => slot.insert(scope.timed("nurbs.body_hulls", || {
            BodyHulls::new(&body.mesh.mesh.positions, &body.mesh.mesh.triangles)
        })),
    };
    let index = probe.index();
    scope.timed("nurbs.collide", || {
        let mut out: Vec<Contact> = collide_body(part, hulls, options.threshold_m, |p: DVec3| index.winding(p) != 0)
            .into_iter()
            .collect();
        for other in state.nurbs.iter().filter(|o| o.name != part.name) {
            out.extend(collide_parts(part, other, options.threshold_m));
        }
        out
    })
}

fn record(scope: &mut StepScope<'_, '_, '_>, part: &NurbsPart, parts: usize, contacts: &[Contact]) {
    let body = contacts.iter().find(|c| c.other == "body");
    scope.record(&NurbsFigures {
        part: &part.name,
        parts,
        leaves: part.tree.patches.len(),
        body_distance_m: body.map(|c| c.distance_m).filter(|d| d.is_finite()),
        inside_body: body.map_or(0, |c| c.inside),
        part_distance_m: contacts
            .iter()
            .filter(|c| c.other != "body")
            .map(|c| c.distance_m)
            .reduce(f64::min),
        colliding: contacts.iter().any(|c| c.colliding),
    });
}

fn describe(c: &Contact, threshold: f64) -> String {
    if c.inside > 0 {
        format!("'{}' would have {} point(s) inside the {}", c.part, c.inside, c.other)
    } else {
        format!(
            "'{}' would come {:.3} mm from '{}', nearer than the threshold {:.3} mm",
            c.part,
            c.distance_m * 1e3,
            c.other,
            threshold * 1e3
        )
    }
}

/// `nurbs FILE name=NAME`.
pub(super) fn add(
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
    let limit = match cx.options.max_input_bytes {
        0 => crate::input::DEFAULT_MAX_INPUT_BYTES,
        n => n,
    };
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

/// `move NAME by=x,y,z turn=DEG`.
pub(super) fn move_part(
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
