//! The pattern pieces at the end of every step that collides the garment (garment, set,
//! drag; `undo` emits the kept ones again): cut from M0 after its collision (or from M1),
//! the panels whose mesh did not change keeping their flattening. Runs only when the scene
//! has a `patterns` statement. A pattern that cannot be made (seams that leave a panel that
//! is not a disc) is reported with the step; the garment step itself stands.

use serde::Serialize;

use crate::pattern::{self, CutLine, CutShape, PatternError, PatternInput, PatternOptions, Source};
use crate::session::emit::StepScope;
use crate::session::stage::{PatternStage, Stage};
use crate::session::state::GarmentState;

/// The figures of a step's pattern.
#[derive(Serialize)]
struct PatternFigures {
    /// Pieces, and of those flattened again (not kept from the previous step).
    pattern_pieces: usize,
    pattern_flattened: usize,
    /// Largest and mean (over the pieces' means) edge strain, %.
    pattern_max_strain_pct: f64,
    pattern_mean_strain_pct: f64,
    /// Smallest and largest triangle area ratio 2D / 3D.
    pattern_area_ratio: [f64; 2],
    /// Flipped triangles and boundary self-crossings over all pieces.
    pattern_flipped: usize,
    pattern_overlaps: usize,
    /// Seams, the largest mismatch between the two sides of one (m), and the seams over
    /// their tolerance.
    pattern_seams: usize,
    pattern_worst_mismatch_m: f64,
    pattern_seams_over_tolerance: usize,
}

/// Builds the state's pattern from its collided mesh.
pub(in crate::session) fn build_patterns(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut GarmentState,
    options: &PatternOptions,
) {
    if state.file.is_some() && state.collision.is_some() {
        state.patterns = Some(Err(PatternError::NoSeams(state.name())));
        return;
    }
    let (Some(fw), Some(outcome)) = (&state.framework, &state.collision) else {
        return;
    };
    let curves = fw.curve_polylines();
    let cuts = cut_lines(state);
    // M1 before its collision stands on the collided M0: M0's own vertices (M1's first)
    // taken back to where they were surfaced.
    let m0_surfaced = &outcome.garment.mesh.positions;
    let m1_surfaced: Option<Vec<_>> = state.m1.as_ref().map(|m1| {
        let mut p = m1.m1.mesh.positions.clone();
        let n = m0_surfaced.len().min(p.len());
        p[..n].copy_from_slice(&m0_surfaced[..n]);
        p
    });
    let input = match (options.source, &state.m1) {
        (Source::M1, Some(m1)) => PatternInput {
            template: fw.template.name(),
            positions: &m1.collision.positions,
            triangles: &m1.m1.mesh.triangles,
            face_patch: &m1.m1.face_patch,
            surfaced: m1_surfaced.as_deref(),
            patch_names: &fw.m0.patch_names,
            curves: &curves,
            cuts: &cuts,
        },
        _ => PatternInput {
            template: fw.template.name(),
            positions: &outcome.collision.mesh.positions,
            triangles: &outcome.garment.mesh.triangles,
            face_patch: &outcome.garment.face_patch,
            surfaced: Some(m0_surfaced),
            patch_names: &fw.m0.patch_names,
            curves: &curves,
            cuts: &cuts,
        },
    };
    let previous = state.patterns.as_ref().and_then(|p| p.as_ref().ok());
    let built = scope.timed("patterns", || pattern::build(&input, options, previous));
    if let Ok(p) = &built {
        let pieces = &p.pieces;
        let area = pieces.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |a, q| {
            [
                a[0].min(q.distortion.area_ratio[0]),
                a[1].max(q.distortion.area_ratio[1]),
            ]
        });
        scope.record(&PatternFigures {
            pattern_pieces: pieces.len(),
            pattern_flattened: p.flattened(),
            pattern_max_strain_pct: 100.0 * pieces.iter().map(|q| q.distortion.max_strain).fold(0.0, f64::max),
            pattern_mean_strain_pct: 100.0 * pieces.iter().map(|q| q.distortion.mean_strain).sum::<f64>()
                / pieces.len().max(1) as f64,
            pattern_area_ratio: area,
            pattern_flipped: pieces.iter().map(|q| q.distortion.flipped).sum(),
            pattern_overlaps: pieces.iter().map(|q| q.distortion.overlaps).sum(),
            pattern_seams: p.seams.len(),
            pattern_worst_mismatch_m: p.seams.iter().map(|s| s.mismatch).fold(0.0, f64::max),
            pattern_seams_over_tolerance: p.seams.iter().filter(|s| !s.sews()).count(),
        });
    }
    if let Err(e) = &built {
        scope.note(format!("no pattern: {e}"));
    }
    state.patterns = Some(built);
}

/// The state's cut lines as pattern seams: the plane cuts, and the cuts through picked
/// points (M0's vertex indices, which M1 keeps).
fn cut_lines(state: &GarmentState) -> Vec<CutLine> {
    let planes = state.cuts.iter().map(|c| CutLine {
        name: c.name.clone(),
        shape: CutShape::Plane {
            point: c.plane.point,
            normal: c.plane.normal,
        },
    });
    let through = state.through_cuts.iter().map(|(name, vertices)| CutLine {
        name: name.clone(),
        shape: CutShape::Through(vertices.clone()),
    });
    planes.chain(through).collect()
}

/// Emits the state's pattern, if it has one.
pub(in crate::session) fn emit_patterns(scope: &mut StepScope<'_, '_, '_>, state: &GarmentState) {
    if let (Some(result), Some(outcome)) = (&state.patterns, &state.collision) {
        scope.emit(
            "garment.patterns",
            Stage::Patterns(PatternStage {
                result,
                garment: &outcome.name,
            }),
        );
    }
}
