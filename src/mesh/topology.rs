//! Triangle adjacency across edges, built once per mesh from a sorted edge list.

use super::TriMesh;

/// Marker for "no neighbour" (a boundary edge).
pub const NO_NEIGHBOUR: u32 = u32::MAX;

/// For each triangle and each of its edges (`k` runs from corner `k` to corner `k+1`),
/// the triangle on the other side.
#[derive(Clone, Debug, PartialEq)]
pub struct Adjacency {
    /// `neighbours[t][k]`: triangle across edge `k` of `t`, or [`NO_NEIGHBOUR`].
    pub neighbours: Vec<[u32; 3]>,
    /// Number of edges with one triangle.
    pub boundary_edges: usize,
}

/// An undirected edge shared by more than two triangles.
#[derive(Clone, Debug, PartialEq)]
pub struct NonManifoldEdge {
    /// The edge's vertices (0-based, smaller first).
    pub vertices: [u32; 2],
    /// The triangles that share it.
    pub triangles: Vec<u32>,
}

/// Undirected edge records `(min vertex, max vertex, triangle, local edge)`, sorted.
pub fn sorted_edges(mesh: &TriMesh) -> Vec<(u32, u32, u32, u8)> {
    let mut edges = Vec::with_capacity(mesh.triangles.len() * 3);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3u8 {
            let (a, b) = (tri[k as usize], tri[(k as usize + 1) % 3]);
            edges.push((a.min(b), a.max(b), t as u32, k));
        }
    }
    edges.sort_unstable();
    edges
}

impl Adjacency {
    /// Builds the adjacency; fails on the first edge shared by more than two triangles.
    pub fn try_new(mesh: &TriMesh) -> Result<Self, NonManifoldEdge> {
        let edges = sorted_edges(mesh);
        let mut neighbours = vec![[NO_NEIGHBOUR; 3]; mesh.triangles.len()];
        let mut boundary_edges = 0;
        for group in edges.chunk_by(|a, b| (a.0, a.1) == (b.0, b.1)) {
            match group {
                [_] => boundary_edges += 1,
                [(_, _, t0, k0), (_, _, t1, k1)] => {
                    neighbours[*t0 as usize][*k0 as usize] = *t1;
                    neighbours[*t1 as usize][*k1 as usize] = *t0;
                }
                _ => {
                    return Err(NonManifoldEdge {
                        vertices: [group[0].0, group[0].1],
                        triangles: group.iter().map(|e| e.2).collect(),
                    });
                }
            }
        }
        Ok(Self {
            neighbours,
            boundary_edges,
        })
    }

    /// The local edge of triangle `t` that leads to triangle `other`.
    pub fn edge_to(&self, t: usize, other: u32) -> Option<usize> {
        self.neighbours[t].iter().position(|&n| n == other)
    }
}
