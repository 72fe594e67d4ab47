//! `cut NAME at=x,y,z normal=nx,ny,nz`: a style line drawn on the current M1 as its section
//! by a plane, stored on M0 (barycentric coordinates, \[collide\] figure 6) so that every
//! later step rebuilds it on its new M1. Undoable. A plane that misses the garment is
//! refused; the session goes on.

use serde::Serialize;

use crate::m1::{CutPlane, cut};
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::stage::{GarmentStage, M1Stage, Stage};
use crate::session::state::SessionState;

/// The figures of a cut.
#[derive(Serialize)]
struct CutFigures {
    /// Pieces of the line (closed loops and open runs between openings).
    cut_pieces: usize,
    /// Points stored on M0.
    cut_points: usize,
    /// Of those, on flipped edges (stored through the plane construction).
    cut_points_flipped: usize,
}

pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    name: &str,
    plane: CutPlane,
) -> Result<(), StepError> {
    let Some(current) = &state.garment else {
        return Err(StepError::NoGarment { verb: "cut" });
    };
    let (Some(outcome), Some(collided)) = (&current.m1, &current.collision) else {
        return Err(StepError::NoGarment { verb: "cut" });
    };
    let m0 = &collided.collision.mesh.triangles;
    let positions = &outcome.collision.positions;
    let drawn = cut::draw(&outcome.m1, positions, &plane);
    let stored = cut::store(&outcome.m1, m0, positions, name, plane, &drawn);
    let points: usize = stored.pieces.iter().map(|(p, _)| p.len()).sum();
    let mut next = current.clone();
    state.history.push(current.clone());
    if points == 0 {
        let message = format!(
            "cut '{name}': the plane through ({:.4}, {:.4}, {:.4}) m misses the garment: edit refused",
            plane.point.x, plane.point.y, plane.point.z
        );
        scope.refuse(
            &message,
            "garment.refused",
            Stage::Garment(GarmentStage::CutRefused {
                name,
                message: &message,
            }),
        );
        return Ok(());
    }
    scope.record(&CutFigures {
        cut_pieces: stored.pieces.len(),
        cut_points: points,
        cut_points_flipped: stored
            .pieces
            .iter()
            .flat_map(|(p, _)| p)
            .filter(|p| matches!(p, cut::StoredPoint::Flipped { .. }))
            .count(),
    });
    next.cuts.push(stored);
    if let Some(m1) = &mut next.m1 {
        m1.stored = next.cuts.clone();
        m1.cuts = next
            .cuts
            .iter()
            .map(|c| cut::rebuild(Some(&m1.m1), m0, &m1.collision.positions, c))
            .collect();
        m1.cuts_on_m0 = next
            .cuts
            .iter()
            .map(|c| cut::rebuild(None, m0, &collided.collision.mesh.positions, c))
            .collect();
    }
    if let (Some(outcome), Some(m0)) = (&next.m1, &next.collision) {
        scope.emit("garment.cut", Stage::M1(M1Stage { outcome, m0 }));
    }
    state.garment = Some(next);
    Ok(())
}
