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

/// Items grouped by a vertex in one counting pass: `(first, grouped)`, where vertex `v`'s
/// items, in the order given, are `grouped[first[v]..first[v + 1]]` (`first` has one entry
/// past the last vertex, `n` vertices in all; an item of a vertex `n` or above is dropped).
/// Each group is then small (a vertex's edges), so sorting the groups one by one sorts
/// the whole by vertex first in linear time.
pub fn group_by_vertex<T: Copy>(n: usize, items: &[(u32, T)]) -> (Vec<usize>, Vec<T>) {
    let within = |v: u32| (v as usize) < n;
    let mut first = vec![0usize; n + 1];
    for &(v, _) in items.iter().filter(|(v, _)| within(*v)) {
        first[v as usize + 1] += 1;
    }
    for v in 0..n {
        first[v + 1] += first[v];
    }
    let Some(&(_, any)) = items.iter().find(|(v, _)| within(*v)) else {
        return (first, Vec::new());
    };
    let mut fill = first.clone();
    let mut grouped = vec![any; first[n]];
    for &(v, item) in items.iter().filter(|(v, _)| within(*v)) {
        grouped[fill[v as usize]] = item;
        fill[v as usize] += 1;
    }
    (first, grouped)
}

/// Items grouped by a key below `groups` (others dropped), in their order within each:
/// where each group begins (and one past the last), and the items.
pub fn group_by_key<T: Copy + Default>(
    groups: usize,
    items: impl Iterator<Item = (u32, T)> + Clone,
) -> (Vec<usize>, Vec<T>) {
    let mut first = vec![0usize; groups + 1];
    for (g, _) in items.clone() {
        if let Some(n) = first.get_mut(g as usize + 1) {
            *n += 1;
        }
    }
    for g in 0..groups {
        first[g + 1] += first[g];
    }
    let mut next = first.clone();
    let mut out = vec![T::default(); first[groups]];
    for (g, item) in items {
        if (g as usize) < groups {
            out[next[g as usize]] = item;
            next[g as usize] += 1;
        }
    }
    (first, out)
}

/// [`group_by_vertex`] with each vertex's group sorted and its repeats dropped: a sorted
/// set of pairs, as where each vertex's group begins (and one past the last) and the groups.
pub fn sorted_sets_by_vertex(n: usize, pairs: &[(u32, u32)]) -> (Vec<usize>, Vec<u32>) {
    let (mut first, mut grouped) = group_by_vertex(n, pairs);
    let mut kept = 0;
    for v in 0..n {
        let (from, to) = (first[v], first[v + 1]);
        first[v] = kept;
        grouped[from..to].sort_unstable();
        for i in from..to {
            if i == from || grouped[i] != grouped[i - 1] {
                grouped[kept] = grouped[i];
                kept += 1;
            }
        }
    }
    first[n] = kept;
    grouped.truncate(kept);
    (first, grouped)
}

/// The undirected edges of a mesh, each once, sorted: grouped by their smaller vertex,
/// then each vertex's few larger neighbours sorted and deduplicated.
pub fn undirected_edges(mesh: &TriMesh) -> Vec<[u32; 2]> {
    let ends: Vec<(u32, u32)> = (mesh.triangles.iter())
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect();
    let n = ends.iter().map(|e| e.0 as usize + 1).max().unwrap_or(0);
    let (first, larger) = sorted_sets_by_vertex(n, &ends);
    (0..n)
        .flat_map(|v| larger[first[v]..first[v + 1]].iter().map(move |&w| [v as u32, w]))
        .collect()
}

/// For each triangle, whether an earlier triangle has the same three corners (in any
/// order): grouped by the smallest corner, then each corner's few triangles sorted.
pub fn repeated_triangles(triangles: &[[u32; 3]]) -> Vec<bool> {
    let keys: Vec<(u32, (u32, u32, u32))> = triangles
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            let mut key = *tri;
            key.sort_unstable();
            (key[0], (key[1], key[2], t as u32))
        })
        .collect();
    let n = keys.iter().map(|k| k.0 as usize + 1).max().unwrap_or(0);
    let (first, mut grouped) = group_by_vertex(n, &keys);
    let mut repeated = vec![false; triangles.len()];
    for v in 0..n {
        let run = &mut grouped[first[v]..first[v + 1]];
        run.sort_unstable();
        for pair in run.windows(2) {
            if (pair[0].0, pair[0].1) == (pair[1].0, pair[1].1) {
                repeated[pair[1].2 as usize] = true;
            }
        }
    }
    repeated
}

/// Undirected edge records `(min vertex, max vertex, triangle, local edge)`, sorted (by
/// smaller vertex in one counting pass, then each vertex's few edges).
pub fn sorted_edges(mesh: &TriMesh) -> Vec<(u32, u32, u32, u8)> {
    let mut records = Vec::with_capacity(mesh.triangles.len() * 3);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3u8 {
            let (a, b) = (tri[k as usize], tri[(k as usize + 1) % 3]);
            records.push((a.min(b), (a.max(b), t as u32, k)));
        }
    }
    let n = records.iter().map(|r| r.0 as usize + 1).max().unwrap_or(0);
    let (first, mut grouped) = group_by_vertex(n, &records);
    let mut edges = Vec::with_capacity(grouped.len());
    for v in 0..n {
        let run = &mut grouped[first[v]..first[v + 1]];
        run.sort_unstable();
        edges.extend(run.iter().map(|&(b, t, k)| (v as u32, b, t, k)));
    }
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

/// Per vertex, the shortest and the longest of its edges (`[INFINITY, 0]` for a vertex of no
/// triangle).
pub fn incident_edge_extremes(positions: &[glam::DVec3], triangles: &[[u32; 3]]) -> Vec<[f64; 2]> {
    let mut out = vec![[f64::INFINITY, 0.0]; positions.len()];
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let l = positions[a].distance(positions[b]);
            for v in [a, b] {
                out[v] = [out[v][0].min(l), out[v][1].max(l)];
            }
        }
    }
    out
}

/// Whether each vertex of `mesh` is on its boundary (an end of an edge with one triangle);
/// all `false` for a mesh with an edge of three or more triangles.
pub fn boundary_vertices(mesh: &TriMesh) -> Vec<bool> {
    let mut boundary = vec![false; mesh.positions.len()];
    if let Ok(adjacency) = Adjacency::try_new(mesh) {
        for (tri, across) in mesh.triangles.iter().zip(&adjacency.neighbours) {
            for k in 0..3 {
                if across[k] == NO_NEIGHBOUR {
                    boundary[tri[k] as usize] = true;
                    boundary[tri[(k + 1) % 3] as usize] = true;
                }
            }
        }
    }
    boundary
}

/// The labels of each vertex's faces, each list ascending and without repeats (a face's
/// label is `face_label`: a patch, a group), for a mesh of `n` vertices.
pub fn face_labels_by_vertex(n: usize, triangles: &[[u32; 3]], face_label: &[u32]) -> Vec<Vec<u32>> {
    let mut lists = vec![Vec::new(); n];
    for (tri, &label) in triangles.iter().zip(face_label) {
        for &v in tri {
            let list: &mut Vec<u32> = &mut lists[v as usize];
            if !list.contains(&label) {
                list.push(label);
            }
        }
    }
    for list in &mut lists {
        list.sort_unstable();
    }
    lists
}
