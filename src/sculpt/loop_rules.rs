//! Loop subdivision's rules (C. Loop, "Smooth subdivision surfaces based on triangles",
//! 1987), with a tunable weight, and one uniform step.
//!
//! A step puts a new point on every edge and splits each triangle `(a, b, c)` into four:
//! `(a, ab, ca)`, `(ab, b, bc)`, `(ca, bc, c)` and `(ab, bc, ca)`, keeping the orientation.
//!
//! * **Edge point** of an interior edge `ab` with opposite corners `c` and `d`:
//!   `3/8 (a + b) + 1/8 (c + d)`. On an opening (one face): the midpoint `(a + b) / 2`.
//! * **Old vertex** of valence `n` with neighbours `q_i`: `(1 - n w beta_n) p + w beta_n
//!   sum q_i`, where `beta_n = (5/8 - (3/8 + 1/4 cos(2 pi / n))^2) / n` is Loop's weight and
//!   `w` the tunable weight ([sculpt]'s shape factor): `w = 1` is Loop's scheme, `w = 0`
//!   keeps old vertices where they are (interpolating), values between pull less.
//!   On an opening, with its two neighbours along the opening: `(1 - w/4) p + w/8 (q0 + q1)`.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::mesh::TriMesh;

/// Loop's vertex weight `beta_n` for valence `n` (`3/16` at `n = 3`, `1/16` at `n = 6`).
pub fn loop_beta(n: usize) -> f64 {
    if n == 0 {
        return 0.0;
    }
    let c = 3.0 / 8.0 + 0.25 * (std::f64::consts::TAU / n as f64).cos();
    (5.0 / 8.0 - c * c) / n as f64
}

/// The edge point of `ab` with opposite corners `opposite` (two on an interior edge, one
/// or none on an opening: the midpoint).
pub fn edge_point(a: DVec3, b: DVec3, opposite: &[DVec3]) -> DVec3 {
    match opposite {
        [c, d] => 0.375 * (a + b) + 0.125 * (*c + *d),
        _ => 0.5 * (a + b),
    }
}

/// The new position of an interior old vertex `p` with neighbours `ring`.
pub fn interior_vertex(p: DVec3, ring: &[DVec3], weight: f64) -> DVec3 {
    let beta = weight * loop_beta(ring.len());
    let sum: DVec3 = ring.iter().copied().sum();
    (1.0 - ring.len() as f64 * beta) * p + beta * sum
}

/// The new position of an old vertex `p` on an opening, between `q0` and `q1` along it.
pub fn boundary_vertex(p: DVec3, q0: DVec3, q1: DVec3, weight: f64) -> DVec3 {
    (1.0 - 0.25 * weight) * p + 0.125 * weight * (q0 + q1)
}

/// Each undirected edge of a mesh once, with the corners opposite it.
#[derive(Clone, Debug, Default)]
pub(crate) struct EdgeTable {
    /// `(a, b)` with `a < b` -> the opposite corners of the faces on it (one or two).
    pub(crate) opposite: BTreeMap<(u32, u32), Vec<u32>>,
}

/// `(min, max)` of an edge.
pub(crate) fn key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

impl EdgeTable {
    pub(crate) fn new<'a>(triangles: impl IntoIterator<Item = &'a [u32; 3]>) -> Self {
        let mut opposite: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
        for t in triangles {
            for k in 0..3 {
                opposite
                    .entry(key(t[k], t[(k + 1) % 3]))
                    .or_default()
                    .push(t[(k + 2) % 3]);
            }
        }
        Self { opposite }
    }

    /// The Loop edge point of `(a, b)` at `positions`.
    pub(crate) fn edge_point(&self, positions: &[DVec3], a: u32, b: u32) -> DVec3 {
        let across: Vec<DVec3> = self
            .opposite
            .get(&key(a, b))
            .map(|o| o.iter().map(|&v| positions[v as usize]).collect())
            .unwrap_or_default();
        edge_point(positions[a as usize], positions[b as usize], &across)
    }

    /// Neighbours of every vertex (sorted), and for vertices on an opening their
    /// neighbours along it.
    pub(crate) fn rings(&self, vertices: usize) -> (Vec<Vec<u32>>, Vec<Vec<u32>>) {
        let mut ring = vec![Vec::new(); vertices];
        let mut along = vec![Vec::new(); vertices];
        for (&(a, b), opposite) in &self.opposite {
            ring[a as usize].push(b);
            ring[b as usize].push(a);
            if opposite.len() == 1 {
                along[a as usize].push(b);
                along[b as usize].push(a);
            }
        }
        (ring, along)
    }

    /// The new position of old vertex `v` by Loop's vertex rule (`None` where the rule
    /// does not apply: a non-manifold vertex on an opening).
    pub(crate) fn vertex_point(positions: &[DVec3], v: u32, ring: &[u32], along: &[u32], weight: f64) -> Option<DVec3> {
        let p = positions[v as usize];
        match along {
            [] => {
                let q: Vec<DVec3> = ring.iter().map(|&w| positions[w as usize]).collect();
                Some(interior_vertex(p, &q, weight))
            }
            [q0, q1] => Some(boundary_vertex(
                p,
                positions[*q0 as usize],
                positions[*q1 as usize],
                weight,
            )),
            _ => None,
        }
    }
}

/// The four children of triangle `[a, b, c]` with edge points `ab`, `bc`, `ca`.
pub(crate) fn quarter([a, b, c]: [u32; 3], [ab, bc, ca]: [u32; 3]) -> [[u32; 3]; 4] {
    [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
}

/// One uniform Loop step.
#[derive(Clone, Debug, PartialEq)]
pub struct UniformStep {
    /// The refined mesh: the old vertices first (same indices, moved by the vertex rule),
    /// then one per edge.
    pub mesh: TriMesh,
    /// Children `4 f .. 4 f + 3` come from face `f`.
    pub parent: Vec<u32>,
    /// For each new vertex, the edge it splits.
    pub edges: Vec<[u32; 2]>,
}

/// One step of uniform Loop subdivision with tunable `weight` (1: Loop's rules).
pub fn uniform_step(mesh: &TriMesh, weight: f64) -> UniformStep {
    let table = EdgeTable::new(&mesh.triangles);
    let n = mesh.positions.len();
    let (ring, along) = table.rings(n);
    let mut positions: Vec<DVec3> = (0..n as u32)
        .map(|v| {
            EdgeTable::vertex_point(&mesh.positions, v, &ring[v as usize], &along[v as usize], weight)
                .unwrap_or(mesh.positions[v as usize])
        })
        .collect();
    let mut index: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    let mut edges = Vec::with_capacity(table.opposite.len());
    for &(a, b) in table.opposite.keys() {
        index.insert((a, b), positions.len() as u32);
        positions.push(table.edge_point(&mesh.positions, a, b));
        edges.push([a, b]);
    }
    let mut triangles = Vec::with_capacity(4 * mesh.triangles.len());
    let mut parent = Vec::with_capacity(4 * mesh.triangles.len());
    for (f, &[a, b, c]) in mesh.triangles.iter().enumerate() {
        let mid = |x: u32, y: u32| index[&key(x, y)];
        triangles.extend(quarter([a, b, c], [mid(a, b), mid(b, c), mid(c, a)]));
        parent.extend([f as u32; 4]);
    }
    UniformStep {
        mesh: TriMesh { positions, triangles },
        parent,
        edges,
    }
}
