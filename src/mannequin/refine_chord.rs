//! Parametric cubic-spline refinement on accumulated chord length (\[spline\] section 4).
//!
//! Per layer, `x(l)`, `y(l)`, `z(l)` through the ring's points with periodic ends; per
//! meridian, the same through the refined layers' columns with end tangents from the
//! first and last chords. Each interval is split `k` ways in its parameter.

use glam::DVec3;

use super::{MannequinError, RingGrid};
use crate::geom::{ChordSpline3, CurveEnds};

/// Refines a measured grid, splitting every interval `k` ways.
pub fn refine(grid: &RingGrid, k: usize) -> Result<RingGrid, MannequinError> {
    let (layers, points) = (grid.layers, grid.points);
    let dense_points = points * k;
    let spline_error = |curve: String| {
        move |source| MannequinError::Spline {
            method: "chord",
            curve,
            source,
        }
    };
    let mut rows: Vec<Vec<DVec3>> = Vec::with_capacity(layers);
    for i in 0..layers {
        let ring: Vec<DVec3> = (0..points).map(|j| grid.at(i, j)).collect();
        let spline = ChordSpline3::try_new(&ring, CurveEnds::Closed).map_err(spline_error(format!("layer {i}")))?;
        rows.push(spline.subdivide(k, true));
    }
    let dense_layers = (layers - 1) * k + 1;
    let mut positions = vec![DVec3::ZERO; dense_layers * dense_points];
    for c in 0..dense_points {
        let column: Vec<DVec3> = rows.iter().map(|r| r[c]).collect();
        let n = column.len() - 1;
        let ends = CurveEnds::Open {
            start: Some(column[1] - column[0]),
            end: Some(column[n] - column[n - 1]),
        };
        let spline = ChordSpline3::try_new(&column, ends).map_err(spline_error(format!("meridian {c}")))?;
        for (i, p) in spline.subdivide(k, false).into_iter().enumerate() {
            positions[i * dense_points + c] = p;
        }
    }
    Ok(RingGrid {
        layers: dense_layers,
        points: dense_points,
        positions,
    })
}
