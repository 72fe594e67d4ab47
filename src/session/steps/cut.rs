//! `cut NAME at=x,y,z normal=nx,ny,nz`: a style line drawn on the current M1 as its section
//! by a plane, stored on M0 (barycentric coordinates, \[collide\] figure 6) so that every
//! later step rebuilds it on its new M1. `cut NAME through=P;Q;...`: a cut line through
//! picked points of the garment. Both are seams of the pattern (when the scene has one).
//! Undoable. A plane that misses the garment, or a point off it, is refused; the session
//! goes on.

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
    cx: &crate::session::options::StepContext<'_>,
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
    if points == 0 {
        // Refused: the garment stays, and an undo of this step changes nothing.
        state.history.push(next);
        refuse(
            scope,
            name,
            &format!(
                "the plane through ({:.4}, {:.4}, {:.4}) m misses the garment",
                plane.point.x, plane.point.y, plane.point.z
            ),
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
    // The cut line is a seam of the pattern from now on.
    patterns_again(scope, cx, &mut next);
    state.advance(next);
    Ok(())
}

/// `cut NAME through=P;Q;...`: a cut line through picked points, each taken to the
/// garment's nearest vertex (so that it follows the garment through later edits), a seam of
/// the pattern from now on. Undoable. A point farther from the garment than the longest edge
/// at its nearest vertex, or two points on one vertex, refuse the cut; the session goes on.
pub(super) fn through(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &crate::session::options::StepContext<'_>,
    name: &str,
    points: &[glam::DVec3],
) -> Result<(), StepError> {
    let Some(current) = &state.garment else {
        return Err(StepError::NoGarment { verb: "cut" });
    };
    let Some(collided) = &current.collision else {
        return Err(StepError::NoGarment { verb: "cut" });
    };
    let mesh = &collided.collision.mesh;
    let edges = crate::mesh::topology::incident_edge_extremes(&mesh.positions, &mesh.triangles);
    let mut vertices: Vec<u32> = Vec::with_capacity(points.len());
    let mut problem = None;
    for p in points {
        let nearest = (0..mesh.positions.len()).min_by(|&a, &b| {
            mesh.positions[a]
                .distance_squared(*p)
                .total_cmp(&mesh.positions[b].distance_squared(*p))
                .then(a.cmp(&b))
        });
        let Some(v) = nearest else { break };
        let d = mesh.positions[v].distance(*p);
        if d > edges[v][1] {
            problem = Some(format!(
                "the point ({:.4}, {:.4}, {:.4}) m is {:.1} mm from the garment",
                p.x,
                p.y,
                p.z,
                1e3 * d
            ));
            break;
        }
        if vertices.last() == Some(&(v as u32)) {
            problem = Some(format!(
                "the points before and at ({:.4}, {:.4}, {:.4}) m fall on one vertex of the garment",
                p.x, p.y, p.z
            ));
            break;
        }
        vertices.push(v as u32);
    }
    let mut next = current.clone();
    if let Some(why) = problem {
        // Refused: the garment stays, and an undo of this step changes nothing.
        state.history.push(next);
        refuse(scope, name, &why);
        return Ok(());
    }
    next.through_cuts.push((name.to_string(), vertices));
    patterns_again(scope, cx, &mut next);
    state.advance(next);
    Ok(())
}

/// Refuses a cut named `name` because of `why`: logged and counted, the garment kept.
fn refuse(scope: &mut StepScope<'_, '_, '_>, name: &str, why: &str) {
    let message = format!("cut '{name}': {why}: edit refused");
    scope.refuse(
        &message,
        "garment.refused",
        Stage::Garment(GarmentStage::CutRefused {
            name,
            message: &message,
        }),
    );
}

/// The garment's pattern made again with its new cut line, when the scene has one.
fn patterns_again(
    scope: &mut StepScope<'_, '_, '_>,
    cx: &crate::session::options::StepContext<'_>,
    next: &mut crate::session::state::GarmentState,
) {
    if let Some(options) = &cx.session.scene.patterns {
        crate::session::flow::patterns::build_patterns(scope, next, options);
        crate::session::flow::patterns::emit_patterns(scope, next);
    }
}
