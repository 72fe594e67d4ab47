//! The user's cut lines as seams: the mesh split along them, exactly.
//!
//! A plane cut (`cut NAME at= normal=`) splits every face its plane crosses. A polyline cut
//! (`cut NAME through=P;Q;...`, its points on mesh vertices) splits, between each two
//! consecutive points `A` and `B`, the faces crossed by the plane through `A` and `B` that
//! holds the surface's normal there: the faces facing the same way as the surface at `A` and
//! `B`, whose crossing lies between them (along `AB`) and within half `|AB|` of the segment;
//! then every face sharing a split edge with them, so that no T-junction is left. A split
//! face gives two or three faces of its patch; the edges the plane leaves in the mesh are
//! the seam.

use std::collections::BTreeMap;

use glam::DVec3;

/// A cut line's shape.
#[derive(Clone, Debug, PartialEq)]
pub enum CutShape {
    /// The section by the plane through `point` with `normal`.
    Plane {
        /// A point of the plane, m.
        point: DVec3,
        /// Its normal (any length but zero).
        normal: DVec3,
    },
    /// Through these mesh vertices, in order.
    Through(Vec<u32>),
}

/// A named cut line.
#[derive(Clone, Debug, PartialEq)]
pub struct CutLine {
    /// Its name (the seam's curve name).
    pub name: String,
    /// Its shape.
    pub shape: CutShape,
}

/// A mesh being split: positions, triangles, the patch of each triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SplitMesh {
    /// Positions, m.
    pub positions: Vec<DVec3>,
    /// A second position per vertex carried along (the surfaced mesh's): a new vertex gets
    /// the point at its edge's same fraction.
    pub surfaced: Vec<DVec3>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
    /// The patch of each triangle.
    pub face_patch: Vec<u32>,
}

/// Distances below this (m) count as on the plane.
const ON_PLANE: f64 = 1e-9;

/// A vertex of a face to split nearer the plane than this fraction of its shortest edge is
/// moved onto the plane.
const SNAP: f64 = 0.1;

impl SplitMesh {
    /// Splits the mesh along `cut`; returns the seam's edges (vertex pairs, smaller first,
    /// sorted).
    pub fn split(&mut self, cut: &CutShape) -> Vec<[u32; 2]> {
        let mut seam = Vec::new();
        match cut {
            CutShape::Plane { point, normal } => {
                let n = normal.normalize_or_zero();
                let all: Vec<usize> = (0..self.triangles.len()).collect();
                seam.extend(self.split_faces(*point, n, &all));
            }
            CutShape::Through(points) => {
                for w in points.windows(2) {
                    let (a, b) = (w[0] as usize, w[1] as usize);
                    if a == b || a >= self.positions.len() || b >= self.positions.len() {
                        continue;
                    }
                    let (pa, pb) = (self.positions[a], self.positions[b]);
                    let up = self.vertex_normal(a as u32) + self.vertex_normal(b as u32);
                    let along = pb - pa;
                    let n = along.cross(up).normalize_or_zero();
                    if n == DVec3::ZERO {
                        continue;
                    }
                    let t = along / along.length();
                    let reach = 0.5 * along.length();
                    let chosen: Vec<usize> = (0..self.triangles.len())
                        .filter(|&f| {
                            let [p, q, r] = self.triangles[f].map(|v| self.positions[v as usize]);
                            if (q - p).cross(r - p).dot(up) <= 0.0 {
                                return false;
                            }
                            let Some((x, y)) = crossing(pa, n, [p, q, r]) else {
                                return false;
                            };
                            let mid = 0.5 * (x + y);
                            let s = (mid - pa).dot(t);
                            let off = (mid - pa - s * t).length();
                            (0.0..=along.length()).contains(&s) && off <= reach
                        })
                        .collect();
                    seam.extend(self.split_faces(pa, n, &chosen));
                }
            }
        }
        seam.sort_unstable();
        seam.dedup();
        seam
    }

    /// Area-weighted normal at a vertex.
    fn vertex_normal(&self, v: u32) -> DVec3 {
        self.triangles
            .iter()
            .filter(|t| t.contains(&v))
            .map(|t| {
                let [p, q, r] = t.map(|i| self.positions[i as usize]);
                (q - p).cross(r - p)
            })
            .sum()
    }

    /// Splits faces `chosen` (and any face left with a split edge) by the plane through
    /// `point` with unit normal `n`; returns the edges left on the plane inside them.
    fn split_faces(&mut self, point: DVec3, n: DVec3, chosen: &[usize]) -> Vec<[u32; 2]> {
        // A vertex nearer the plane than a tenth of its shortest edge is moved onto it, so
        // that no split leaves a sliver (a triangle with an edge a hair long).
        let edges = crate::mesh::topology::incident_edge_extremes(&self.positions, &self.triangles);
        let touched: std::collections::BTreeSet<u32> = chosen.iter().flat_map(|&f| self.triangles[f]).collect();
        let mut d = Vec::with_capacity(self.positions.len());
        for (v, p) in self.positions.iter_mut().enumerate() {
            let x = (*p - point).dot(n);
            if x.abs() < ON_PLANE || (touched.contains(&(v as u32)) && x.abs() < SNAP * edges[v][0]) {
                *p -= x * n;
                d.push(0.0);
            } else {
                d.push(x);
            }
        }
        let crosses = |a: u32, b: u32| {
            (d[a as usize] < 0.0 && d[b as usize] > 0.0) || (d[a as usize] > 0.0 && d[b as usize] < 0.0)
        };
        let mut todo = vec![false; self.triangles.len()];
        for &f in chosen {
            todo[f] = true;
        }
        // Close over shared split edges.
        let mut split_edges: std::collections::BTreeSet<[u32; 2]> = Default::default();
        loop {
            let before = split_edges.len();
            for (f, t) in self.triangles.iter().enumerate() {
                if !todo[f] {
                    let touches = (0..3).any(|k| {
                        let (a, b) = (t[k], t[(k + 1) % 3]);
                        split_edges.contains(&[a.min(b), a.max(b)])
                    });
                    if !touches {
                        continue;
                    }
                    todo[f] = true;
                }
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    if crosses(a, b) {
                        split_edges.insert([a.min(b), a.max(b)]);
                    }
                }
            }
            if split_edges.len() == before {
                break;
            }
        }
        // One new vertex per split edge.
        let mut new_vertex: BTreeMap<[u32; 2], u32> = BTreeMap::new();
        for &[a, b] in &split_edges {
            let (da, db) = (d[a as usize], d[b as usize]);
            let s = da / (da - db);
            let p = self.positions[a as usize].lerp(self.positions[b as usize], s);
            let q = self.surfaced[a as usize].lerp(self.surfaced[b as usize], s);
            new_vertex.insert([a, b], self.positions.len() as u32);
            self.positions.push(p);
            self.surfaced.push(q);
        }
        let on = |v: u32| v as usize >= d.len() || d[v as usize] == 0.0;
        let mut seam = Vec::new();
        for (f, _) in todo.iter().enumerate().filter(|(_, t)| **t) {
            let t = self.triangles[f];
            let patch = self.face_patch[f];
            // The face's corners with the new points between them, in order.
            let mut ring: Vec<u32> = Vec::with_capacity(5);
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                ring.push(a);
                if let Some(&m) = new_vertex.get(&[a.min(b), a.max(b)]) {
                    ring.push(m);
                }
            }
            let cut_points: Vec<usize> = (0..ring.len()).filter(|&i| on(ring[i])).collect();
            if cut_points.len() != 2 {
                continue;
            }
            let (i, j) = (cut_points[0], cut_points[1]);
            if (j - i) == 1 || (i == 0 && j == ring.len() - 1) {
                // The two points are neighbours on the ring: an edge of the face on the
                // plane, nothing to split.
                let (a, b) = (ring[i], ring[j]);
                seam.push([a.min(b), a.max(b)]);
                continue;
            }
            // Two polygons, ring[i..=j] and ring[j..] + ring[..=i], each fanned from its first.
            let first: Vec<u32> = ring[i..=j].to_vec();
            let second: Vec<u32> = ring[j..].iter().chain(&ring[..=i]).copied().collect();
            let mut pieces = Vec::new();
            for poly in [first, second] {
                for k in 1..poly.len() - 1 {
                    pieces.push([poly[0], poly[k], poly[k + 1]]);
                }
            }
            let (a, b) = (ring[i], ring[j]);
            seam.push([a.min(b), a.max(b)]);
            self.triangles[f] = pieces[0];
            for p in pieces.into_iter().skip(1) {
                self.triangles.push(p);
                self.face_patch.push(patch);
            }
        }
        seam
    }
}

/// Where the plane through `point` with normal `n` crosses triangle `[p, q, r]`: the two ends
/// of the crossing, or `None` when it does not cross it.
fn crossing(point: DVec3, n: DVec3, corners: [DVec3; 3]) -> Option<(DVec3, DVec3)> {
    let d = corners.map(|c| {
        let x = (c - point).dot(n);
        if x.abs() < ON_PLANE { 0.0 } else { x }
    });
    let mut ends = Vec::with_capacity(3);
    for k in 0..3 {
        let (a, b) = (k, (k + 1) % 3);
        if d[a] == 0.0 {
            ends.push(corners[a]);
        }
        if (d[a] < 0.0 && d[b] > 0.0) || (d[a] > 0.0 && d[b] < 0.0) {
            ends.push(corners[a].lerp(corners[b], d[a] / (d[a] - d[b])));
        }
    }
    (ends.len() == 2).then(|| (ends[0], ends[1]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat square grid in the `z = 0` plane, `n` cells a side, facing `+z`.
    fn grid(n: usize) -> SplitMesh {
        let mut m = SplitMesh::default();
        for j in 0..=n {
            for i in 0..=n {
                m.positions.push(DVec3::new(i as f64, j as f64, 0.0));
            }
        }
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        for j in 0..n {
            for i in 0..n {
                m.triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                m.triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
                m.face_patch.extend([0, 0]);
            }
        }
        m.surfaced = m.positions.clone();
        m
    }

    #[test]
    fn a_plane_splits_a_grid_into_two_halves_along_it() {
        let mut m = grid(4);
        let area = |m: &SplitMesh| -> f64 {
            m.triangles
                .iter()
                .map(|t| {
                    let [p, q, r] = t.map(|v| m.positions[v as usize]);
                    0.5 * (q - p).cross(r - p).z
                })
                .sum()
        };
        let seam = m.split(&CutShape::Plane {
            point: DVec3::new(1.3, 0.0, 0.0),
            normal: DVec3::new(1.0, 0.2, 0.0),
        });
        assert!(
            (area(&m) - 16.0).abs() < 1e-12,
            "area kept, every face counter-clockwise"
        );
        assert!(m.triangles.iter().all(|t| {
            let [p, q, r] = t.map(|v| m.positions[v as usize]);
            (q - p).cross(r - p).z > 0.0
        }));
        // Every seam edge lies on the plane, and together they run across the grid.
        let n = DVec3::new(1.0, 0.2, 0.0).normalize();
        let length: f64 = seam
            .iter()
            .map(|&[a, b]| {
                let (p, q) = (m.positions[a as usize], m.positions[b as usize]);
                assert!(((p - DVec3::new(1.3, 0.0, 0.0)).dot(n)).abs() < 1e-9);
                p.distance(q)
            })
            .sum();
        // The line x + 0.2 y = 1.3 from y = 0 to y = 4: length 4 / cos(atan 0.2).
        assert!((length - 4.0 * (1.0f64 + 0.04).sqrt()).abs() < 1e-9, "{length}");
    }

    #[test]
    fn a_polyline_cut_stops_at_its_points() {
        let mut m = grid(6);
        let id = |i: u32, j: u32| j * 7 + i;
        let seam = m.split(&CutShape::Through(vec![id(1, 1), id(4, 3)]));
        let length: f64 = seam
            .iter()
            .map(|&[a, b]| m.positions[a as usize].distance(m.positions[b as usize]))
            .sum();
        assert!(
            (length - 13f64.sqrt()).abs() < 1e-9,
            "the segment from (1,1) to (4,3): {length}"
        );
    }
}
