//! As-rigid-as-possible flattening (Liu et al. 2008, "A local/global approach to mesh
//! parameterization"), with springs on the boundary edges.
//!
//! The energy is `sum_t sum_(i,j) cot_ij |(u_i - u_j) - R_t (x_i - x_j)|^2 / 2` over every
//! triangle `t`, its edges `(i, j)` with the cotangent of the opposite angle and its own
//! plane coordinates `x`, plus `w |(u_i - u_j) - l_ij d_ij|^2 / 2` over the boundary edges
//! (`l_ij` the 3D length, `d_ij` a unit direction). The local step takes each `R_t` as the
//! rotation nearest the triangle's map (for a 2 x 2 matrix `S`, the angle
//! `atan2(S21 - S12, S11 + S22)`) and each `d_ij` as the edge's current direction; the global
//! step solves one fixed sparse system (the cotangent Laplacian plus the springs, one vertex
//! pinned), factored once, for `u` and for `v`. Each step lowers the energy.
//!
//! Seam sides whose lengths are held are added once the free iterations settle: each global
//! step is then moved onto the linearised length constraints ([`hold_lengths`]) and taken
//! only as far as lowers the merit and keeps every upright triangle upright.

use glam::{DMat2, DVec2, DVec3};

use super::sparse::PinnedSystem;
use super::types::{FlattenError, FlattenOptions, Flattening, Frames, boundary_half_edges, signed_area};

/// Runs ARAP from `start`: free until it settles, then, when there are `runs`, with their
/// lengths held (from the free result, whose sides are already near their 3D lengths, so
/// the held steps are small), never turning a triangle over. Each phase takes at most
/// `options.max_iterations`.
pub(crate) fn arap(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    frames: &Frames,
    start: Vec<DVec2>,
    runs: &[Vec<u32>],
    options: &FlattenOptions,
) -> Result<Flattening, FlattenError> {
    let solver = Solver::new(positions, triangles, frames, options)?;
    let free = solver.run(start, &Held::default());
    if runs.is_empty() {
        return Ok(free);
    }
    let held = Held {
        runs,
        targets: runs
            .iter()
            .map(|r| {
                r.windows(2)
                    .map(|w| positions[w[0] as usize].distance(positions[w[1] as usize]))
                    .sum()
            })
            .collect(),
    };
    let mut out = solver.run(free.uv, &held);
    out.iterations += free.iterations;
    Ok(out)
}

/// Seam sides whose lengths are held, with their 3D lengths.
#[derive(Default)]
struct Held<'r> {
    runs: &'r [Vec<u32>],
    targets: Vec<f64>,
}

/// One panel's ARAP: its triangles, the boundary springs and the factored global system.
struct Solver<'a> {
    triangles: &'a [[u32; 3]],
    frames: &'a Frames,
    options: &'a FlattenOptions,
    /// Boundary edges `(i, j, 3D length)`.
    springs: Vec<(usize, usize, f64)>,
    system: PinnedSystem,
}

impl<'a> Solver<'a> {
    fn new(
        positions: &[DVec3],
        triangles: &'a [[u32; 3]],
        frames: &'a Frames,
        options: &'a FlattenOptions,
    ) -> Result<Self, FlattenError> {
        let springs: Vec<(usize, usize, f64)> = boundary_half_edges(triangles)
            .into_iter()
            .map(|[i, j]| {
                let (i, j) = (i as usize, j as usize);
                (i, j, positions[i].distance(positions[j]))
            })
            .collect();
        let w = options.boundary_weight;
        let mut triplets = Vec::with_capacity(triangles.len() * 12 + springs.len() * 4);
        for (t, cot) in triangles.iter().zip(&frames.cot) {
            for (k, &c) in cot.iter().enumerate() {
                let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                triplets.extend([(i, i, c), (j, j, c), (i, j, -c), (j, i, -c)]);
            }
        }
        if w > 0.0 {
            for &(i, j, _) in &springs {
                triplets.extend([(i, i, w), (j, j, w), (i, j, -w), (j, i, -w)]);
            }
        }
        let system = PinnedSystem::factor(positions.len(), &triplets, &[0])?;
        Ok(Self {
            triangles,
            frames,
            options,
            springs,
            system,
        })
    }

    /// Local/global iterations from `uv` until the energy settles, no step lowers the merit,
    /// or the iteration budget is spent.
    fn run(&self, mut uv: Vec<DVec2>, held: &Held<'_>) -> Flattening {
        let (triangles, frames, options) = (self.triangles, self.frames, self.options);
        let n = uv.len();
        let w = options.boundary_weight;
        let mut rotations = vec![DMat2::IDENTITY; triangles.len()];
        let mut directions = vec![DVec2::X; self.springs.len()];
        let mut previous = f64::INFINITY;
        let mut energy = f64::INFINITY;
        let mut iterations = 0;
        let (mut bu, mut bv) = (vec![0.0; n], vec![0.0; n]);
        let (mut u, mut v) = (vec![0.0; n], vec![0.0; n]);
        while iterations < options.max_iterations {
            local_step(triangles, frames, &uv, &mut rotations);
            for (d, &(i, j, _)) in directions.iter_mut().zip(&self.springs) {
                let e = uv[i] - uv[j];
                if e.length_squared() > 0.0 {
                    *d = e.normalize();
                }
            }
            energy =
                arap_energy(triangles, frames, &uv, &rotations) + spring_energy(&self.springs, &directions, &uv, w);
            if (previous - energy).abs() <= options.tolerance * energy {
                break;
            }
            previous = energy;
            bu.fill(0.0);
            bv.fill(0.0);
            for (((t, cot), local), r) in triangles.iter().zip(&frames.cot).zip(&frames.local).zip(&rotations) {
                for (k, &c) in cot.iter().enumerate() {
                    let (a, b) = ((k + 1) % 3, (k + 2) % 3);
                    let (i, j) = (t[a] as usize, t[b] as usize);
                    let e = c * (*r * (local[a] - local[b]));
                    bu[i] += e.x;
                    bv[i] += e.y;
                    bu[j] -= e.x;
                    bv[j] -= e.y;
                }
            }
            if w > 0.0 {
                for (&(i, j, l), d) in self.springs.iter().zip(&directions) {
                    let e = w * l * *d;
                    bu[i] += e.x;
                    bv[i] += e.y;
                    bu[j] -= e.x;
                    bv[j] -= e.y;
                }
            }
            for (k, p) in uv.iter().enumerate() {
                u[k] = p.x;
                v[k] = p.y;
            }
            self.system.solve(&bu, &mut u);
            self.system.solve(&bv, &mut v);
            if held.runs.is_empty() {
                for (k, p) in uv.iter_mut().enumerate() {
                    *p = DVec2::new(u[k], v[k]);
                }
            } else {
                hold_lengths(&self.system, held, &uv, &mut u, &mut v);
                let candidate: Vec<DVec2> = (0..n).map(|k| DVec2::new(u[k], v[k])).collect();
                match self.step_back(&uv, &candidate, held) {
                    Some(next) => uv = next,
                    None => break,
                }
            }
            iterations += 1;
        }
        Flattening { uv, iterations, energy }
    }

    /// The held lengths are linearised about the current directions, so a whole step can
    /// overshoot and the iteration cycle: the step from `uv` to `candidate` is halved until
    /// the merit (the ARAP and spring energies at their best rotations and directions, plus
    /// the squared length errors)
    /// does not rise and no triangle upright at `uv` is turned over; `None` when no such
    /// step is found.
    fn step_back(&self, uv: &[DVec2], candidate: &[DVec2], held: &Held<'_>) -> Option<Vec<DVec2>> {
        let triangles = self.triangles;
        let area = |at: &[DVec2], t: &[u32; 3]| signed_area(at[t[0] as usize], at[t[1] as usize], at[t[2] as usize]);
        let merit = |at: &[DVec2]| -> f64 {
            let mut turns = vec![DMat2::IDENTITY; triangles.len()];
            local_step(triangles, self.frames, at, &mut turns);
            let errors: f64 = held
                .runs
                .iter()
                .zip(&held.targets)
                .map(|(r, l)| {
                    let got: f64 = r
                        .windows(2)
                        .map(|w| at[w[0] as usize].distance(at[w[1] as usize]))
                        .sum();
                    (got - l).powi(2)
                })
                .sum();
            // The springs at their best directions (each edge's own).
            let springs: f64 = self
                .springs
                .iter()
                .map(|&(i, j, l)| 0.5 * self.options.boundary_weight * (at[i].distance(at[j]) - l).powi(2))
                .sum();
            arap_energy(triangles, self.frames, at, &turns) + springs + HELD * errors
        };
        let here = merit(uv);
        let upright: Vec<bool> = triangles.iter().map(|t| area(uv, t) > 0.0).collect();
        let mut step = 1.0;
        for _ in 0..BACKTRACKS {
            let trial: Vec<DVec2> = uv.iter().zip(candidate).map(|(a, b)| *a + step * (*b - *a)).collect();
            let kept = triangles
                .iter()
                .zip(&upright)
                .all(|(t, &up)| !up || area(&trial, t) > 0.0);
            if kept && merit(&trial) <= here {
                return Some(trial);
            }
            step *= 0.5;
        }
        None
    }
}

/// Halvings of a held step before the iteration stops.
const BACKTRACKS: usize = 8;

/// Each triangle's rotation nearest its current map.
fn local_step(triangles: &[[u32; 3]], frames: &Frames, uv: &[DVec2], rotations: &mut [DMat2]) {
    for (((t, cot), local), r) in triangles.iter().zip(&frames.cot).zip(&frames.local).zip(rotations) {
        let mut s = DMat2::ZERO;
        for (k, &c) in cot.iter().enumerate() {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            let du = uv[t[a] as usize] - uv[t[b] as usize];
            let dx = local[a] - local[b];
            // c du dx^T, column by column.
            s += DMat2::from_cols(c * du * dx.x, c * du * dx.y);
        }
        let angle = (s.x_axis.y - s.y_axis.x).atan2(s.x_axis.x + s.y_axis.y);
        *r = DMat2::from_angle(angle);
    }
}

fn arap_energy(triangles: &[[u32; 3]], frames: &Frames, uv: &[DVec2], rotations: &[DMat2]) -> f64 {
    let mut e = 0.0;
    for (((t, cot), local), r) in triangles.iter().zip(&frames.cot).zip(&frames.local).zip(rotations) {
        for (k, &c) in cot.iter().enumerate() {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            let d = (uv[t[a] as usize] - uv[t[b] as usize]) - *r * (local[a] - local[b]);
            e += 0.5 * c * d.length_squared();
        }
    }
    e
}

fn spring_energy(springs: &[(usize, usize, f64)], directions: &[DVec2], uv: &[DVec2], w: f64) -> f64 {
    springs
        .iter()
        .zip(directions)
        .map(|(&(i, j, l), d)| 0.5 * w * ((uv[i] - uv[j]) - l * *d).length_squared())
        .sum()
}

/// Weight of the squared length errors of the held runs in the merit the constrained steps
/// must not raise (against the ARAP energy, whose weights are about 1).
const HELD: f64 = 1e3;

/// Moves the global step's solution `(u, v)` to the nearest point (in the system's own
/// norm) where every run's length measured along its edges' current directions is its 3D
/// length: the linearised constraints `sum_e d_e . (p_i - p_j) = L_k`, one Lagrange
/// multiplier each (`x = x0 + K^-1 C^T lambda`, `C K^-1 C^T lambda = L - C x0`). At
/// convergence the directions are the edges' own and each run's 2D length is its 3D length.
fn hold_lengths(system: &PinnedSystem, held: &Held<'_>, uv: &[DVec2], u: &mut [f64], v: &mut [f64]) {
    let (runs, targets) = (held.runs, &held.targets);
    let n = u.len();
    let m = runs.len();
    // C's rows as (u part, v part), over every unknown (the pinned one's entries unused).
    let rows: Vec<(Vec<f64>, Vec<f64>)> = runs
        .iter()
        .map(|run| {
            let (mut cu, mut cv) = (vec![0.0; n], vec![0.0; n]);
            for w in run.windows(2) {
                let (i, j) = (w[0] as usize, w[1] as usize);
                let d = (uv[i] - uv[j]).normalize_or_zero();
                cu[i] += d.x;
                cu[j] -= d.x;
                cv[i] += d.y;
                cv[j] -= d.y;
            }
            (cu, cv)
        })
        .collect();
    let apply = |(cu, cv): &(Vec<f64>, Vec<f64>), u: &[f64], v: &[f64]| -> f64 {
        cu.iter().zip(u).map(|(a, b)| a * b).sum::<f64>() + cv.iter().zip(v).map(|(a, b)| a * b).sum::<f64>()
    };
    // Y = K^-1 C^T, the pinned unknown held at 0 (it does not move).
    let ys: Vec<(Vec<f64>, Vec<f64>)> = rows
        .iter()
        .map(|(cu, cv)| {
            let (mut yu, mut yv) = (vec![0.0; n], vec![0.0; n]);
            system.solve(cu, &mut yu);
            system.solve(cv, &mut yv);
            (yu, yv)
        })
        .collect();
    let s = nalgebra::DMatrix::from_fn(m, m, |a, b| apply(&rows[a], &ys[b].0, &ys[b].1));
    let r = nalgebra::DVector::from_fn(m, |a, _| targets[a] - apply(&rows[a], u, v));
    let Some(lambda) = s.lu().solve(&r) else {
        return;
    };
    if lambda.iter().any(|x| !x.is_finite()) {
        return;
    }
    for (k, (yu, yv)) in ys.iter().enumerate() {
        for i in 0..n {
            u[i] += lambda[k] * yu[i];
            v[i] += lambda[k] * yv[i];
        }
    }
}
