//! Mesh-layer detection (\[collide\] 4): every garment vertex is given the body partition
//! its height falls in and tested against that partition's triangles only (plus the
//! margin band), with the partition's own test: point-face, or line-line for legs and
//! abdomen. Which test a partition uses is data ([`crate::body::Partition::method`]).
//!
//! Two accelerations skip vertices between steps (\[collide\] 4.3):
//! - **patch skipping**: a patch none of whose boundary curves' control points moved more
//!   than a threshold is not re-tested;
//! - **inert points**: a vertex that moved less than a threshold since it was last tested
//!   is not re-tested.
//!
//! Both are guarded so that they never change a result: a vertex is skipped only if it was
//! outside when last tested and has moved less than its clearance then (and, for the
//! line-line test, still reads the same slice), so its verdict cannot have changed.

use std::collections::BTreeMap;

use glam::DVec3;

use super::line_line::line_line;
use super::point_face::{Reach, Search, point_face};
use super::types::{Hit, VertexDistance};
use crate::body::DetectionMethod;
use crate::body::index::{BodyIndex, Nearest};
use crate::garment::CurveRef;
use crate::par::par_map;

/// Which triangles each vertex is tested against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Acceleration {
    /// Every body triangle (no partitions, no BVH): the reference.
    BruteForce,
    /// The partition's triangles, one by one.
    Partitioned,
    /// The partition's triangles through its BVH.
    PartitionedBvh,
}

/// Detection settings. Lengths are fractions of the body's height or of the garment's
/// mean edge, so that they carry over to other bodies and garments.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct DetectOptions {
    /// Default value: partitions with their BVHs.
    pub acceleration: Acceleration,
    /// Use this test everywhere instead of each partition's own (benchmarks, checks).
    /// Default value: `None` (each partition's).
    pub method_override: Option<DetectionMethod>,
    /// `w1`, the depth below the skin still detected, over the body height. Default value:
    /// 0.1 (16 cm on 1.6 m: deeper than any point of a human torso lies).
    pub inside_reach: f64,
    /// `w2`, the reach outside the surface, as a fraction of the body height. Default value:
    /// 0.02.
    pub outside_reach: f64,
    /// Skip inert vertices. Default value: true.
    pub inert: bool,
    /// A vertex that moved less than this fraction of the garment's mean edge since its last
    /// test is inert. Default value: 0.1.
    pub inert_threshold: f64,
    /// Skip patches whose curves did not move. Default value: true.
    pub patch_skipping: bool,
    /// A patch whose boundary curves' control points all moved less than this fraction of
    /// the garment's mean edge is not re-tested. Default value: 0.1.
    pub patch_threshold: f64,
}

impl Default for DetectOptions {
    fn default() -> Self {
        Self {
            acceleration: Acceleration::PartitionedBvh,
            method_override: None,
            inside_reach: 0.1,
            outside_reach: 0.02,
            inert: true,
            inert_threshold: 0.1,
            patch_skipping: true,
            patch_threshold: 0.1,
        }
    }
}

impl DetectOptions {
    /// Sets [`Self::acceleration`].
    #[must_use]
    pub fn with_acceleration(mut self, acceleration: Acceleration) -> Self {
        self.acceleration = acceleration;
        self
    }

    /// Sets [`Self::method_override`].
    #[must_use]
    pub fn with_method(mut self, method: Option<DetectionMethod>) -> Self {
        self.method_override = method;
        self
    }

    /// Sets [`Self::inert`] and [`Self::patch_skipping`].
    #[must_use]
    pub fn with_skipping(mut self, skipping: bool) -> Self {
        self.inert = skipping;
        self.patch_skipping = skipping;
        self
    }

    /// The reach in metres for a body of height `height`.
    pub fn reach(&self, height: f64) -> Reach {
        Reach {
            inside: self.inside_reach * height,
            outside: self.outside_reach * height,
            surface: 1e-12 * height,
        }
    }
}

/// The garment mesh as detection sees it.
#[derive(Clone, Copy, Debug)]
pub struct GarmentInput<'a> {
    /// Vertex positions.
    pub positions: &'a [DVec3],
    /// Vertex normals (outward).
    pub normals: &'a [DVec3],
    /// Edges (for the mean edge length).
    pub edges: &'a [[u32; 2]],
    /// For each vertex, the patches it belongs to (empty: no patch skipping for it).
    pub vertex_patches: &'a [Vec<u32>],
    /// For each patch, the curves its boundary comes from.
    pub patch_curves: &'a [Vec<CurveRef>],
    /// The control points of every curve by name.
    pub controls: &'a BTreeMap<String, Vec<DVec3>>,
}

/// Why a vertex was not tested this step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Skip {
    /// Tested.
    Tested,
    /// Inert.
    Inert,
    /// Its patches' curves did not move.
    Patch,
}

/// What a vertex's last test left to decide whether it can be skipped.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Memo {
    position: DVec3,
    clearance: f64,
    partition: u32,
    /// The slice read by the line-line test (`u32::MAX`: none).
    slice: u32,
    method: DetectionMethod,
}

/// What detection remembers between steps (same garment topology).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DetectState {
    memo: Vec<Memo>,
    controls: BTreeMap<String, Vec<DVec3>>,
    /// What the edge rounds and the quality check measured (see [`super::reuse`]).
    pub(super) reuse: super::reuse::Reuse,
}

impl DetectState {
    /// Remembers the body's nearest points `measured` (vertex, its nearest point where it
    /// stands in `positions`, found with no limit on the distance: by the garment's
    /// assembly, which clears its samples off the body): the edge rounds and the quality
    /// check take those distances instead of measuring the vertices again. The answers are
    /// the same, as a nearest point depends on the position alone.
    pub fn remember_nearest(&mut self, index: &BodyIndex, positions: &[DVec3], measured: &[(u32, Nearest)]) {
        for (v, n) in measured {
            let (v, p) = (*v as usize, positions[*v as usize]);
            if self.reuse.distance(v, p).is_none() {
                let d = VertexDistance::from_nearest(index, p, Some(n));
                self.reuse.set_distance(positions.len(), v, p, d);
            }
        }
    }
}

/// One step's detection.
#[derive(Clone, Debug, PartialEq)]
pub struct Detection {
    /// Penetrating vertices, by vertex.
    pub hits: Vec<Hit>,
    /// Partition of every vertex (index into [`BodyIndex::partitions`]).
    pub partition: Vec<usize>,
    /// What happened to every vertex.
    pub skip: Vec<Skip>,
    /// The test each vertex had (`None`: skipped).
    pub methods: Vec<Option<DetectionMethod>>,
    /// Vertices tested.
    pub tested: usize,
    /// Vertices skipped as inert.
    pub skipped_inert: usize,
    /// Vertices skipped with their patch.
    pub skipped_patch: usize,
    /// Patches not re-tested.
    pub patches_skipped: usize,
    /// Vertices tested point-face and line-line.
    pub by_method: [usize; 2],
}

fn mean_edge(positions: &[DVec3], edges: &[[u32; 2]]) -> f64 {
    if edges.is_empty() {
        return 0.0;
    }
    edges
        .iter()
        .map(|[a, b]| positions[*a as usize].distance(positions[*b as usize]))
        .sum::<f64>()
        / edges.len() as f64
}

fn max_move(before: Option<&Vec<DVec3>>, after: Option<&Vec<DVec3>>, r: &CurveRef) -> f64 {
    match (before, after) {
        (Some(b), Some(a)) if a.len() == b.len() && !a.is_empty() => {
            let last = r.last.min(a.len() - 1);
            (r.first..=last).map(|i| a[i].distance(b[i])).fold(0.0, f64::max)
        }
        _ => f64::INFINITY,
    }
}

/// No slice in a [`Memo`].
const NO_SLICE: u32 = u32::MAX;

/// The test of one vertex: its hit (if inside; boxed, as hits are few and the memos are
/// many) and its memo.
fn test_vertex(
    index: &BodyIndex,
    options: &DetectOptions,
    reach: &Reach,
    v: usize,
    p: DVec3,
    normal: DVec3,
    partition: usize,
) -> (Option<Box<Hit>>, Memo) {
    let method = options.method_override.unwrap_or(index.partitions[partition].method);
    let slice = match method {
        DetectionMethod::LineLine => index.slices.nearest(p.y),
        DetectionMethod::PointFace => None,
    };
    let memo = |clearance: f64, slice: Option<usize>| Memo {
        position: p,
        clearance,
        partition: partition as u32,
        slice: slice.map_or(NO_SLICE, |k| k as u32),
        method,
    };
    if let Some((k, s)) = slice {
        let r = line_line(s, k, p, normal, reach);
        let hit = r.inside.then(|| {
            Box::new(Hit {
                vertex: v as u32,
                partition,
                method,
                depth: r.depth,
                foot: r.foot,
                normal: r.normal,
                triangle: None,
            })
        });
        return (hit, memo(r.clearance, Some(k)));
    }
    // Point-face (also where a line-line partition lies outside the slice stack).
    let search = match options.acceleration {
        Acceleration::BruteForce => Search::Brute,
        Acceleration::Partitioned => Search::Partition(partition),
        Acceleration::PartitionedBvh => Search::PartitionBvh(partition),
    };
    let r = point_face(index, search, p, reach);
    let hit = match (r.inside, r.nearest) {
        (true, Some(n)) => Some(Box::new(Hit {
            vertex: v as u32,
            partition,
            method: DetectionMethod::PointFace,
            depth: n.distance,
            foot: n.foot,
            normal: n.normal,
            triangle: Some(n.triangle),
        })),
        _ => None,
    };
    let mut m = memo(r.clearance(reach), None);
    m.method = DetectionMethod::PointFace;
    (hit, m)
}

/// The patches whose curves did not move (none moved more than the patch threshold of the
/// mean edge `edge` since `controls`); none on a `fresh` state or without patch skipping.
fn still_patches(
    garment: &GarmentInput<'_>,
    options: &DetectOptions,
    controls: &BTreeMap<String, Vec<DVec3>>,
    (fresh, edge): (bool, f64),
) -> Vec<bool> {
    garment
        .patch_curves
        .iter()
        .map(|curves| {
            options.patch_skipping
                && !fresh
                && !curves.is_empty()
                && curves.iter().all(|r| {
                    max_move(controls.get(&r.curve), garment.controls.get(&r.curve), r) < options.patch_threshold * edge
                })
        })
        .collect()
}

/// Detects the penetrating vertices of `garment`, skipping what `state` allows, and
/// updates `state` (reset it when the garment's topology changes).
pub fn detect(
    index: &BodyIndex,
    garment: &GarmentInput<'_>,
    options: &DetectOptions,
    state: &mut DetectState,
) -> Detection {
    let n = garment.positions.len();
    if index.partitions.is_empty() {
        // A body without partitions has nothing to test against.
        return Detection {
            hits: Vec::new(),
            partition: vec![0; n],
            skip: vec![Skip::Tested; n],
            methods: vec![None; n],
            tested: 0,
            skipped_inert: 0,
            skipped_patch: 0,
            patches_skipped: 0,
            by_method: [0, 0],
        };
    }
    let reach = options.reach(index.height);
    if state.memo.len() != n {
        state.memo.clear();
        state.controls.clear();
    }
    let fresh = state.memo.is_empty();
    // The skipping thresholds' unit (a fresh state tests every vertex: no need of it).
    let edge = if fresh {
        0.0
    } else {
        mean_edge(garment.positions, garment.edges)
    };
    let patch_still = still_patches(garment, options, &state.controls, (fresh, edge));
    let mut out = Detection {
        hits: Vec::new(),
        partition: Vec::with_capacity(n),
        skip: Vec::with_capacity(n),
        methods: Vec::with_capacity(n),
        tested: 0,
        skipped_inert: 0,
        skipped_patch: 0,
        patches_skipped: patch_still.iter().filter(|s| **s).count(),
        by_method: [0, 0],
    };
    if fresh {
        state.memo.reserve_exact(n);
    }
    // Which vertices to test (cheap, in order), then their tests on the worker threads, then
    // the results in vertex order: the same whatever the number of threads.
    let mut to_test = Vec::with_capacity(n);
    for v in 0..n {
        let p = garment.positions[v];
        let partition = index.partition_at(p.y).unwrap_or(0);
        out.partition.push(partition);
        let method = options.method_override.unwrap_or(index.partitions[partition].method);
        if !fresh {
            let m = &state.memo[v];
            let moved = p.distance(m.position);
            let same_slice =
                m.slice == NO_SLICE || index.slices.nearest(p.y).is_some_and(|(k, _)| k == m.slice as usize);
            let safe = moved < m.clearance && m.partition as usize == partition && same_slice && m.method == method;
            let patch = garment.vertex_patches.get(v).is_some_and(|ps| {
                !ps.is_empty()
                    && ps
                        .iter()
                        .all(|&k| patch_still.get(k as usize).copied().unwrap_or(false))
            });
            if safe && patch {
                out.skip.push(Skip::Patch);
                out.methods.push(None);
                out.skipped_patch += 1;
                continue;
            }
            if safe && options.inert && moved < options.inert_threshold * edge {
                out.skip.push(Skip::Inert);
                out.methods.push(None);
                out.skipped_inert += 1;
                continue;
            }
        }
        out.skip.push(Skip::Tested);
        out.methods.push(None);
        to_test.push(v);
    }
    let tests = par_map(to_test.len(), |k| {
        let v = to_test[k];
        let normal = garment.normals.get(v).copied().unwrap_or(DVec3::ZERO);
        test_vertex(
            index,
            options,
            &reach,
            v,
            garment.positions[v],
            normal,
            out.partition[v],
        )
    });
    // Fresh: every vertex was tested, in order.
    for (&v, (hit, memo)) in to_test.iter().zip(tests) {
        out.by_method[usize::from(memo.method == DetectionMethod::LineLine)] += 1;
        out.tested += 1;
        out.methods[v] = Some(memo.method);
        out.hits.extend(hit.map(|h| *h));
        if fresh {
            state.memo.push(memo);
        } else {
            state.memo[v] = memo;
        }
    }
    state.controls = garment.controls.clone();
    out
}
