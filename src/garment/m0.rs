//! Surfaces and the stitched mesh M0 (\[frame\] section 4, \[collide\] section 3.1).
//!
//! Each region bounded by four curves is a bilinearly blended Coons patch, sampled on a
//! fixed `(nu + 1) x (nv + 1)` grid; its boundary samples are the curves' own samples, so
//! patches that share a curve share those points. The patches are stitched into one mesh:
//! (1) merge the vertex lists, (2) weld vertices closer than a threshold, (3) renumber the
//! faces, (4) drop degenerate and duplicate faces, (5) build the directed and undirected
//! edge lists. Every quad is split along the same diagonal whatever the geometry, so M0's
//! connectivity depends only on the template.

use std::sync::Arc;

use glam::DVec3;

use crate::geom::{CoonsPatch, CornerMismatch, triangle_grid};
use crate::mesh::TriMesh;
use crate::mesh::topology::{boundary_vertices, face_labels_by_vertex, repeated_triangles, undirected_edges};

/// One patch sampled on its grid.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PatchGrid {
    /// Patch name (`torso.waist_bust.front_left`, ...).
    pub name: String,
    /// Segments along `u` (the rings).
    pub nu: usize,
    /// Segments along `v` (the contours).
    pub nv: usize,
    /// `(nu + 1) (nv + 1)` points, m (world frame), row by row in `v`.
    pub points: Vec<DVec3>,
    /// The feature curves (and the runs of their control points) its boundary comes from:
    /// when none of those control points moves, the patch does not move much either.
    pub curves: Vec<CurveRef>,
    /// A three-sided patch: `nu = nv = n` segments per side, its `(n + 1) (n + 2) / 2`
    /// points row by row away from its first side (see [`TrianglePatch::grid`]).
    pub triangular: bool,
}

/// Control points `first..=last` of feature curve `curve` (a ring, contour, open curve or
/// line); `last` is clamped to the curve's last control point.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CurveRef {
    /// Curve name.
    pub curve: String,
    /// First control point.
    pub first: usize,
    /// Last control point.
    pub last: usize,
}

impl CurveRef {
    /// Every control point of `curve`.
    pub fn whole(curve: &str) -> Self {
        Self {
            curve: curve.to_string(),
            first: 0,
            last: usize::MAX,
        }
    }
}

/// Samples a curve given by `n + 1` samples at `t = k / n`; between samples, linear.
pub(super) struct Samples<'a>(pub(super) &'a [DVec3]);

impl crate::geom::ParametricCurve for Samples<'_> {
    fn sample(&self, t: f64) -> DVec3 {
        let n = self.0.len() - 1;
        let x = t.clamp(0.0, 1.0) * n as f64;
        let k = x.round();
        if (x - k).abs() < 1e-9 {
            return self.0[k as usize];
        }
        let i = (x.floor() as usize).min(n - 1);
        self.0[i].lerp(self.0[i + 1], x - i as f64)
    }
}

impl PatchGrid {
    /// The Coons patch over four sampled boundaries: `bottom` and `top` with `nu + 1`
    /// samples (u from 0 to 1), `left` and `right` with `nv + 1` (v from 0 to 1). Corners
    /// must meet within `tolerance`. Boundary grid points are the samples themselves.
    pub fn coons(name: &str, [bottom, top, left, right]: [&[DVec3]; 4], tolerance: f64) -> Result<Self, PatchError> {
        let nu = bottom.len().saturating_sub(1);
        let nv = left.len().saturating_sub(1);
        if nu == 0 || nv == 0 || top.len() != nu + 1 || right.len() != nv + 1 {
            return Err(PatchError::Counts {
                patch: name.to_string(),
                counts: [bottom.len(), top.len(), left.len(), right.len()],
            });
        }
        let patch = CoonsPatch::try_new(Samples(bottom), Samples(top), Samples(left), Samples(right), tolerance)
            .map_err(|e| PatchError::Corners(name.to_string(), e))?;
        let mut points = patch.grid(nu, nv);
        for i in 0..=nu {
            points[i] = bottom[i];
            points[nv * (nu + 1) + i] = top[i];
        }
        for j in 0..=nv {
            points[j * (nu + 1)] = left[j];
            points[j * (nu + 1) + nu] = right[j];
        }
        Ok(Self {
            name: name.to_string(),
            nu,
            nv,
            points,
            curves: Vec::new(),
            triangular: false,
        })
    }

    /// Whether its boundary is `[bottom, top, left, right]` (as given to [`Self::coons`]).
    pub fn sides_are(&self, [bottom, top, left, right]: [&[DVec3]; 4]) -> bool {
        if self.triangular {
            return false;
        }
        let w = self.nu + 1;
        let row = |j: usize| &self.points[j * w..(j + 1) * w];
        let column = |i: usize| (0..=self.nv).map(move |j| self.points[j * w + i]);
        bottom.len() == w
            && top.len() == w
            && left.len() == self.nv + 1
            && right.len() == self.nv + 1
            && row(0) == bottom
            && row(self.nv) == top
            && column(0).eq(left.iter().copied())
            && column(self.nu).eq(right.iter().copied())
    }

    /// Records the curves the boundary comes from.
    pub fn with_curves(mut self, curves: Vec<CurveRef>) -> Self {
        self.curves = curves;
        self
    }

    /// The two triangles of every grid cell (same diagonal everywhere), indices local to
    /// the patch, counter-clockwise about `du x dv`.
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        if self.triangular {
            return triangle_grid(self.nu);
        }
        let w = self.nu + 1;
        let id = |i: usize, j: usize| (j * w + i) as u32;
        let mut out = Vec::with_capacity(2 * self.nu * self.nv);
        for j in 0..self.nv {
            for i in 0..self.nu {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                out.push([a, b, c]);
                out.push([a, c, d]);
            }
        }
        out
    }
}

/// Why a patch cannot be built.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum PatchError {
    /// Boundary sample counts do not pair up.
    #[error("patch '{patch}': boundary sample counts {counts:?} (bottom, top, left, right) do not pair up")]
    Counts {
        /// Patch.
        patch: String,
        /// Counts.
        counts: [usize; 4],
    },
    /// Corners do not meet.
    #[error("patch '{0}': {1}")]
    Corners(String, CornerMismatch),
}

/// What stitching did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct StitchReport {
    /// Vertices of all patches together.
    pub input_vertices: usize,
    /// Vertices merged away by welding.
    pub welded: usize,
    /// Faces dropped for repeating a vertex after welding.
    pub degenerate_faces: usize,
    /// Faces dropped as duplicates of another.
    pub duplicate_faces: usize,
}

/// The stitched mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct M0 {
    /// Vertices and faces.
    pub mesh: TriMesh,
    /// The patch of each face.
    pub face_patch: Arc<Vec<u32>>,
    /// Patch names, by index.
    pub patch_names: Vec<String>,
    /// Every face's edges, in face order (`3 x faces`).
    pub directed_edges: Arc<Vec<[u32; 2]>>,
    /// Unique undirected edges, smaller index first, sorted.
    pub edges: Arc<Vec<[u32; 2]>>,
    /// What stitching did.
    pub report: StitchReport,
    /// The vertex each patch sample became (the patches' samples in order).
    pub welds: Vec<u32>,
    /// Whether each vertex is on the boundary (an opening: an end of an edge with one
    /// face), as [`boundary_vertices`] finds it; kept with the faces.
    pub boundary: Arc<Vec<bool>>,
    /// The patches of each vertex's faces, ascending ([`face_labels_by_vertex`]): shared by
    /// every M0 of the same faces (the collision's skipping reads it at every step).
    pub vertex_patches: Arc<Vec<Vec<u32>>>,
}

/// `x` as an unsigned key in the order [`f64::total_cmp`] gives (negatives, by their bits
/// flipped, below the positives, by their sign bit set).
fn total_key(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 { !bits } else { bits | 1 << 63 }
}

/// The root of `i` in a union-find forest, compressing the path.
pub(crate) fn find(parent: &mut [u32], i: u32) -> u32 {
    let mut r = i;
    while parent[r as usize] != r {
        r = parent[r as usize];
    }
    let mut i = i;
    while parent[i as usize] != r {
        let next = parent[i as usize];
        parent[i as usize] = r;
        i = next;
    }
    r
}

/// Welds points closer than `threshold` (distance `<= threshold`, transitively): returns
/// the new index of every point and the number of distinct points. New indices follow the
/// first appearance of each group, so the result is deterministic.
pub fn weld(points: &[DVec3], threshold: f64) -> (Vec<u32>, usize) {
    let n = points.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    // A total order (ties by index), so the unstable sort gives the one sorted order; sorted
    // as plain keys, not through the points (a quarter of the time at resolution 24).
    let mut keyed: Vec<(u64, u32)> = points
        .iter()
        .enumerate()
        .map(|(i, p)| (total_key(p.x), i as u32))
        .collect();
    keyed.sort_unstable();
    let order: Vec<u32> = keyed.into_iter().map(|(_, i)| i).collect();
    for (k, &i) in order.iter().enumerate() {
        let p = points[i as usize];
        for &j in &order[k + 1..] {
            let q = points[j as usize];
            if q.x - p.x > threshold {
                break;
            }
            if p.distance(q) <= threshold {
                let (ri, rj) = (find(&mut parent, i), find(&mut parent, j));
                // The smaller index is the root: groups are named by their first point.
                let (lo, hi) = (ri.min(rj), ri.max(rj));
                parent[hi as usize] = lo;
            }
        }
    }
    let mut new_id = vec![u32::MAX; n];
    let mut map = vec![0u32; n];
    let mut count = 0u32;
    for i in 0..n as u32 {
        let r = find(&mut parent, i) as usize;
        if new_id[r] == u32::MAX {
            new_id[r] = count;
            count += 1;
        }
        map[i as usize] = new_id[r];
    }
    (map, count as usize)
}

/// Stitches patches into M0 (\[collide\] section 3.1, steps 1-5: merge the vertex lists, weld
/// within `threshold` (m), renumber the faces, drop degenerate and duplicate faces, build
/// the directed and undirected edge lists).
pub fn stitch(patches: &[PatchGrid], threshold: f64) -> M0 {
    restitch(patches, threshold, None)
}

/// [`stitch`], given the patches and M0 of the framework before an edit: where the new
/// patches have the same names and grids and the welding joins the same samples, M0's
/// faces and edges are those of before (they depend on nothing else) and only its
/// positions are new.
pub fn restitch(patches: &[PatchGrid], threshold: f64, before: Option<(&[PatchGrid], &M0)>) -> M0 {
    let points: Vec<DVec3> = patches.iter().flat_map(|p| p.points.iter().copied()).collect();
    let (map, count) = weld(&points, threshold);
    let mut positions = vec![DVec3::ZERO; count];
    for (i, &m) in map.iter().enumerate().rev() {
        // The group's first point gives the position.
        positions[m as usize] = points[i];
    }
    let same_grids = |old: &[PatchGrid]| {
        old.len() == patches.len()
            && old
                .iter()
                .zip(patches)
                .all(|(a, b)| a.name == b.name && a.nu == b.nu && a.nv == b.nv)
    };
    if let Some((old, m0)) = before
        && m0.welds == map
        && same_grids(old)
    {
        return M0 {
            mesh: TriMesh {
                positions,
                triangles: m0.mesh.triangles.clone(),
            },
            welds: map,
            ..m0.clone_topology()
        };
    }
    let mut faces: Vec<([u32; 3], u32)> = Vec::new();
    let mut base = 0u32;
    for (p, patch) in patches.iter().enumerate() {
        faces.extend(patch.triangles().into_iter().map(|t| (t.map(|i| i + base), p as u32)));
        base += patch.points.len() as u32;
    }
    let mut report = StitchReport {
        input_vertices: points.len(),
        welded: points.len() - count,
        ..StitchReport::default()
    };
    // Degenerate faces out, then every face with the corners of an earlier one.
    let (kept, degenerate): (Vec<([u32; 3], u32)>, Vec<_>) = faces
        .into_iter()
        .map(|(t, p)| (t.map(|i| map[i as usize]), p))
        .partition(|(t, _)| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    report.degenerate_faces = degenerate.len();
    let repeated = repeated_triangles(&kept.iter().map(|(t, _)| *t).collect::<Vec<_>>());
    report.duplicate_faces = repeated.iter().filter(|r| **r).count();
    let (triangles, face_patch): (Vec<[u32; 3]>, Vec<u32>) = kept
        .into_iter()
        .zip(&repeated)
        .filter(|(_, r)| !**r)
        .map(|(f, _)| f)
        .unzip();
    let directed_edges: Vec<[u32; 2]> = triangles
        .iter()
        .flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]])
        .collect();
    let mesh = TriMesh { positions, triangles };
    let edges = undirected_edges(&mesh);
    let boundary = boundary_vertices(&mesh);
    let vertex_patches = Arc::new(face_labels_by_vertex(count, &mesh.triangles, &face_patch));
    M0 {
        mesh,
        vertex_patches,
        face_patch: Arc::new(face_patch),
        patch_names: patches.iter().map(|p| p.name.clone()).collect(),
        directed_edges: Arc::new(directed_edges),
        edges: Arc::new(edges),
        report,
        welds: map,
        boundary: Arc::new(boundary),
    }
}

impl M0 {
    /// Its faces' patches, names, edges and report, without the mesh and welds.
    fn clone_topology(&self) -> Self {
        Self {
            mesh: TriMesh::default(),
            face_patch: Arc::clone(&self.face_patch),
            patch_names: self.patch_names.clone(),
            directed_edges: Arc::clone(&self.directed_edges),
            edges: Arc::clone(&self.edges),
            report: self.report,
            welds: Vec::new(),
            boundary: Arc::clone(&self.boundary),
            vertex_patches: Arc::clone(&self.vertex_patches),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::total_key;

    /// The keys sort as `f64::total_cmp` does, over signed zeros, infinities, NaNs of both
    /// signs, subnormals, the extremes and numbers spread over every exponent.
    #[test]
    fn the_sort_key_orders_as_the_total_order_of_floats() {
        let mut xs = vec![
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::from_bits(1),
            -f64::from_bits(1),
            f64::MAX,
            f64::MIN,
            1.0,
            -1.0,
        ];
        let mut state = 0x9e3779b97f4a7c15u64;
        for _ in 0..2000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            xs.push(f64::from_bits(state));
        }
        for a in &xs {
            for b in xs.iter().step_by(7) {
                assert_eq!(total_key(*a).cmp(&total_key(*b)), a.total_cmp(b), "{a:e} vs {b:e}");
            }
        }
    }
}
