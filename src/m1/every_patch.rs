//! M1's sqrt(3) step for any choice of refined patches, from one step over every patch
//! (docs/design.md section 7).
//!
//! What a split face becomes depends only on its own patch: it splits when its patch is
//! refined, and one of its edges flips when the face across is split and in the same patch,
//! that is, when the face across is in the same patch (the same patch is refined or not as
//! a whole). So one step with every patch refined, kept while M0's faces and patches stay
//! the same, holds what each face becomes, with the centroid of face `g` standing as vertex
//! `n0 + g`. The step for a given refinement ([`EveryPatch::step`]) then reads it face by
//! face: a face of a refined patch takes its faces from there, its centroids renumbered in
//! the order of the split faces; another keeps its own face. M1's edges come the same way,
//! with no sort: an old vertex's edges to the old vertices (M0's edges, but those every
//! face of a refined patch flips away), then to the centroids round it (in face order, the
//! centroids' order), then the edges between two centroids. The same step and the same
//! edges as [`super::sqrt3_step`] and a sort of M1's edges, bit for bit, by construction;
//! tests compare them on every choice of patches of a small mesh and on random sessions on
//! every body.

use std::sync::Arc;

use glam::DVec3;

use super::select::EdgeFaces;
use super::sqrt3::{Directed, split_faces};
use super::{Origin, Step, sqrt3::keep_last_flip_of_each_edge};
use crate::mesh::TriMesh;
use crate::mesh::topology::sorted_sets_by_vertex;

/// One step over every patch of M0, kept while M0's faces and patches stay the same.
#[derive(Debug)]
pub struct EveryPatch {
    /// M0's faces with their edges (the same `Arc` while M0's faces are the same).
    m0_edges: Arc<EdgeFaces>,
    /// The patch of each of M0's faces.
    face_patch: Vec<u32>,
    /// M0's vertex count.
    n0: usize,
    /// The faces each face becomes when its patch is refined, `start[f]..start[f + 1]`, the
    /// centroid of face `g` numbered `n0 + g`.
    start: Vec<u32>,
    triangles: Vec<[u32; 3]>,
    /// Every flipped edge, sorted by edge (an edge met twice keeps both, in order).
    flips: Vec<([u32; 2], [u32; 2])>,
    /// M0's edges, each once, sorted, and the patches whose refinement removes each
    /// (`gone_start[e]..gone_start[e + 1]` in `gone_by`): the edge stays while one of them
    /// is not refined, or always when none is listed.
    old_edges: Vec<[u32; 2]>,
    gone_start: Vec<u32>,
    gone_by: Vec<u32>,
    /// Per M0 vertex, the faces whose centroid it joins, ascending.
    joins_start: Vec<usize>,
    joins: Vec<u32>,
    /// Per face, the later faces whose centroid its own joins, ascending.
    pairs_start: Vec<usize>,
    pairs: Vec<u32>,
}

impl EveryPatch {
    /// The step over every patch of `m0` (whose faces and edges `m0_edges` holds).
    pub fn new(m0: &TriMesh, m0_edges: &Arc<EdgeFaces>, face_patch: &[u32]) -> Self {
        let n0 = m0.positions.len();
        let faces = m0.triangles.len();
        let directed = Directed::new(m0);
        let centroid_of: Vec<Option<u32>> = (0..faces).map(|f| Some((n0 + f) as u32)).collect();
        let every = split_faces(m0, face_patch, &|_| true, &directed, &centroid_of);
        let start = every.start;
        let triangles = every.triangles;
        // The edges of each face's faces that meet a centroid.
        let (mut joins, mut pairs) = (Vec::new(), Vec::new());
        for t in &triangles {
            for k in 0..3 {
                let (a, b) = (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]));
                match ((a as usize) < n0, (b as usize) < n0) {
                    (true, false) => joins.push((a, b - n0 as u32)),
                    (false, false) => pairs.push((a - n0 as u32, b - n0 as u32)),
                    _ => {}
                }
            }
        }
        let (joins_start, joins) = sorted_sets_by_vertex(n0, &joins);
        let (pairs_start, pairs) = sorted_sets_by_vertex(faces, &pairs);
        // M0's edges: one stays when a face of it keeps it once its patch is refined (or
        // while the patch of a face that flips it is not).
        let keeps = |t: u32, [a, b]: [u32; 2]| {
            let made = &triangles[start[t as usize] as usize..start[t as usize + 1] as usize];
            made.iter()
                .any(|m| (0..3).any(|k| [m[k].min(m[(k + 1) % 3]), m[k].max(m[(k + 1) % 3])] == [a, b]))
        };
        let (mut old_edges, mut gone_start, mut gone_by) = (Vec::new(), vec![0u32], Vec::new());
        for group in m0_edges.records().chunk_by(|a, b| (a.0, a.1) == (b.0, b.1)) {
            let edge = [group[0].0, group[0].1];
            old_edges.push(edge);
            if !group.iter().any(|r| keeps(r.2, edge)) {
                let mut by: Vec<u32> = group.iter().map(|r| face_patch[r.2 as usize]).collect();
                by.sort_unstable();
                by.dedup();
                gone_by.extend(by);
            }
            gone_start.push(gone_by.len() as u32);
        }
        Self {
            m0_edges: Arc::clone(m0_edges),
            face_patch: face_patch.to_vec(),
            n0,
            start,
            triangles,
            flips: every.flips,
            old_edges,
            gone_start,
            gone_by,
            joins_start,
            joins,
            pairs_start,
            pairs,
        }
    }

    /// Whether it was made over M0's faces `m0_edges` with these patches.
    pub fn fits(&self, m0: &TriMesh, m0_edges: &Arc<EdgeFaces>, face_patch: &[u32]) -> bool {
        self.n0 == m0.positions.len() && Arc::ptr_eq(&self.m0_edges, m0_edges) && self.face_patch == face_patch
    }

    /// The sqrt(3) step of `m0` over the patches `refine` selects, as
    /// [`super::sqrt3_step`] makes it with the old vertices kept, and the refined mesh's
    /// undirected edges, each once, sorted.
    pub fn step(&self, m0: &TriMesh, refine: &[bool]) -> (Step, Vec<[u32; 2]>) {
        let n0 = self.n0;
        let refined = |p: u32| refine.get(p as usize).copied().unwrap_or(false);
        let split: Vec<bool> = self.face_patch.iter().map(|&p| refined(p)).collect();
        let new = split.iter().filter(|&&s| s).count();
        let mut positions: Vec<DVec3> = Vec::with_capacity(n0 + new);
        positions.extend_from_slice(&m0.positions);
        let mut origin = Vec::with_capacity(n0 + new);
        origin.resize(n0, Origin::Old);
        let mut centroid_of = vec![None; split.len()];
        for (f, t) in m0.triangles.iter().enumerate() {
            if split[f] {
                let [a, b, c] = t.map(|v| m0.positions[v as usize]);
                centroid_of[f] = Some(positions.len() as u32);
                positions.push((a + b + c) / 3.0);
                origin.push(Origin::Centroid(*t));
            }
        }
        let at = |v: u32| {
            if (v as usize) < n0 {
                v
            } else {
                centroid_of[v as usize - n0].unwrap_or(v)
            }
        };
        let mut triangles = Vec::with_capacity(m0.triangles.len() + 2 * (positions.len() - n0));
        let mut patches = Vec::with_capacity(triangles.capacity());
        for (f, t) in m0.triangles.iter().enumerate() {
            let p = self.face_patch[f];
            if split[f] {
                let made = &self.triangles[self.start[f] as usize..self.start[f + 1] as usize];
                triangles.extend(made.iter().map(|m| m.map(at)));
                patches.extend(std::iter::repeat_n(p, made.len()));
            } else {
                triangles.push(*t);
                patches.push(p);
            }
        }
        let mut flips: Vec<([u32; 2], [u32; 2])> = (self.flips.iter())
            .filter(|(_, [f, _])| split[*f as usize])
            .copied()
            .collect();
        keep_last_flip_of_each_edge(&mut flips);
        let step = Step {
            mesh: TriMesh { positions, triangles },
            face_patch: patches,
            origin,
            centroid_of,
            flips,
            smoothed: Vec::new(),
        };
        let edges = self.edges(&step, &split, refined);
        (step, edges)
    }

    /// The undirected edges of `step`, each once, sorted: per old vertex its edges to old
    /// vertices that stay, then to the centroids round it; then the edges between two
    /// centroids.
    fn edges(&self, step: &Step, split: &[bool], refined: impl Fn(u32) -> bool) -> Vec<[u32; 2]> {
        let n0 = self.n0;
        let centroid = |f: u32| step.centroid_of[f as usize];
        let mut edges = Vec::with_capacity(self.old_edges.len() + 4 * (step.mesh.positions.len() - n0));
        let mut e = 0;
        for u in 0..n0 as u32 {
            while let Some(&edge) = self.old_edges.get(e).filter(|edge| edge[0] == u) {
                let gone = &self.gone_by[self.gone_start[e] as usize..self.gone_start[e + 1] as usize];
                if gone.is_empty() || gone.iter().any(|&p| !refined(p)) {
                    edges.push(edge);
                }
                e += 1;
            }
            let joins = &self.joins[self.joins_start[u as usize]..self.joins_start[u as usize + 1]];
            edges.extend(joins.iter().filter_map(|&f| centroid(f)).map(|m| [u, m]));
        }
        for (f, &split) in split.iter().enumerate() {
            if let (true, Some(m)) = (split, centroid(f as u32)) {
                let pairs = &self.pairs[self.pairs_start[f]..self.pairs_start[f + 1]];
                edges.extend(pairs.iter().filter_map(|&g| centroid(g)).map(|n| [m, n]));
            }
        }
        edges
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::m1::{Smoothing, sqrt3_step};
    use crate::mesh::topology::undirected_edges;

    /// A 9 x 9 grid of squares, each cut by one diagonal or the other, in 3 x 3 patches
    /// numbered out of order; with a face repeated (a mesh folded on itself) and one with
    /// a corner twice.
    fn grid() -> (TriMesh, Vec<u32>) {
        let n = 9u32;
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| DVec3::new(f64::from(i), f64::from(j), f64::from(i * j % 5) * 0.1)))
            .collect();
        let (mut triangles, mut face_patch) = (Vec::new(), Vec::new());
        for j in 0..n {
            for i in 0..n {
                let v = |di: u32, dj: u32| (j + dj) * (n + 1) + i + di;
                let patch = (i / 3 * 7 + j / 3 * 4) % 9;
                if (i + j) % 2 == 0 {
                    triangles.extend([[v(0, 0), v(1, 0), v(1, 1)], [v(0, 0), v(1, 1), v(0, 1)]]);
                } else {
                    triangles.extend([[v(0, 0), v(1, 0), v(0, 1)], [v(1, 0), v(1, 1), v(0, 1)]]);
                }
                face_patch.extend([patch, patch]);
            }
        }
        triangles.push(triangles[40]);
        face_patch.push(face_patch[40]);
        triangles.push([3, 3, 4]);
        face_patch.push(face_patch[3]);
        (TriMesh { positions, triangles }, face_patch)
    }

    #[test]
    fn every_choice_of_patches_gives_the_step_and_the_sorted_edges_a_whole_step_gives() {
        let (mesh, face_patch) = grid();
        let every = EveryPatch::new(&mesh, &EdgeFaces::of(&mesh, None), &face_patch);
        // Every subset of the 9 patches.
        for set in 0u32..512 {
            let refine: Vec<bool> = (0..9).map(|p| set >> p & 1 == 1).collect();
            let whole = sqrt3_step(&mesh, &face_patch, &refine, Smoothing::None);
            let (step, edges) = every.step(&mesh, &refine);
            assert_eq!(step, whole, "patches {set:09b}");
            assert_eq!(edges, undirected_edges(&whole.mesh), "patches {set:09b}");
        }
    }
}
