//! Geometry into Rerun's shapes: meshes with vertex colours, a mesh's edges as few
//! polylines, closed loops, face outlines.

use glam::DVec3;

use super::recording::OrderedRecording;
use crate::session::SinkError;

/// A mesh with smooth vertex normals and one colour per vertex.
pub(super) fn colored_mesh(mesh: &crate::mesh::TriMesh, colors: Vec<[u8; 3]>) -> rerun::Mesh3D {
    let normals: Vec<[f32; 3]> = mesh.vertex_normals().iter().map(|n| n.as_vec3().to_array()).collect();
    rerun::Mesh3D::new(mesh.positions_f32())
        .with_triangle_indices(mesh.triangles.iter().copied())
        .with_vertex_normals(normals)
        .with_vertex_colors(colors)
}

/// A mesh's edges as few polylines, every edge in exactly one: from each vertex in turn,
/// a walk along unused edges (the first unused one at each vertex, by edge order) until it
/// reaches a vertex with none left. The same segments as one two-point strip per edge, in
/// about half the points and far fewer strips; deterministic.
pub(super) fn edge_paths(positions: &[[f32; 3]], edges: &[[u32; 2]]) -> Vec<Vec<[f32; 3]>> {
    edge_walks(positions.len(), edges).along(positions)
}

/// The walks of [`edge_paths`], as the vertices they pass, one after another.
pub(super) struct Walks {
    /// Where each walk begins in `vertices`, and one past the last.
    start: Vec<u32>,
    /// The vertices of every walk.
    vertices: Vec<u32>,
}

impl Walks {
    /// Where each walk begins in [`Self::vertices`], and one past the last.
    pub(super) fn start(&self) -> &[u32] {
        &self.start
    }

    /// The vertices of every walk, one walk after another.
    pub(super) fn vertices(&self) -> &[u32] {
        &self.vertices
    }

    /// The points of each walk.
    pub(super) fn along(&self, positions: &[[f32; 3]]) -> Vec<Vec<[f32; 3]>> {
        self.start
            .windows(2)
            .map(|w| {
                (self.vertices[w[0] as usize..w[1] as usize].iter())
                    .map(|&v| positions[v as usize])
                    .collect()
            })
            .collect()
    }
}

/// The walks of [`edge_paths`] over `n` vertices.
pub(super) fn edge_walks(n: usize, edges: &[[u32; 2]]) -> Walks {
    // Incident edges of every vertex, by edge order (counting sort).
    let mut start = vec![0usize; n + 1];
    for &[a, b] in edges {
        start[a as usize + 1] += 1;
        start[b as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut incident = vec![0u32; 2 * edges.len()];
    for (e, &[a, b]) in edges.iter().enumerate() {
        for v in [a, b] {
            incident[fill[v as usize]] = e as u32;
            fill[v as usize] += 1;
        }
    }
    let mut next = start.clone();
    let mut used = vec![false; edges.len()];
    let mut unused_at = |v: usize, used: &[bool]| -> Option<u32> {
        while next[v] < start[v + 1] {
            let e = incident[next[v]];
            if !used[e as usize] {
                return Some(e);
            }
            next[v] += 1;
        }
        None
    };
    let mut walks = Walks {
        start: vec![0],
        vertices: Vec::with_capacity(2 * edges.len()),
    };
    for v in 0..n {
        while let Some(e) = unused_at(v, &used) {
            walks.vertices.push(v as u32);
            let (mut at, mut edge) = (v, e);
            loop {
                used[edge as usize] = true;
                let [a, b] = edges[edge as usize];
                at = if a as usize == at { b as usize } else { a as usize };
                walks.vertices.push(at as u32);
                match unused_at(at, &used) {
                    Some(e) => edge = e,
                    None => break,
                }
            }
            walks.start.push(walks.vertices.len() as u32);
        }
    }
    walks
}

pub(super) fn f32s(points: &[DVec3]) -> Vec<[f32; 3]> {
    points.iter().map(|p| p.as_vec3().to_array()).collect()
}

/// [`f32s`] as words: the bits of each point's x, y and z in turn (what a part's fields
/// are compared by, and what [`super::columns`] makes Rerun's arrays of).
pub(super) fn f32_words(points: &[DVec3]) -> Vec<u32> {
    points
        .iter()
        .flat_map(|p| p.as_vec3().to_array().map(f32::to_bits))
        .collect()
}

/// Logs the closed outlines of `faces` (indices into `triangles`, corners at `positions`)
/// at `path`, or clears it when there are none.
pub(super) fn log_face_outlines(
    rec: &OrderedRecording,
    path: &str,
    (triangles, positions): (&[[u32; 3]], &[DVec3]),
    faces: &[u32],
    (radius, colour): (f32, [u8; 3]),
) -> Result<(), SinkError> {
    if faces.is_empty() {
        return rec.clear(path);
    }
    let outlines: Vec<Vec<[f32; 3]>> = faces
        .iter()
        .map(|&f| closed(&triangles[f as usize].map(|v| positions[v as usize])))
        .collect();
    rec.log(
        path,
        &rerun::LineStrips3D::new(outlines)
            .with_radii([radius])
            .with_colors([colour]),
    )
}

pub(super) fn closed(points: &[DVec3]) -> Vec<[f32; 3]> {
    let mut v = f32s(points);
    if let Some(first) = v.first().copied() {
        v.push(first);
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every edge of a mesh (a grid with both diagonals here and there, a fan, a lone edge,
    /// an isolated vertex) is drawn exactly once by the paths, and nothing else is.
    #[test]
    fn edge_paths_draw_every_edge_once_and_nothing_else() {
        let w = 7;
        let mut positions: Vec<DVec3> = (0..w * w)
            .map(|k| DVec3::new((k % w) as f64, (k / w) as f64, 0.1 * ((k * 7919) % 13) as f64))
            .collect();
        let id = |i: usize, j: usize| (j * w + i) as u32;
        let mut edges = Vec::new();
        for j in 0..w {
            for i in 0..w {
                if i + 1 < w {
                    edges.push([id(i, j), id(i + 1, j)]);
                }
                if j + 1 < w {
                    edges.push([id(i, j + 1), id(i, j)]);
                }
                if i + 1 < w && j + 1 < w {
                    edges.push([id(i, j), id(i + 1, j + 1)]);
                    if (i + j) % 3 == 0 {
                        edges.push([id(i + 1, j), id(i, j + 1)]);
                    }
                }
            }
        }
        let lone = positions.len() as u32;
        positions.extend([
            DVec3::new(9.0, 9.0, 9.0),
            DVec3::new(9.5, 9.0, 9.0),
            DVec3::new(-3.0, 0.0, 0.0),
        ]);
        edges.push([lone, lone + 1]);
        let key = |p: [f32; 3]| p.map(f32::to_bits);
        let mut expected: Vec<_> = edges
            .iter()
            .map(|&[a, b]| {
                let (p, q) = (
                    key(positions[a as usize].as_vec3().to_array()),
                    key(positions[b as usize].as_vec3().to_array()),
                );
                if p <= q { (p, q) } else { (q, p) }
            })
            .collect();
        expected.sort_unstable();
        let points: Vec<[f32; 3]> = positions.iter().map(|p| p.as_vec3().to_array()).collect();
        let paths = edge_paths(&points, &edges);
        let mut drawn: Vec<_> = paths
            .iter()
            .flat_map(|path| path.windows(2).map(|s| (key(s[0]), key(s[1]))))
            .map(|(p, q)| if p <= q { (p, q) } else { (q, p) })
            .collect();
        drawn.sort_unstable();
        assert_eq!(drawn, expected);
        let drawn_points: usize = paths.iter().map(Vec::len).sum();
        assert!(
            drawn_points < 2 * edges.len() * 3 / 4,
            "{drawn_points} points for {} edges",
            edges.len()
        );
        assert!(edge_paths(&points, &[]).is_empty());
    }
}
