//! Garments worn in layers, around the steps: which garment a step works on (the one it
//! names, else the outermost), the garments under it handed to the step as surfaces, and
//! after an edit that moved a garment, every garment over it collided and pushed out in
//! front again, innermost first. When one of them cannot be kept in order the whole edit is
//! refused and every garment stays as it was. `undo` takes back a step's changes to every
//! garment it changed.
//!
//! A session with one garment goes through here unchanged: nothing is under it, nothing
//! over it.

use super::emit::StepScope;
use super::error::StepError;
use super::flow::collide::{collide_and_emit, emit_kept};
use super::flow::layers::{Below, below, latest_mesh};
use super::flow::restore::restore_m1;
use super::format::{Op, Session, Step};
use super::options::{RunOptions, StepContext};
use super::stage::Stage;
use super::state::{GarmentState, SessionState, Worn};
use super::steps::run_step;

/// Which garment a step works on.
enum Target {
    /// A new garment: replacing every garment worn, or over the outermost.
    New { name: String, over: bool },
    /// A garment worn (its index, innermost first).
    Worn(usize),
    /// No garment is worn (the step needs none, or fails for want of one).
    None,
}

/// Runs `step` on the garment it works on; with more than one garment worn, records the
/// certificates of every garment against the body and of every pair of layers after it.
pub(super) fn run_worn(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    run: (&Session, &RunOptions),
    step: &Step,
) -> Result<(), StepError> {
    run_on_target(scope, state, run, step)?;
    if state.worn.len() > 1 {
        scope.record(&WornFigures {
            worn: certificates(&state.worn),
        });
    }
    Ok(())
}

/// The certificates after a step of a session with layers.
#[derive(serde::Serialize)]
struct WornFigures {
    /// `body/NAME`: the garment against the body; `UNDER/OVER`: a pair of layers (M0, plus
    /// the latest mesh).
    worn: std::collections::BTreeMap<String, Certificate>,
}

/// A certificate's counts.
#[derive(serde::Serialize)]
struct Certificate {
    /// Vertices inside the body, or behind the garment under.
    inside_or_behind: usize,
    /// Edges through the body's faces, or through the faces of the garment under.
    edges_through: usize,
    /// Faces an edge of the body, or of the garment under, passes through.
    faces_pierced: usize,
}

impl From<[usize; 3]> for Certificate {
    fn from([inside_or_behind, edges_through, faces_pierced]: [usize; 3]) -> Self {
        Self {
            inside_or_behind,
            edges_through,
            faces_pierced,
        }
    }
}

/// Every worn garment against the body and against each garment under it.
fn certificates(worn: &[Worn]) -> std::collections::BTreeMap<String, Certificate> {
    let mut out = std::collections::BTreeMap::new();
    for w in worn {
        let Some(g) = &w.garment else { continue };
        let mut body = [0; 3];
        if let Some(c) = &g.collision {
            let q = &c.collision.quality;
            body = [q.penetrating_vertices, q.crossing_edges, q.pierced_faces];
        }
        let latest = g
            .sculpted
            .as_ref()
            .map(|s| &s.collision)
            .or(g.m1.as_ref().map(|m| &m.collision));
        if let Some(l) = latest {
            let more = [
                l.inside_after.len(),
                l.crossing_after_edges.len(),
                l.pierced_after.len(),
            ];
            body = std::array::from_fn(|k| body[k] + more[k]);
        }
        out.insert(format!("body/{}", w.name), body.into());
        for pair in g.layered.iter().flat_map(|l| &l.pairs) {
            let count = |r: &crate::layers::PushReport| {
                [
                    r.after.behind,
                    r.after.outer_edges_through_inner,
                    r.after.outer_faces_pierced,
                ]
            };
            let m0 = count(&pair.m0);
            let latest = pair.latest.as_ref().map_or([0; 3], count);
            out.insert(
                format!("{}/{}", pair.under, w.name),
                Certificate::from(std::array::from_fn(|k| m0[k] + latest[k])),
            );
        }
    }
    out
}

/// Runs `step` on the garment it works on.
fn run_on_target(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    (session, options): (&Session, &RunOptions),
    step: &Step,
) -> Result<(), StepError> {
    let target = match (&step.op, &step.garment) {
        (Op::Garment { layer, .. }, _) => Target::New {
            name: layer.name.clone(),
            over: layer.over.is_some(),
        },
        (Op::GarmentMesh { name, over, .. }, _) => Target::New {
            name: name.clone(),
            over: over.is_some(),
        },
        (Op::Undo, _) => return undo(scope, state, (session, options)),
        (_, Some(name)) => Target::Worn(worn_index(state, name)?),
        (_, None) if state.worn.is_empty() => Target::None,
        (_, None) => Target::Worn(state.worn.len() - 1),
    };
    match target {
        Target::None => run_step(scope, state, &context(session, options, &[]), &step.op),
        Target::New { name, over } => {
            let under = if over {
                surfaces(state, state.worn.len())?
            } else {
                Vec::new()
            };
            state.garment = None;
            state.history.clear();
            scope.layer = over.then(|| name.clone());
            let ran = run_step(scope, state, &context(session, options, &under), &step.op);
            scope.layer = None;
            ran?;
            if !over {
                state.worn.clear();
            }
            for w in &mut state.worn {
                w.history.clear();
            }
            state.undo.clear();
            state.undo_dropped_past = None;
            state.worn.push(Worn {
                name,
                garment: state.garment.take(),
                history: std::mem::take(&mut state.history),
            });
            Ok(())
        }
        Target::Worn(k) => edit(scope, state, (session, options), step, k),
    }
}

fn context<'a>(session: &'a Session, options: &'a RunOptions, below: &'a [Below]) -> StepContext<'a> {
    StepContext {
        session,
        options,
        below,
    }
}

/// The index of the worn garment `name`.
fn worn_index(state: &SessionState, name: &str) -> Result<usize, StepError> {
    state
        .worn
        .iter()
        .position(|w| w.name == name)
        .ok_or_else(|| StepError::NoSuchGarment {
            name: name.to_string(),
            worn: state
                .worn
                .iter()
                .map(|w| w.name.as_str())
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// The garments under garment `k` as surfaces.
fn surfaces(state: &SessionState, k: usize) -> Result<Vec<Below>, StepError> {
    match (&state.probe, k) {
        (_, 0) | (None, _) => Ok(Vec::new()),
        (Some(probe), _) => Ok(below(&state.worn[..k], probe.index())?),
    }
}

/// Takes garment `k` out for a step (into the state's current slot).
fn checkout(state: &mut SessionState, k: usize) {
    state.garment = state.worn[k].garment.take();
    state.history = std::mem::take(&mut state.worn[k].history);
}

/// Puts the current slot back as garment `k`.
fn checkin(state: &mut SessionState, k: usize) {
    state.worn[k].garment = state.garment.take();
    state.worn[k].history = std::mem::take(&mut state.history);
}

/// What a garment's surface is now (its latest mesh, else its collided M0): whether an edit
/// moved it.
fn surface_of(g: Option<&GarmentState>) -> Option<Vec<glam::DVec3>> {
    let g = g?;
    latest_mesh(g)
        .map(|m| m.positions)
        .or_else(|| g.collision.as_ref().map(|c| c.collision.mesh.positions.clone()))
}

/// Runs an edit on garment `k`, then collides and pushes the garments over it when it
/// moved; refuses the whole edit when one of them cannot be kept in order.
fn edit(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    (session, options): (&Session, &RunOptions),
    step: &Step,
    k: usize,
) -> Result<(), StepError> {
    let under = surfaces(state, k)?;
    // What the garments over it are pushed in front of (none over it: nothing to compare).
    let covered = k + 1 < state.worn.len();
    let before = covered.then(|| surface_of(state.worn[k].garment.as_ref()));
    let undoable = state.worn[k].history.len();
    checkout(state, k);
    scope.layer = (k > 0).then(|| state.worn[k].name.clone());
    let ran = run_step(scope, state, &context(session, options, &under), &step.op);
    scope.layer = None;
    checkin(state, k);
    ran?;
    if state.worn[k].history.len() <= undoable {
        return Ok(());
    }
    let mut changed = vec![k];
    if covered && Some(surface_of(state.worn[k].garment.as_ref())) != before {
        match push_over(scope, state, (session, options), k)? {
            Ok(pushed) => changed.extend(pushed),
            Err(message) => refuse_all(scope, state, (session, options), (k, &message)),
        }
    }
    state.undo.push(changed);
    Ok(())
}

/// Collides every garment over garment `k` again, innermost first, each pushed out in
/// front of those under it. `Ok(Ok(changed))`: the garments changed (their states before
/// are in their histories); `Ok(Err(message))`: one could not be kept in order, and every
/// garment over `k` is as it was.
fn push_over(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    (session, options): (&Session, &RunOptions),
    k: usize,
) -> Result<Result<Vec<usize>, String>, StepError> {
    let mut kept: Vec<(usize, GarmentState)> = Vec::new();
    for j in k + 1..state.worn.len() {
        let under = surfaces(state, j)?;
        let (Some(current), Some(probe)) = (state.worn[j].garment.clone(), state.probe.as_ref()) else {
            continue;
        };
        let mut next = current.clone();
        scope.layer = Some(state.worn[j].name.clone());
        let unmet = collide_and_emit(
            scope,
            &state.body,
            probe.index(),
            &mut next,
            &context(session, options, &under),
        );
        scope.layer = None;
        if let Some(unmet) = unmet {
            let message = format!(
                "'{}' cannot be kept over '{}' after this edit: {}",
                state.worn[j].name,
                state.worn[k].name,
                unmet.message()
            );
            for (j, previous) in kept {
                state.worn[j].garment = Some(previous);
            }
            return Ok(Err(message));
        }
        kept.push((j, current));
        state.worn[j].garment = Some(next);
    }
    let changed = kept.iter().map(|(j, _)| *j).collect();
    for (j, previous) in kept {
        state.worn[j].history.push(previous);
    }
    Ok(Ok(changed))
}

/// Refuses an edit of garment `k` that the garments over it could not follow: `k` back to
/// its state before (which stays in its history: undoing the refused edit changes nothing),
/// every garment from `k` out emitted again as it is, and the refusal recorded.
fn refuse_all(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    (session, options): (&Session, &RunOptions),
    (k, message): (usize, &str),
) {
    let mut previous = state.worn[k].history.last().cloned();
    if let (Some(kept), Some(probe)) = (previous.as_mut(), state.probe.as_ref()) {
        let m1 = session.scene.m1.as_ref();
        let restored = (kept, state.worn[k].garment.as_mut());
        restore_m1(scope, (&state.body, probe.index()), restored, options, m1);
    }
    state.worn[k].garment = previous;
    if let Some(probe) = &state.probe {
        for (j, w) in state.worn.iter().enumerate().skip(k) {
            if let Some(g) = &w.garment {
                scope.layer = (j > 0).then(|| w.name.clone());
                emit_kept(scope, g, probe.index());
            }
        }
    }
    scope.layer = None;
    let outer = state.worn.last().and_then(|w| w.garment.as_ref()?.layered.as_ref());
    match outer {
        Some(layered) => scope.refuse(message, "layers.refused", Stage::Layers(layered)),
        None => scope
            .shortfalls
            .push(super::emit::Shortfall::Refused(message.to_string())),
    }
}

/// `undo`: every garment the last undoable step changed back to its state before it.
fn undo(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    run: (&Session, &RunOptions),
) -> Result<(), StepError> {
    let changed = state.undo.pop().ok_or(match state.undo_dropped_past {
        Some(limit) => StepError::UndoLimit(limit),
        None => StepError::NothingToUndo,
    })?;
    for k in changed {
        checkout(state, k);
        scope.layer = (k > 0).then(|| state.worn[k].name.clone());
        let undone = super::steps::undo_step(scope, state, run);
        scope.layer = None;
        checkin(state, k);
        undone?;
    }
    Ok(())
}
