//! Polar cubic-spline refinement (\[spline\] section 3).
//!
//! Per layer, the ring is written as radius against polar angle about the vertical axis,
//! `rho(psi)`, interpolated by a periodic cubic spline; heights vary linearly in `psi`.
//! Per meridian (a column of the refined layers), `rho(y)` is a cubic spline in height
//! with end slopes from the one-sided differences, and the angle varies linearly in `y`.
//! Each interval is split `k` ways. The method needs star-shaped rings and heights that
//! increase up every meridian; where the surface runs nearly horizontal (the shoulder
//! slope) `rho(y)` is steep and the method distorts, which is what the paper reports.

use glam::DVec3;

use super::{MannequinError, RingGrid};
use crate::geom::{CubicSpline, EndCondition};

/// `psi` grows as the rings run (front, left, back, right): `psi = -atan2(z, x)`.
fn polar(p: DVec3) -> (f64, f64) {
    (-p.z.atan2(p.x), p.x.hypot(p.z))
}

fn spline_error(curve: String) -> impl FnOnce(crate::geom::SplineError) -> MannequinError {
    move |source| MannequinError::Spline {
        method: "polar",
        curve,
        source,
    }
}

/// Refines a measured grid, splitting every interval `k` ways.
pub fn refine(grid: &RingGrid, k: usize) -> Result<RingGrid, MannequinError> {
    let (layers, points) = (grid.layers, grid.points);
    let dense_points = points * k;
    // Layer pass: (y, rho, psi) for every refined point of every measured layer.
    let mut rows: Vec<Vec<(f64, f64, f64)>> = Vec::with_capacity(layers);
    for i in 0..layers {
        let mut psi: Vec<f64> = Vec::with_capacity(points + 1);
        let mut rho = Vec::with_capacity(points + 1);
        let mut ys = Vec::with_capacity(points + 1);
        for j in 0..points {
            let p = grid.at(i, j);
            let (a, r) = polar(p);
            let a = match psi.last() {
                None => a,
                Some(&prev) => {
                    let step = (a - prev).rem_euclid(std::f64::consts::TAU);
                    if step <= 0.0 || step >= std::f64::consts::PI {
                        return Err(MannequinError::NotStarShaped { layer: i, point: j });
                    }
                    prev + step
                }
            };
            psi.push(a);
            rho.push(r);
            ys.push(p.y);
        }
        let closing = psi[0] + std::f64::consts::TAU;
        if closing <= psi[points - 1] {
            return Err(MannequinError::NotStarShaped { layer: i, point: 0 });
        }
        psi.push(closing);
        rho.push(rho[0]);
        ys.push(ys[0]);
        let spline =
            CubicSpline::try_new(&psi, &rho, EndCondition::Periodic).map_err(spline_error(format!("layer {i}")))?;
        let mut row = Vec::with_capacity(dense_points);
        for j in 0..points {
            for m in 0..k {
                let f = m as f64 / k as f64;
                let a = psi[j] + (psi[j + 1] - psi[j]) * f;
                row.push((ys[j] + (ys[j + 1] - ys[j]) * f, spline.sample(a), a));
            }
        }
        rows.push(row);
    }
    // Meridian pass: rho(y) per column.
    let dense_layers = (layers - 1) * k + 1;
    let mut positions = vec![DVec3::ZERO; dense_layers * dense_points];
    for c in 0..dense_points {
        let ys: Vec<f64> = rows.iter().map(|r| r[c].0).collect();
        let rhos: Vec<f64> = rows.iter().map(|r| r[c].1).collect();
        let psis: Vec<f64> = rows.iter().map(|r| r[c].2).collect();
        if let Some(i) = ys.windows(2).position(|w| w[1] <= w[0]) {
            return Err(MannequinError::NotMonotone {
                meridian: c,
                layer: i + 1,
            });
        }
        let n = layers - 1;
        let start_slope = (rhos[1] - rhos[0]) / (ys[1] - ys[0]);
        let end_slope = (rhos[n] - rhos[n - 1]) / (ys[n] - ys[n - 1]);
        let spline = CubicSpline::try_new(&ys, &rhos, EndCondition::Clamped { start_slope, end_slope })
            .map_err(spline_error(format!("meridian {c}")))?;
        for i in 0..dense_layers {
            let (seg, m) = ((i / k).min(n - 1), i - (i / k).min(n - 1) * k);
            let f = m as f64 / k as f64;
            let y = ys[seg] + (ys[seg + 1] - ys[seg]) * f;
            let a = psis[seg] + (psis[seg + 1] - psis[seg]) * f;
            let r = spline.sample(y);
            positions[i * dense_points + c] = DVec3::new(r * a.cos(), y, -r * a.sin());
        }
    }
    Ok(RingGrid {
        layers: dense_layers,
        points: dense_points,
        positions,
    })
}
