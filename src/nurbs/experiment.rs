//! The paper's L/T experiment: a butterfly held very near a corn leaf, collided at levels
//! `L = 3..8` with the control-point distance test, with the true surface distance beside
//! each figure so that its error is known; a second pose pushes the butterfly through the
//! leaf, which must be detected at every level; and the level and threshold recommended for
//! a wanted accuracy.

use std::time::Instant;

use glam::{DMat3, DVec3};
use serde::Serialize;

use super::distance::{coverage, nearest_among, nearest_control_points, net_deviation, pairs_within, surface_distance};
use super::file::{NurbsFileError, parse};
use super::hull::Kdop;
use super::surface::NurbsSurface;
use super::tree::PatchTree;

/// The shipped butterfly (`assets/nurbs/butterfly.nurbs`).
pub const BUTTERFLY: &str = include_str!("../../assets/nurbs/butterfly.nurbs");
/// The shipped corn leaf (`assets/nurbs/corn-leaf.nurbs`).
pub const CORN_LEAF: &str = include_str!("../../assets/nurbs/corn-leaf.nurbs");

/// The shipped butterfly and corn leaf.
pub fn shipped_pair() -> Result<(NurbsSurface, NurbsSurface), NurbsFileError> {
    Ok((parse(BUTTERFLY)?.surface, parse(CORN_LEAF)?.surface))
}

/// Where the butterfly sits on the leaf: at the leaf's parameters `at`, its body along the
/// leaf turned by `yaw_deg` about the leaf's upward normal and rolled by `roll_deg` about
/// its own body, lifted by `gap` along the normal (negative: pushed through).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Placement {
    /// Leaf parameters `(u, v)`.
    pub at: [f64; 2],
    /// Lift along the leaf's normal, m.
    pub gap: f64,
    /// Turn about the leaf's normal, degrees.
    pub yaw_deg: f64,
    /// Roll about the butterfly's body axis, degrees.
    pub roll_deg: f64,
}

/// The butterfly moved rigidly onto the leaf as `placement` says.
pub fn place(butterfly: &NurbsSurface, leaf: &NurbsSurface, placement: Placement) -> NurbsSurface {
    let j = leaf.jet(placement.at[0], placement.at[1]);
    let along = j.dv.normalize();
    let mut up = j.du.cross(j.dv).normalize();
    if up.y < 0.0 {
        up = -up;
    }
    let across = up.cross(along);
    let frame = DMat3::from_cols(across, up, along);
    let turn = DMat3::from_rotation_y(placement.yaw_deg.to_radians())
        * DMat3::from_rotation_z(placement.roll_deg.to_radians());
    butterfly.mapped(frame * turn, j.point + up * placement.gap)
}

/// Experiment settings.
#[derive(Clone, Debug, PartialEq)]
pub struct ExperimentOptions {
    /// Levels to run (default 3..=8, the paper's).
    pub levels: std::ops::RangeInclusive<u8>,
    /// The accuracy wanted of the distance test, m (default 0.5 mm): the recommended level
    /// is the least whose control-point distance is within it of the true distance.
    pub accuracy_m: f64,
    /// Where and how the butterfly sits (default: off the midrib, 43% along the blade,
    /// turned 25 degrees and rolled 30, so that the nearest points lie off the subdivision
    /// lines); its `gap` is found, see `near_distance_m`.
    pub pose: Placement,
    /// The near pose is lifted until the true distance is this, m (default 1 mm).
    pub near_distance_m: f64,
    /// The crossing pose is the near pose pushed along the leaf's normal by the near
    /// distance and this much more, m (default 2 mm).
    pub crossing_depth_m: f64,
    /// Least wall time over which each level's detection is repeated and the median
    /// taken, ms (default 200).
    pub timing_ms: f64,
    /// Samples per side of each leaf for [`coverage`] (default 5).
    pub coverage_samples: usize,
    /// Most leaf hulls kept per surface and level for the picture (default 600).
    pub hulls_kept: usize,
}

impl Default for ExperimentOptions {
    fn default() -> Self {
        Self {
            levels: 3..=8,
            accuracy_m: 0.5e-3,
            pose: Placement {
                at: [0.6, 0.43],
                gap: 0.0,
                yaw_deg: 25.0,
                roll_deg: 30.0,
            },
            near_distance_m: 1e-3,
            crossing_depth_m: 2e-3,
            timing_ms: 200.0,
            coverage_samples: 5,
            hulls_kept: 600,
        }
    }
}

/// One level of the near pose.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LevelRow {
    /// Subdivision level.
    pub level: u8,
    /// Detection from the surfaces: both subdivided, then the control-point distance
    /// (median of repeats), ms.
    pub time_ms: f64,
    /// The control-point distance on trees already built (median of repeats), ms.
    pub query_ms: f64,
    /// Hull pairs tested by the control-point search.
    pub pairs_tested: u64,
    /// Leaf pairs whose control points were compared.
    pub leaf_pairs: u64,
    /// The paper's figure: the least distance between control points, m.
    pub cp_min_distance_m: f64,
    /// The true least distance between the surfaces, m.
    pub true_distance_m: f64,
    /// `cp_min_distance_m - true_distance_m`, m.
    pub error_m: f64,
    /// How far the control points stand off each surface (butterfly, leaf), m; bounds how
    /// far the control-point distance can fall below the true one.
    pub net_deviation_m: [f64; 2],
    /// How far a surface point can be from its leaf's control points (butterfly, leaf), m;
    /// bounds how far the control-point distance can exceed the true one.
    pub coverage_m: [f64; 2],
    /// Leaf pairs refined by Newton for the true distance.
    pub refined_pairs: u64,
    /// Where the true distance is: `(u, v)` on the butterfly, then on the leaf.
    pub true_params: [f64; 4],
}

/// One level of the crossing pose.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CrossingRow {
    /// Subdivision level.
    pub level: u8,
    /// drape's verdict: a leaf pair within the threshold whose refined distance is below it.
    pub detected: bool,
    /// The paper's verdict: a leaf pair within the threshold whose control points are
    /// nearer than it.
    pub paper_rule: bool,
    /// Leaf pairs whose hulls come within the threshold.
    pub candidate_pairs: usize,
    /// Least control-point distance among them, m (infinite when there are none).
    pub cp_min_distance_m: f64,
    /// Least refined distance among them (the true distance when they are near), m.
    pub true_distance_m: f64,
}

/// The recommendation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Recommendation {
    /// The least level whose control-point distance is within the accuracy of the truth
    /// (the deepest level run when none is).
    pub level: u8,
    /// The collision threshold: the error at that level with the paper's margin (its
    /// T = 0.0006 over an error of 0.0004, so 1.5 times), m.
    pub threshold_m: f64,
    /// The accuracy asked for, m.
    pub accuracy_m: f64,
    /// Whether some level met it.
    pub met: bool,
}

/// What the picture needs of one level.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelPicture {
    /// Subdivision level.
    pub level: u8,
    /// The near pose: hulls (butterfly, leaf) of the leaf pairs whose hulls come within the
    /// control-point distance (the pairs an exact search must open).
    pub near_hulls: [Vec<Kdop>; 2],
    /// The crossing pose: hulls of the leaf pairs within the threshold.
    pub crossing_hulls: [Vec<Kdop>; 2],
    /// The nearest control points.
    pub cp_points: [DVec3; 2],
    /// The true nearest surface points.
    pub true_points: [DVec3; 2],
}

/// The whole experiment.
#[derive(Clone, Debug, PartialEq)]
pub struct Experiment {
    /// The near pose.
    pub near_pose: Placement,
    /// The crossing pose.
    pub crossing_pose: Placement,
    /// The butterfly in the near pose.
    pub near: NurbsSurface,
    /// The butterfly in the crossing pose.
    pub crossing_butterfly: NurbsSurface,
    /// The leaf.
    pub leaf: NurbsSurface,
    /// The near pose per level.
    pub levels: Vec<LevelRow>,
    /// The crossing pose per level.
    pub crossing: Vec<CrossingRow>,
    /// The recommendation.
    pub recommended: Recommendation,
    /// Per level, for the picture.
    pub pictures: Vec<LevelPicture>,
}

/// The median wall time of `f` in ms, repeated until `budget_ms` have passed (at least 3
/// and at most 1000 times).
fn median_ms<R>(budget_ms: f64, mut f: impl FnMut() -> R) -> f64 {
    let mut times = Vec::new();
    let start = Instant::now();
    while times.len() < 3 || (times.len() < 1000 && start.elapsed().as_secs_f64() * 1e3 < budget_ms) {
        let t = Instant::now();
        std::hint::black_box(f());
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// The distinct leaf hulls of `pairs` on each side, the first `keep` of each.
fn hulls_of(a: &PatchTree, b: &PatchTree, pairs: &[[u32; 2]], keep: usize) -> [Vec<Kdop>; 2] {
    let pick = |t: &PatchTree, side: usize| {
        let mut ids: Vec<u32> = pairs.iter().map(|p| p[side]).collect();
        ids.sort_unstable();
        ids.dedup();
        ids.truncate(keep);
        ids.iter()
            .map(|&i| Kdop::from_points(t.patches[i as usize].points.iter().copied()))
            .collect()
    };
    [pick(a, 0), pick(b, 1)]
}

/// The verdicts for the threshold `threshold` at one level.
fn crossing_row(level: u8, a: &PatchTree, b: &PatchTree, threshold: f64) -> (CrossingRow, Vec<[u32; 2]>) {
    let (pairs, _) = pairs_within(a, b, threshold);
    let cp = pairs.iter().map(|p| p.control_distance).fold(f64::INFINITY, f64::min);
    // Refined on to touching (not just below the threshold), so that the figure is the
    // true distance.
    let best = nearest_among(a, b, &pairs).map_or(f64::INFINITY, |r| r.distance);
    let row = CrossingRow {
        level,
        detected: best < threshold,
        paper_rule: cp < threshold,
        candidate_pairs: pairs.len(),
        cp_min_distance_m: cp,
        true_distance_m: best,
    };
    (row, pairs.iter().map(|p| p.patches).collect())
}

/// Levels of subdivision for finding the lift of the near pose.
const HOLD_LEVEL: u8 = 4;

/// `pose` with the lift at which the butterfly's true distance from the leaf is `distance`
/// (bisection on the lift between touching and the butterfly's size above it).
pub fn hold_at(butterfly: &NurbsSurface, leaf: &NurbsSurface, pose: Placement, distance: f64) -> Placement {
    let leaf_tree = PatchTree::build(leaf, HOLD_LEVEL);
    let size = Kdop::from_points(butterfly.control_points()).extent();
    let gap_distance = |gap: f64| {
        let b = place(butterfly, leaf, Placement { gap, ..pose });
        surface_distance(&PatchTree::build(&b, HOLD_LEVEL), &leaf_tree)
            .best
            .distance
    };
    // From a lift where the surfaces are nearer than `distance` (stepping down from the
    // placement point) to one above the butterfly's size, where they are farther.
    let (mut lo, hi) = (0.0, size + distance);
    while gap_distance(lo) >= distance && lo > -size {
        lo -= size / 16.0;
    }
    let search = crate::convergence::Bisection {
        name: "nurbs.pose.bisection",
        steps: 80,
        tolerance: 1e-9 * size.max(f64::MIN_POSITIVE),
        stop_at_tolerance: true,
    };
    let (_, gap) = search.run(lo, hi, |g| gap_distance(g) < distance);
    Placement { gap, ..pose }
}

/// Runs the experiment on `butterfly` and `leaf`.
pub fn run_experiment(butterfly: &NurbsSurface, leaf: &NurbsSurface, options: &ExperimentOptions) -> Experiment {
    let held = hold_at(butterfly, leaf, options.pose, options.near_distance_m);
    let through = Placement {
        gap: held.gap - options.near_distance_m - options.crossing_depth_m,
        ..held
    };
    let near = place(butterfly, leaf, held);
    let crossing_butterfly = place(butterfly, leaf, through);
    let mut levels = Vec::new();
    let mut pictures = Vec::new();
    let mut trees = Vec::new();
    for level in options.levels.clone() {
        let time_ms = median_ms(options.timing_ms, || {
            let (a, b) = (PatchTree::build(&near, level), PatchTree::build(leaf, level));
            nearest_control_points(&a, &b)
        });
        let (a, b) = (PatchTree::build(&near, level), PatchTree::build(leaf, level));
        let query_ms = median_ms(options.timing_ms, || nearest_control_points(&a, &b));
        let cp = nearest_control_points(&a, &b);
        let truth = surface_distance(&a, &b);
        let n = options.coverage_samples;
        levels.push(LevelRow {
            level,
            time_ms,
            query_ms,
            pairs_tested: cp.hull_tests,
            leaf_pairs: cp.leaf_pairs,
            cp_min_distance_m: cp.distance,
            true_distance_m: truth.best.distance,
            error_m: cp.distance - truth.best.distance,
            net_deviation_m: [net_deviation(&a), net_deviation(&b)],
            coverage_m: [coverage(&a, n), coverage(&b, n)],
            refined_pairs: truth.refined,
            true_params: truth.best.params,
        });
        let (open, _) = pairs_within(&a, &b, cp.distance);
        let open: Vec<[u32; 2]> = open.iter().map(|p| p.patches).collect();
        pictures.push(LevelPicture {
            level,
            near_hulls: hulls_of(&a, &b, &open, options.hulls_kept),
            crossing_hulls: [Vec::new(), Vec::new()],
            cp_points: cp.points,
            true_points: truth.best.points,
        });
        trees.push(b);
    }
    let recommended = recommend(&levels, options.accuracy_m);
    let mut crossing = Vec::new();
    for (k, level) in options.levels.clone().enumerate() {
        let a = PatchTree::build(&crossing_butterfly, level);
        let (row, pairs) = crossing_row(level, &a, &trees[k], recommended.threshold_m);
        pictures[k].crossing_hulls = hulls_of(&a, &trees[k], &pairs, options.hulls_kept);
        crossing.push(row);
    }
    Experiment {
        near_pose: held,
        crossing_pose: through,
        near,
        crossing_butterfly,
        leaf: leaf.clone(),
        levels,
        crossing,
        recommended,
        pictures,
    }
}

/// The least level whose error is within `accuracy` (else the deepest), and the threshold
/// 1.5 times its error (the paper's margin); never below the accuracy's tenth, so that a
/// level that happens to hit the truth does not give a threshold of zero.
pub fn recommend(levels: &[LevelRow], accuracy: f64) -> Recommendation {
    let chosen = levels.iter().find(|r| r.error_m.abs() <= accuracy);
    let row = chosen.or(levels.last());
    let (level, error) = row.map_or((0, accuracy), |r| (r.level, r.error_m.abs()));
    Recommendation {
        level,
        threshold_m: (1.5 * error).max(0.1 * accuracy),
        accuracy_m: accuracy,
        met: chosen.is_some(),
    }
}
