//! The study: the dress form sampled, refined both ways and measured against its true
//! surface, per region.

use super::deviation::{ErrorStats, TrueSurface};
use super::dress_form::{DressForm, Region};
use super::{MannequinError, MannequinOptions, RingGrid, refine_chord, refine_polar};

/// Deviation of both methods in one region.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct RegionErrors {
    /// Region name.
    pub region: &'static str,
    /// Polar method.
    pub polar: ErrorStats,
    /// Chord-length method.
    pub chord: ErrorStats,
}

impl RegionErrors {
    /// `[polar max, polar rms, chord max, chord rms]` in millimetres.
    pub fn millimetres(&self) -> [f64; 4] {
        [self.polar.max_m, self.polar.rms_m, self.chord.max_m, self.chord.rms_m].map(|m| m * 1e3)
    }
}

/// Everything the mannequin step produces.
#[derive(Clone, Debug)]
pub struct MannequinResult {
    /// Settings used.
    pub options: MannequinOptions,
    /// The measured grid.
    pub measured: RingGrid,
    /// Polar refinement.
    pub polar: RingGrid,
    /// Chord-length refinement.
    pub chord: RingGrid,
    /// Distance of each polar point to the true surface, m.
    pub polar_error: Vec<f64>,
    /// Distance of each chord point to the true surface, m.
    pub chord_error: Vec<f64>,
    /// The true surface, finely tessellated (for display).
    pub truth: RingGrid,
    /// Per-region statistics, bottom (hip) to top (neck).
    pub regions: Vec<RegionErrors>,
}

/// Samples the dress form, refines it both ways and measures both against the truth.
pub fn run_mannequin(form: &DressForm, options: &MannequinOptions) -> Result<MannequinResult, MannequinError> {
    if options.layers < 4 || options.points < 6 {
        return Err(MannequinError::TooCoarse {
            layers: options.layers,
            points: options.points,
        });
    }
    let measured = form.measure(options.layers, options.points);
    let k = options.subdivisions.max(1);
    let polar = refine_polar::refine(&measured, k)?;
    let chord = refine_chord::refine(&measured, k)?;
    let truth = TrueSurface::new(form);
    let (polar_error, polar_region) = truth.deviations(&polar.positions);
    let (chord_error, chord_region) = truth.deviations(&chord.positions);
    let regions = Region::ALL
        .iter()
        .map(|&r| RegionErrors {
            region: r.name(),
            polar: ErrorStats::of(
                polar_error
                    .iter()
                    .zip(&polar_region)
                    .filter(|(_, g)| **g == r)
                    .map(|(e, _)| *e),
            ),
            chord: ErrorStats::of(
                chord_error
                    .iter()
                    .zip(&chord_region)
                    .filter(|(_, g)| **g == r)
                    .map(|(e, _)| *e),
            ),
        })
        .collect();
    Ok(MannequinResult {
        options: options.clone(),
        measured,
        polar,
        chord,
        polar_error,
        chord_error,
        truth: form.measure(120, 96),
        regions,
    })
}
