//! M1's collision patch by patch, and what a step keeps of the last one (docs/design.md
//! section 7).
//!
//! The vertices M1's collision may move (the centroids of a refined patch's faces, and the
//! old vertices its smoothing moved) have every edge and face in that patch, and M0's
//! vertices stay where M0's collision put them. So each refined patch is collided alone,
//! in its own numbering (its vertices in M1's order: M0's first, then its new ones), and
//! the patches' results are joined in patch order ([`join`]); the parts of M1 that are M0's
//! take M0's own verdicts ([`super::collide`]). A patch's result depends only on its
//! [`PatchInput`]: its faces, their positions, and what M0's collision and check left at
//! its vertices (partition, ring normal, measured distance). A patch whose input equals,
//! bit for bit, that of a patch collided before ([`M1Reuse`]) takes that result instead of
//! colliding again: the same M1 as a full rebuild, bit for bit, by construction.

use std::sync::Arc;

use glam::DVec3;

use super::collide::{Free, Kept, M0Collided, M1Collision, RefinedInput, assemble, collide_free, pinned_of};
use super::{M1, M1Shape};
use crate::collision::VertexDistance;
use crate::collision::quality::Measured;
use crate::collision::types::NO_TRIANGLE;
use crate::collision::{BodyIndex, CollisionOptions, Quality};
use crate::mesh::topology::group_by_key as group;

/// A refined patch's shape in its own numbering: what stays the same while M1 keeps its
/// shape ([`super::M1Shape`]), shared by the steps that keep it.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchShape {
    /// Its vertices' numbers in M1, ascending (M0's first).
    pub vertices: Vec<u32>,
    /// Its faces' numbers in M1, ascending.
    pub faces: Vec<u32>,
    /// Its faces in its own numbering.
    pub triangles: Vec<[u32; 3]>,
    /// Its undirected edges, each once, sorted.
    pub edges: Vec<[u32; 2]>,
    /// How many of its vertices are M0's.
    pub base: usize,
    /// Its M0 vertices the smoothing moved, ascending.
    pub moved: Vec<u32>,
    /// The M0 vertex each of its vertices descends from (its own numbering).
    pub anchor: Vec<u32>,
}

/// One refined patch of M1 in its own numbering: what its collision reads.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchInput {
    /// Its shape.
    pub shape: Arc<PatchShape>,
    /// Its vertices' positions before the collision.
    pub positions: Vec<DVec3>,
    /// Partition of each of its M0 vertices.
    pub partition: Vec<usize>,
    /// Ring normal of each of its M0 vertices.
    pub ring_normal: Vec<Option<DVec3>>,
    /// M0's check's distance at each of its M0 vertices, where kept.
    pub measured: Vec<Option<VertexDistance>>,
}

impl PatchInput {
    /// Whether its collision is that of `other`: the same faces in its own numbering, at the
    /// same positions bit for bit, with the same moved vertices, anchors, partitions and ring
    /// normals. Where it lies in M1 (its vertices' and faces' numbers there, which shift when
    /// another patch is refined or no longer is) does not count, nor which of its distances
    /// M0's check kept: a kept distance is the one the check would measure at the same
    /// position.
    fn same_as(&self, other: &Self) -> bool {
        let bits = |p: &DVec3| p.to_array().map(f64::to_bits);
        let (a, b) = (&*self.shape, &*other.shape);
        let same_shape = Arc::ptr_eq(&self.shape, &other.shape)
            || (a.base == b.base
                && a.triangles == b.triangles
                && a.edges == b.edges
                && a.moved == b.moved
                && a.anchor == b.anchor);
        same_shape
            && self.partition == other.partition
            && self.ring_normal == other.ring_normal
            && self.positions.len() == other.positions.len()
            && (self.positions.iter().zip(&other.positions)).all(|(a, b)| bits(a) == bits(b))
    }

    /// The input of a patch of shape `shape`, its values read from `m1` and M0's
    /// collision: its vertices' positions, and M0's partition, ring normal and measured
    /// distance at its M0 vertices.
    fn place(shape: Arc<PatchShape>, m1: &M1, m0: &M0Collided<'_>) -> Self {
        let old = &shape.vertices[..shape.base];
        Self {
            positions: (shape.vertices.iter())
                .map(|&v| m1.mesh.positions[v as usize])
                .collect(),
            partition: (old.iter())
                .map(|&v| m0.partition.get(v as usize).copied().unwrap_or(0))
                .collect(),
            ring_normal: (old.iter())
                .map(|&v| m0.ring_normal.get(v as usize).copied().flatten())
                .collect(),
            measured: (old.iter())
                .map(|&v| (m0.measured).and_then(|m| m.distance(v as usize, m1.mesh.positions[v as usize])))
                .collect(),
            shape,
        }
    }

    /// Its collision, alone.
    fn collide(&self, index: &BodyIndex, ease: f64, options: &CollisionOptions) -> Free {
        let shape = &*self.shape;
        let refined = RefinedInput {
            positions: &self.positions,
            triangles: &shape.triangles,
            edges: &shape.edges,
            base_vertices: shape.base,
            moved: &shape.moved,
            anchor: &shape.anchor,
        };
        // M0's distances at the patch's M0 vertices; where none was kept the vertex stands
        // nowhere (NaN, which no position equals), so the check measures it.
        let unknown = VertexDistance {
            signed: f64::NAN,
            triangle: NO_TRIANGLE,
        };
        let measured = Measured {
            at: (self.positions[..shape.base].iter().zip(&self.measured))
                .map(|(&p, d)| if d.is_some() { p } else { DVec3::NAN })
                .collect(),
            distance: self.measured.iter().map(|d| d.unwrap_or(unknown)).collect(),
        };
        let base = M0Collided {
            inside: &[],
            crossing: &[],
            triangles: &[],
            pierced: &[],
            partition: &self.partition,
            ring_normal: &self.ring_normal,
            measured: Some(&measured),
        };
        let pinned = pinned_of(&refined);
        let faces: Vec<u32> = (0..shape.triangles.len() as u32)
            .filter(|&f| shape.triangles[f as usize].iter().any(|&v| !pinned[v as usize]))
            .collect();
        collide_free(index, &refined, &pinned, &faces, &base, ease, options)
    }
}

/// What the last M1's collision left for the next: each refined patch's input and result,
/// with the settings they were made under.
#[derive(Clone, Debug, Default)]
pub struct M1Reuse {
    /// The body (a hash of its index's positions and triangles), the garment's ease (its
    /// bits) and the collision settings.
    settings: Option<(u64, u64, CollisionOptions)>,
    /// Per patch: its input and its collision.
    patches: Vec<Option<(PatchInput, Arc<Free>)>>,
    /// The shape of the M1 they were found on: an M1 of the same shape (the same `Arc`)
    /// has the same patches in the same numbering, so only their values are read again.
    shape: Option<Arc<M1Shape>>,
}

/// How M1's collision went patch by patch: how many were collided and how many taken from
/// before.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PatchCounts {
    /// Refined patches collided at this step.
    pub collided: usize,
    /// Refined patches whose collision was taken from an earlier step.
    pub kept: usize,
    /// Vertices tested in the patches collided at this step.
    pub tested: usize,
}

/// Collides M1 (whose M0 vertices are already collided): only the vertices M0 does not
/// have move, each refined patch alone (see the module's notes). `garment_ease` is the
/// garment's ease.
pub fn collide_m1(
    index: &BodyIndex,
    m1: &M1,
    m0: &M0Collided<'_>,
    garment_ease: f64,
    options: &CollisionOptions,
) -> M1Collision {
    collide_m1_patches(index, m1, m0, garment_ease, options, None, None).0
}

/// Collides M1 patch by patch; with `reuse`, a refined patch whose input is the same as
/// there takes its collision from there. `shape` is `m1`'s shape, if known
/// ([`super::subdivide`]). Returns the collision, what to keep for the next step, and the
/// counts.
pub fn collide_m1_patches(
    index: &BodyIndex,
    m1: &M1,
    m0: &M0Collided<'_>,
    garment_ease: f64,
    options: &CollisionOptions,
    reuse: Option<&M1Reuse>,
    shape: Option<&Arc<M1Shape>>,
) -> (M1Collision, M1Reuse, PatchCounts) {
    let settings = Some((index.fingerprint(), garment_ease.to_bits(), options.clone()));
    // The patches as last found, when M1 has their shape (whatever the settings).
    let same_shape = reuse.filter(|r| matches!((&r.shape, shape), (Some(a), Some(b)) if Arc::ptr_eq(a, b)));
    // The last patches whatever the settings (their shapes do not depend on them).
    let last = reuse;
    let reuse = reuse.filter(|r| r.settings == settings);
    let pinned = pinned_of(&RefinedInput {
        positions: &m1.mesh.positions,
        triangles: &m1.mesh.triangles,
        edges: m1.edges(),
        base_vertices: m1.m0_vertices,
        moved: &m1.smoothed,
        anchor: &m1.anchor,
    });
    let kept = super::kept::kept_of_m1(m1, &pinned, m0);
    let inputs = match same_shape {
        Some(before) => (before.patches.iter().enumerate())
            .filter_map(|(p, kept)| kept.as_ref().map(|(input, _)| (p as u32, input.shape.clone())))
            .map(|(p, shape)| (p, PatchInput::place(shape, m1, m0)))
            .collect(),
        None => {
            // When only which patches are refined changed, the patches refined before too
            // are renumbered.
            let renumber = last.and_then(|r| match (&r.shape, shape) {
                (Some(a), Some(b)) if a.renumbers(b) => Some(Renumber::new(r, a.m1(), m1)),
                _ => None,
            });
            patch_inputs(m1, &pinned, m0, renumber.as_ref())
        }
    };
    // The patches kept from before, then the others collided, shared out among the threads.
    let kept_before: Vec<Option<Arc<Free>>> = (inputs.iter())
        .map(|(p, input)| {
            let before = reuse.and_then(|r| r.patches.get(*p as usize)).and_then(Option::as_ref);
            before
                .filter(|(was, _)| was.same_as(input))
                .map(|(_, free)| free.clone())
        })
        .collect();
    let anew: Vec<usize> = (0..inputs.len()).filter(|&k| kept_before[k].is_none()).collect();
    let mut collided = crate::par::par_map_from(anew.len(), 2, |i| {
        Arc::new(inputs[anew[i]].1.collide(index, garment_ease, options))
    })
    .into_iter();
    // One collided result for each patch not kept, in order.
    let results: Vec<(Arc<Free>, bool)> = kept_before
        .into_iter()
        .filter_map(|kept| match kept {
            Some(free) => Some((free, true)),
            None => collided.next().map(|free| (free, false)),
        })
        .collect();
    let counts = PatchCounts {
        collided: results.iter().filter(|r| !r.1).count(),
        kept: results.iter().filter(|r| r.1).count(),
        tested: results.iter().filter(|r| !r.1).map(|r| r.0.tested).sum(),
    };
    let collision = join(m1, &inputs, results.iter().map(|r| &*r.0), kept);
    let mut next = M1Reuse {
        settings,
        patches: vec![None; m1.selection.rules.len()],
        shape: shape.cloned(),
    };
    for ((p, input), (free, _)) in inputs.into_iter().zip(results) {
        if let Some(slot) = next.patches.get_mut(p as usize) {
            *slot = Some((input, free));
        }
    }
    (collision, next, counts)
}

/// The last M1's refined patches, read for an M1 that refines other patches over the same
/// M0 faces ([`super::M1Shape::renumbers`]): a patch refined in both keeps its faces,
/// edges and anchors in its own numbering; its M0 vertices keep their numbers and its
/// centroids take those of the same faces' centroids here.
struct Renumber<'a> {
    /// The last step's patches.
    last: &'a M1Reuse,
    /// M0's vertex count.
    n0: usize,
    /// The M0 face each of the last M1's centroids (`n0 + k`) is the centroid of.
    face_of: Vec<u32>,
    /// The centroid of each M0 face in this M1.
    centroid_of: &'a [Option<u32>],
}

impl<'a> Renumber<'a> {
    fn new(last: &'a M1Reuse, last_m1: &M1, m1: &'a M1) -> Self {
        let n0 = m1.m0_vertices;
        let mut face_of = vec![u32::MAX; last_m1.first_vertices.saturating_sub(n0)];
        for (g, c) in last_m1.first.centroid_of.iter().enumerate() {
            if let Some(slot) = c.and_then(|c| face_of.get_mut((c as usize).wrapping_sub(n0))) {
                *slot = g as u32;
            }
        }
        Self {
            last,
            n0,
            face_of,
            centroid_of: &m1.first.centroid_of,
        }
    }

    /// Patch `p`'s shape, with `faces` (its faces' numbers here), from the last step's,
    /// renumbered; `None` when the last step did not refine it (or its faces do not match).
    fn shape_of(&self, p: usize, faces: &[u32]) -> Option<PatchShape> {
        let (input, _) = self.last.patches.get(p)?.as_ref()?;
        let old = &*input.shape;
        if old.faces.len() != faces.len() {
            return None;
        }
        let vertices = (old.vertices.iter())
            .map(|&v| match (v as usize).checked_sub(self.n0) {
                None => Some(v),
                Some(k) => (self.face_of.get(k)).and_then(|&g| self.centroid_of.get(g as usize).copied().flatten()),
            })
            .collect::<Option<Vec<u32>>>()?;
        Some(PatchShape {
            vertices,
            faces: faces.to_vec(),
            triangles: old.triangles.clone(),
            edges: old.edges.clone(),
            base: old.base,
            moved: old.moved.clone(),
            anchor: old.anchor.clone(),
        })
    }
}

/// Each refined patch's input, by patch number; the patches built on all cores, each on
/// its own (the same inputs on any number of threads). With `renumber`, a patch the last
/// M1 refined too takes its shape from there, renumbered.
fn patch_inputs(
    m1: &M1,
    pinned: &[bool],
    m0: &M0Collided<'_>,
    renumber: Option<&Renumber<'_>>,
) -> Vec<(u32, PatchInput)> {
    let patches = m1.selection.rules.len();
    let n = m1.mesh.positions.len();
    // M1's faces grouped by patch, ascending within each.
    let (first, grouped) = group(patches, m1.face_patch.iter().enumerate().map(|(f, &p)| (p, f as u32)));
    // The patch of each vertex that is not pinned (all its faces are in one patch), and the
    // edges at such a vertex grouped by it, in M1's order: found once, when a patch is built
    // anew (not for patches renumbered).
    let edge_groups = std::sync::OnceLock::new();
    let edges_by_patch = || {
        edge_groups.get_or_init(|| {
            let mut patch_of = vec![u32::MAX; n];
            for (t, &p) in m1.mesh.triangles.iter().zip(m1.face_patch.iter()) {
                for &v in t {
                    if !pinned[v as usize] {
                        patch_of[v as usize] = p;
                    }
                }
            }
            let free_end = |[a, b]: [u32; 2]| if pinned[b as usize] { a } else { b };
            group(
                patches,
                (m1.edges.iter())
                    .filter(|&&[a, b]| !pinned[a as usize] || !pinned[b as usize])
                    .map(|&e| (patch_of[free_end(e) as usize], e)),
            )
        })
    };
    let refined: Vec<usize> = (0..patches).filter(|&p| !m1.selection.rules[p].is_empty()).collect();
    crate::par::par_map_from(refined.len(), 2, |k| {
        let p = refined[k];
        if let Some(shape) = renumber.and_then(|r| r.shape_of(p, &grouped[first[p]..first[p + 1]])) {
            return (p as u32, PatchInput::place(Arc::new(shape), m1, m0));
        }
        let faces = grouped[first[p]..first[p + 1]].to_vec();
        let (edge_first, edges) = edges_by_patch();
        super::numbering::NUMBERING.with_borrow_mut(|numbering| {
            let local = numbering.start(n);
            let mut vertices: Vec<u32> = Vec::with_capacity(faces.len());
            for &v in faces.iter().flat_map(|&f| &m1.mesh.triangles[f as usize]) {
                if local.get(v).is_none() {
                    local.set(v, 0);
                    vertices.push(v);
                }
            }
            vertices.sort_unstable();
            for (i, &v) in vertices.iter().enumerate() {
                local.set(v, i as u32);
            }
            let at = |v: u32| local.get(v).unwrap_or(u32::MAX);
            let base = vertices.partition_point(|&v| (v as usize) < m1.m0_vertices);
            let shape = PatchShape {
                triangles: faces.iter().map(|&f| m1.mesh.triangles[f as usize].map(at)).collect(),
                edges: edges[edge_first[p]..edge_first[p + 1]]
                    .iter()
                    .map(|e| e.map(at))
                    .collect(),
                moved: (vertices.iter().enumerate())
                    .filter(|&(i, &v)| i < base && !pinned[v as usize])
                    .map(|(i, _)| i as u32)
                    .collect(),
                anchor: vertices.iter().map(|&v| at(m1.anchor[v as usize])).collect(),
                base,
                vertices,
                faces,
            };
            (p as u32, PatchInput::place(Arc::new(shape), m1, m0))
        })
    })
}

/// The patches' collisions joined into M1's (vertex, edge and face numbers M1's; moves in
/// patch order), with the kept part.
fn join<'a>(m1: &M1, inputs: &[(u32, PatchInput)], frees: impl Iterator<Item = &'a Free>, kept: Kept) -> M1Collision {
    let n = m1.mesh.positions.len();
    let mut positions = m1.mesh.positions.clone();
    let mut quality = Quality {
        clearance: vec![f64::INFINITY; n],
        nearest: vec![NO_TRIANGLE; n],
        max_stretch: 1.0,
        ..Quality::default()
    };
    let (mut tested, mut hits, mut pierced_before) = (0, 0, 0);
    let (mut crossing_before, mut crossing_after, mut pierced_after) = (Vec::new(), Vec::new(), Vec::new());
    let (mut edge_rounds, mut face_rounds) = (vec![0], vec![0]);
    let mut responses = Vec::new();
    let mut inside = Vec::new();
    for ((_, input), free) in inputs.iter().zip(frees) {
        let input = &*input.shape;
        let global = |v: u32| input.vertices[v as usize];
        let edge = |[a, b]: [u32; 2]| [global(a), global(b)];
        tested += free.tested;
        hits += free.hits;
        pierced_before += free.pierced_before;
        crossing_before.extend(free.crossing_before.iter().map(|&e| edge(e)));
        crossing_after.extend(free.crossing_after.iter().map(|&e| edge(e)));
        pierced_after.extend(free.pierced_after.iter().map(|&f| input.faces[f as usize]));
        add_rounds(&mut edge_rounds, &free.edge_rounds);
        add_rounds(&mut face_rounds, &free.face_rounds);
        responses.extend(free.responses.iter().map(|r| {
            let mut r = *r;
            r.vertex = global(r.vertex);
            r
        }));
        inside.extend(free.quality.inside.iter().map(|&v| global(v)));
        for (k, &v) in input.vertices.iter().enumerate() {
            let v = v as usize;
            if k >= input.base || input.moved.binary_search(&(k as u32)).is_ok() {
                positions[v] = free.positions[k];
            }
            if free.quality.clearance[k].is_finite() {
                quality.clearance[v] = free.quality.clearance[k];
                quality.nearest[v] = free.quality.nearest[k];
            }
        }
        let q = &free.quality;
        quality.max_depth_m = quality.max_depth_m.max(q.max_depth_m);
        quality.max_move_m = quality.max_move_m.max(q.max_move_m);
        quality.max_stretch = quality.max_stretch.max(q.max_stretch);
    }
    crossing_before.sort_unstable();
    crossing_after.sort_unstable();
    inside.sort_unstable();
    quality.penetrating_vertices = inside.len();
    if !inside.is_empty() {
        let depth: f64 = inside.iter().map(|&v| -quality.clearance[v as usize]).sum();
        quality.mean_depth_m = depth / inside.len() as f64;
    }
    quality.inside = inside;
    if !responses.is_empty() {
        let errs = responses.iter().map(|r| r.ease_error.abs());
        quality.max_ease_error_m = errs.clone().fold(0.0, f64::max);
        quality.mean_ease_error_m = errs.sum::<f64>() / responses.len() as f64;
    }
    let free = Free {
        tested,
        hits,
        crossing_before,
        responses,
        edge_rounds,
        positions,
        quality,
        crossing_after,
        pierced_before,
        face_rounds,
        pierced_after,
    };
    assemble(kept, free)
}

/// Adds a patch's per-round counts to the whole's, round by round.
fn add_rounds(total: &mut Vec<usize>, rounds: &[usize]) {
    if total.len() < rounds.len() {
        total.resize(rounds.len(), 0);
    }
    for (t, r) in total.iter_mut().zip(rounds) {
        *t += r;
    }
}
