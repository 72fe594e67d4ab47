//! `mannequin`: the \[spline\] study. The analytic dress form is sampled as a ring grid,
//! refined by polar and by chord-length cubic splines, and both are measured against the
//! true surface, region by region.

use serde::Serialize;

use crate::mannequin::{DressForm, MannequinOptions, Region, RegionErrors, run_mannequin};
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::stage::Stage;

/// The figures of a mannequin step.
#[derive(Serialize)]
struct MannequinFigures<'a> {
    /// Measured layers (rings).
    layers: usize,
    /// Measured points per layer.
    points: usize,
    /// Layers of the refined grids.
    dense_layers: usize,
    /// Points per layer of the refined grids.
    dense_points: usize,
    /// Max and RMS deviation (m) of both methods per region, hip to neck.
    regions: Vec<&'a RegionErrors>,
}

pub(super) fn run(scope: &mut StepScope<'_, '_, '_>, options: &MannequinOptions) -> Result<(), StepError> {
    let form = DressForm::default();
    let result = scope.timed("mannequin.refine", || run_mannequin(&form, options))?;
    scope.record(&MannequinFigures {
        layers: options.layers,
        points: options.points,
        dense_layers: result.polar.layers,
        dense_points: result.polar.points,
        regions: Region::REPORT_ORDER
            .iter()
            .filter_map(|r| result.regions.iter().find(|e| e.region == r.name()))
            .collect(),
    });
    scope.emit("mannequin.refine", Stage::Mannequin(&result));
    Ok(())
}
