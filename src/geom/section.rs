//! Plane sections of a triangle mesh as ordered polylines.
//!
//! A vertex on the plane counts as being on its positive side (a symbolic perturbation),
//! so every edge is either crossed or not and each crossed triangle holds exactly one
//! segment. The crossing point of an edge is computed from its endpoints in index order,
//! so the two triangles that share the edge produce the same point bit for bit, and the
//! walk from triangle to triangle goes through the mesh adjacency: no point matching
//! with a tolerance anywhere.

use glam::DVec3;

use super::Plane;
use super::height_bands::HeightBands;
use super::polygon;
use crate::mesh::TriMesh;
use crate::mesh::topology::{Adjacency, NO_NEIGHBOUR};

/// One connected piece of a section.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionLoop {
    /// Points in order, in the mesh's units (m in drape); a closed loop does not repeat its
    /// first point.
    pub points: Vec<DVec3>,
    /// Closed (the normal case on a closed mesh) or open (the mesh has a boundary there).
    pub closed: bool,
}

impl SectionLoop {
    /// Length (mesh units), including the closing segment of a closed loop.
    pub fn length(&self) -> f64 {
        let open: f64 = self.points.windows(2).map(|w| w[0].distance(w[1])).sum();
        match (self.closed, self.points.first(), self.points.last()) {
            (true, Some(a), Some(b)) => open + a.distance(*b),
            _ => open,
        }
    }
}

/// Intersects `mesh` with `plane`. Closed loops run counter-clockwise seen from the
/// normal's side and start at their point of largest `u` ([`Plane::frame`]; for a
/// horizontal plane, the front-most point). Loops come in the order of their first
/// triangle, so the output is deterministic.
pub fn section_mesh(mesh: &TriMesh, adjacency: &Adjacency, plane: &Plane) -> Vec<SectionLoop> {
    section_of(mesh, adjacency, plane, 0..mesh.triangles.len())
}

/// [`section_mesh`], the same loops bit for bit, looking only at the triangles `bands`
/// lists at the plane's height when the plane is horizontal (normal exactly `+y`) and
/// `bands` [fit](HeightBands::fit) the mesh; any other plane, or a mesh changed since its
/// bands were made, is cut by [`section_mesh`]. With finite coordinates a horizontal plane at `y` gives a vertex the
/// signed distance `p.y - y` exactly, so only triangles with `min_y < y <= max_y` are
/// crossed, and the band of `y` lists every one of them.
pub fn section_mesh_banded(
    mesh: &TriMesh,
    adjacency: &Adjacency,
    bands: &HeightBands,
    plane: &Plane,
) -> Vec<SectionLoop> {
    if plane.normal != DVec3::Y || !bands.fit(mesh) {
        return section_mesh(mesh, adjacency, plane);
    }
    section_of(
        mesh,
        adjacency,
        plane,
        bands.at(plane.offset).iter().map(|&t| t as usize),
    )
}

/// The section through the triangles `candidates` (ascending; a superset of the crossed
/// ones).
fn section_of(
    mesh: &TriMesh,
    adjacency: &Adjacency,
    plane: &Plane,
    candidates: impl Iterator<Item = usize>,
) -> Vec<SectionLoop> {
    let distance = |v: u32| plane.signed_distance(mesh.positions[v as usize]);
    let positive = |v: u32| distance(v) >= 0.0;
    let crossed_edges = |t: usize| -> ([usize; 2], usize) {
        let tri = mesh.triangles[t];
        let mut found = [0usize; 2];
        let mut count = 0;
        for k in 0..3 {
            if positive(tri[k]) != positive(tri[(k + 1) % 3]) && count < 2 {
                found[count] = k;
                count += 1;
            }
        }
        (found, count)
    };
    let crossing = |t: usize, k: usize| -> DVec3 {
        let tri = mesh.triangles[t];
        let (a, b) = (tri[k], tri[(k + 1) % 3]);
        let (lo, hi) = (a.min(b), a.max(b));
        let (d_lo, d_hi) = (distance(lo), distance(hi));
        let s = d_lo / (d_lo - d_hi);
        let (p_lo, p_hi) = (mesh.positions[lo as usize], mesh.positions[hi as usize]);
        p_lo + (p_hi - p_lo) * s
    };
    // Local edge of triangle `t` with the vertex pair of edge `k` of triangle `from`.
    let matching_edge = |t: usize, from: usize, k: usize| -> Option<usize> {
        let f = mesh.triangles[from];
        let (a, b) = (f[k], f[(k + 1) % 3]);
        let tri = mesh.triangles[t];
        (0..3).find(|&j| {
            let (c, d) = (tri[j], tri[(j + 1) % 3]);
            (c == a && d == b) || (c == b && d == a)
        })
    };

    let mut visited = vec![false; mesh.triangles.len()];
    let mut loops = Vec::new();
    for start in candidates {
        if visited[start] {
            continue;
        }
        let (edges, count) = crossed_edges(start);
        if count != 2 {
            continue;
        }
        visited[start] = true;
        // Walk forward out of edge[1], then (if the walk ends on a boundary) backward out of edge[0].
        let mut forward = vec![crossing(start, edges[0]), crossing(start, edges[1])];
        let walk = |exit_triangle: usize, exit_edge: usize, visited: &mut Vec<bool>, out: &mut Vec<DVec3>| -> bool {
            let (mut t, mut k) = (exit_triangle, exit_edge);
            loop {
                let next = adjacency.neighbours[t][k];
                if next == NO_NEIGHBOUR {
                    return false;
                }
                let n = next as usize;
                if n == start {
                    return true;
                }
                if visited[n] {
                    return false;
                }
                visited[n] = true;
                let Some(entry) = matching_edge(n, t, k) else {
                    return false;
                };
                let (edges_n, count_n) = crossed_edges(n);
                if count_n != 2 {
                    return false;
                }
                let exit = if edges_n[0] == entry { edges_n[1] } else { edges_n[0] };
                out.push(crossing(n, exit));
                t = n;
                k = exit;
            }
        };
        let closed = walk(start, edges[1], &mut visited, &mut forward);
        let mut points = if closed {
            forward.pop(); // the walk came back to the first crossing
            forward
        } else {
            let mut backward = Vec::new();
            walk(start, edges[0], &mut visited, &mut backward);
            backward.reverse();
            backward.extend(forward);
            backward
        };
        points.dedup();
        if closed && points.len() > 1 && points.first() == points.last() {
            points.pop();
        }
        if points.len() < 2 {
            continue;
        }
        if closed {
            let flat: Vec<_> = points.iter().map(|p| plane.project(*p)).collect();
            if polygon::signed_area(&flat) < 0.0 {
                points.reverse();
            }
            let (u, _) = plane.frame();
            let first = (0..points.len())
                .max_by(|&i, &j| points[i].dot(u).total_cmp(&points[j].dot(u)).then(j.cmp(&i)))
                .unwrap_or(0);
            points.rotate_left(first);
        }
        loops.push(SectionLoop { points, closed });
    }
    loops
}
