//! The same drag three ways ([sculpt]'s comparison): no subdivision (the dragged mesh as
//! it is: stretched faces, slivers), uniform Loop subdivision of the whole mesh until the
//! region's longest edge is at most epsilon, and adaptive Loop subdivision to the same
//! epsilon (and once more to the longest edge uniform Loop reached). Each is measured by [`measure`] over the faces that descend from the region.

use std::time::Instant;

use super::adaptive::{Level, refine};
use super::drag::{Displacement, Drag};
use super::loop_rules::uniform_step;
use super::make::{longest_edge, prepare};
use super::measure::{Measures, measure};
use super::options::{SculptError, SculptOptions};
use crate::mesh::TriMesh;

/// One way of refining the drag.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// Its figures.
    pub measures: Measures,
    /// Subdivision levels run.
    pub levels: usize,
    /// Stopped at the level limit above epsilon.
    pub limited: bool,
    /// Time for the drag and the refinement, ms (wall clock: printed, never logged).
    pub time_ms: f64,
    /// The mesh.
    pub mesh: TriMesh,
    /// Per face: descends from the region.
    pub region: Vec<bool>,
}

/// The three variants of one drag.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// The drag.
    pub drag: Drag,
    /// The drag on the input.
    pub displacement: Displacement,
    /// Epsilon, m.
    pub epsilon: f64,
    /// No subdivision.
    pub none: Variant,
    /// Uniform Loop.
    pub uniform: Variant,
    /// Adaptive Loop.
    pub adaptive: Variant,
    /// Adaptive Loop with epsilon set to the longest edge uniform Loop reached (uniform
    /// refines in halvings, so it usually ends well below epsilon): the two at the same
    /// longest edge.
    pub adaptive_matched: Variant,
    /// The adaptive levels (active faces per level).
    pub adaptive_levels: Vec<Level>,
}

impl Comparison {
    /// How far apart the three results are drawn: 1.2 times the input's width along x.
    pub fn spacing(&self) -> f64 {
        self.none
            .mesh
            .bounds()
            .map_or(1.0, |(lo, hi)| 1.2 * (hi.x - lo.x).max(1e-3))
    }
}

fn variant(mesh: TriMesh, region: Vec<bool>, levels: usize, limited: bool, time_ms: f64) -> Variant {
    Variant {
        measures: measure(&mesh, &region),
        levels,
        limited,
        time_ms,
        mesh,
        region,
    }
}

fn ms_since(started: Instant) -> f64 {
    started.elapsed().as_secs_f64() * 1e3
}

/// Runs `drag` on `mesh` with no, uniform and adaptive subdivision. The drag is made once;
/// its time is part of every variant's.
///
/// # Errors
/// As [`super::sculpt`].
pub fn compare(mesh: &TriMesh, drag: &Drag, options: &SculptOptions) -> Result<Comparison, SculptError> {
    let started = Instant::now();
    let (displacement, region, epsilon) = prepare(mesh, drag, options, None)?;
    let dragged = TriMesh {
        positions: displacement.positions.clone(),
        triangles: mesh.triangles.clone(),
    };
    let drag_ms = ms_since(started);
    let none = variant(dragged.clone(), region.clone(), 0, false, drag_ms);

    let started = Instant::now();
    let region_longest = |m: &TriMesh, flags: &[bool]| longest_edge(m, (0..flags.len()).filter(|&t| flags[t]));
    let (mut current, mut flags) = (dragged.clone(), region.clone());
    let mut levels = 0;
    while region_longest(&current, &flags) > epsilon && levels < options.max_levels {
        let step = uniform_step(&current, options.weight);
        flags = step.parent.iter().map(|&p| flags[p as usize]).collect();
        current = step.mesh;
        levels += 1;
    }
    let limited = region_longest(&current, &flags) > epsilon;
    let uniform = variant(current, flags, levels, limited, drag_ms + ms_since(started));

    let adaptive_to = |epsilon: f64| -> (Variant, Vec<Level>) {
        let started = Instant::now();
        let refined = refine(&dragged, &region, &options.adaptive(epsilon));
        let time_ms = drag_ms + ms_since(started);
        let levels = refined.levels.len();
        (
            variant(refined.mesh, refined.region, levels, refined.limited, time_ms),
            refined.levels,
        )
    };
    let (adaptive, adaptive_levels) = adaptive_to(epsilon);
    let (adaptive_matched, _) = adaptive_to(uniform.measures.max_edge_m);
    Ok(Comparison {
        drag: *drag,
        displacement,
        epsilon,
        none,
        uniform,
        adaptive,
        adaptive_matched,
        adaptive_levels,
    })
}
