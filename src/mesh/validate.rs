//! Mesh validation with reported repairs: what a body mesh must satisfy before use.
//!
//! Repairs (each counted in [`MeshReport`]): triangles that repeat a vertex and exact
//! duplicate triangles are dropped; triangles are flipped so that neighbours agree and
//! each closed part faces outward. Errors: an edge shared by three or more triangles, a
//! part that cannot be oriented, or nothing left. Zero-area triangles are reported and
//! kept. Holes (boundary loops, such as a scan's gap under the arm) are closed by a fan
//! of triangles about each loop's centroid, so that inside and outside stay defined.

use std::collections::VecDeque;

use thiserror::Error;

use super::TriMesh;
use super::topology::{Adjacency, NO_NEIGHBOUR};

/// What validation found and repaired.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct MeshReport {
    /// Vertices.
    pub vertices: usize,
    /// Triangles kept.
    pub triangles: usize,
    /// Triangles dropped because they repeat a vertex.
    pub dropped_repeated_vertex: usize,
    /// Exact duplicate triangles dropped.
    pub dropped_duplicates: usize,
    /// Triangles whose area is below `1e-12` of the bounding box diagonal squared (kept).
    pub zero_area_triangles: usize,
    /// Triangles flipped to agree with their neighbours or to face outward.
    pub flipped: usize,
    /// Edges with a single triangle as read (0 for a closed mesh).
    pub boundary_edges: usize,
    /// Holes closed: boundary loops, each filled by a fan about a new vertex at its
    /// centroid (the triangles are counted in `triangles`).
    pub holes_filled: usize,
    /// Edge-connected parts.
    pub components: usize,
    /// Vertices no triangle uses.
    pub unused_vertices: usize,
}

impl MeshReport {
    /// Human-readable warnings and repairs, one line each (empty for a clean closed mesh).
    pub fn notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        let mut note = |n: usize, text: &str| {
            if n > 0 {
                notes.push(format!("{n} {text}"));
            }
        };
        note(self.dropped_repeated_vertex, "triangle(s) repeating a vertex dropped");
        note(self.dropped_duplicates, "duplicate triangle(s) dropped");
        note(self.zero_area_triangles, "zero-area triangle(s) kept");
        note(self.flipped, "triangle(s) flipped to a consistent outward orientation");
        note(self.unused_vertices, "unused vertex(es)");
        if self.boundary_edges > 0 {
            notes.push(format!(
                "{} boundary edge(s): the mesh was open; {} hole(s) filled by a fan about the centroid",
                self.boundary_edges, self.holes_filled
            ));
        }
        if self.components > 1 {
            notes.push(format!("{} separate parts", self.components));
        }
        notes
    }
}

/// Why a mesh is unusable.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MeshError {
    /// An edge with three or more triangles.
    #[error("{place}edge between vertices {a} and {b} is shared by {count} faces{lines}: the mesh is not manifold")]
    NonManifold {
        /// `file:` prefix or empty.
        place: String,
        /// 1-based vertex.
        a: u32,
        /// 1-based vertex.
        b: u32,
        /// How many faces share it.
        count: usize,
        /// " (lines ...)" or empty.
        lines: String,
    },
    /// A part is a Moebius-like surface.
    #[error("{place}the surface around face{line} cannot be oriented consistently (non-orientable part)")]
    NonOrientable {
        /// `file:` prefix or empty.
        place: String,
        /// " at line N" (" at face N") or empty.
        line: String,
    },
    /// Nothing usable is left.
    #[error("{place}no usable triangles: all {count} repeat a vertex")]
    NoTriangles {
        /// `file:` prefix or empty.
        place: String,
        /// How many there were.
        count: usize,
    },
}

/// Validates and repairs `mesh` in place and returns the report with the repaired mesh's
/// adjacency. `name` and `triangle_lines` (source line of each triangle, may be empty)
/// make error messages point into the file.
pub fn validate_and_repair(
    mesh: &mut TriMesh,
    name: &str,
    triangle_lines: &[usize],
) -> Result<(MeshReport, Adjacency), MeshError> {
    validate_and_repair_at(mesh, name, (triangle_lines, "line"))
}

/// [`validate_and_repair`] with the triangles' places named by `word`: "line" (an OBJ
/// file's lines) or "face" (the face numbers of a PLY or glTF file).
pub fn validate_and_repair_at(
    mesh: &mut TriMesh,
    name: &str,
    (triangle_lines, word): (&[usize], &str),
) -> Result<(MeshReport, Adjacency), MeshError> {
    let place = if name.is_empty() {
        String::new()
    } else {
        format!("{name}: ")
    };
    let mut report = MeshReport {
        vertices: mesh.positions.len(),
        ..MeshReport::default()
    };
    let lines = drop_repeats(mesh, triangle_lines, &mut report, &place)?;
    let mut adjacency = Adjacency::try_new(mesh).map_err(|e| {
        let shown: Vec<String> = e
            .triangles
            .iter()
            .filter_map(|&t| lines.get(t as usize).copied().filter(|&l| l > 0))
            .map(|l| l.to_string())
            .collect();
        MeshError::NonManifold {
            place: place.clone(),
            a: e.vertices[0] + 1,
            b: e.vertices[1] + 1,
            count: e.triangles.len(),
            lines: if shown.is_empty() {
                String::new()
            } else {
                format!(" ({word}s {})", shown.join(", "))
            },
        }
    })?;
    report.boundary_edges = adjacency.boundary_edges;

    let (flipped, parts) = orient(mesh, &mut adjacency, (&lines, word), &place)?;
    report.flipped = flipped;
    report.components = parts;
    if report.boundary_edges > 0 {
        report.holes_filled = fill_holes(mesh, &adjacency);
        adjacency = Adjacency::try_new(mesh).map_err(|e| MeshError::NonManifold {
            place: place.clone(),
            a: e.vertices[0] + 1,
            b: e.vertices[1] + 1,
            count: e.triangles.len(),
            lines: " (after filling holes)".into(),
        })?;
    }
    let n = mesh.triangles.len();
    report.triangles = n;
    let diagonal_sq = mesh.bounds().map_or(0.0, |(lo, hi)| (hi - lo).length_squared());
    report.zero_area_triangles = (0..n)
        .filter(|&t| mesh.scaled_normal(t).length() * 0.5 <= 1e-12 * diagonal_sq)
        .count();
    let mut used = vec![false; mesh.positions.len()];
    for tri in &mesh.triangles {
        for &v in tri {
            used[v as usize] = true;
        }
    }
    report.unused_vertices = used.iter().filter(|u| !**u).count();
    Ok((report, adjacency))
}

/// Drops the triangles that repeat a vertex, then exact duplicates (the same vertex set:
/// the first in file order is kept), counting both in `report`. Returns each kept
/// triangle's file line (`triangle_lines`, 0 where unknown).
fn drop_repeats(
    mesh: &mut TriMesh,
    triangle_lines: &[usize],
    report: &mut MeshReport,
    place: &str,
) -> Result<Vec<usize>, MeshError> {
    let total = mesh.triangles.len();
    let mut lines: Vec<usize> = Vec::with_capacity(total);
    let mut kept = Vec::with_capacity(total);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            report.dropped_repeated_vertex += 1;
            continue;
        }
        kept.push(*tri);
        lines.push(triangle_lines.get(t).copied().unwrap_or(0));
    }
    if kept.is_empty() {
        return Err(MeshError::NoTriangles {
            place: place.to_string(),
            count: total,
        });
    }
    // Exact duplicates (same vertex set): keep the first in file order.
    let mut keys: Vec<([u32; 3], usize)> = kept
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let mut k = *t;
            k.sort_unstable();
            (k, i)
        })
        .collect();
    keys.sort_unstable();
    let mut duplicate = vec![false; kept.len()];
    for w in keys.windows(2) {
        if w[0].0 == w[1].0 {
            duplicate[w[1].1] = true;
        }
    }
    report.dropped_duplicates = duplicate.iter().filter(|d| **d).count();
    let (triangles, lines): (Vec<_>, Vec<_>) = kept
        .into_iter()
        .zip(lines)
        .zip(&duplicate)
        .filter(|(_, d)| !**d)
        .map(|(pair, _)| pair)
        .unzip();
    mesh.triangles = triangles;

    Ok(lines)
}

/// Orients every edge-connected part consistently (breadth-first, on the original winding
/// with a flip flag per triangle: a neighbour must run the shared edge the other way), then
/// outward (a part whose enclosed volume is negative is flipped whole), keeping `adjacency`
/// in step. Returns the triangles flipped and the parts.
fn orient(
    mesh: &mut TriMesh,
    adjacency: &mut Adjacency,
    lines: (&[usize], &str),
    place: &str,
) -> Result<(usize, usize), MeshError> {
    let (mut flipped, parts) = consistent_parts(mesh, adjacency, lines, place)?;
    for (tri, &flip) in mesh.triangles.iter_mut().zip(&flipped) {
        if flip {
            tri.swap(1, 2);
        }
    }
    // Each part faces outward when its enclosed volume is positive.
    for members in &parts {
        let volume: f64 = members
            .iter()
            .map(|&t| {
                let [a, b, c] = mesh.corners(t);
                a.dot(b.cross(c))
            })
            .sum();
        if volume < 0.0 {
            for &t in members {
                mesh.triangles[t].swap(1, 2);
                flipped[t] = !flipped[t];
            }
        }
    }
    // A flip swaps corners 1 and 2, so edges 0 (v0 v1) and 2 (v2 v0) trade places and
    // edge 1 is reversed: the neighbour across each edge moves with it.
    for (neighbours, &flip) in adjacency.neighbours.iter_mut().zip(&flipped) {
        if flip {
            neighbours.swap(0, 2);
        }
    }
    Ok((flipped.iter().filter(|f| **f).count(), parts.len()))
}

/// The edge-connected parts of `mesh` and, per triangle, whether it must be flipped to
/// agree with the first triangle of its part (breadth-first: a neighbour must run the
/// shared edge the other way). `lines` (the source line or face number of each triangle,
/// and the word for it: "line" or "face") and `place` name a part that cannot be oriented.
pub(crate) fn consistent_parts(
    mesh: &TriMesh,
    adjacency: &Adjacency,
    (lines, word): (&[usize], &str),
    place: &str,
) -> Result<(Vec<bool>, Vec<Vec<usize>>), MeshError> {
    let n = mesh.triangles.len();
    let mut component = vec![u32::MAX; n];
    let mut flipped = vec![false; n];
    let mut parts: Vec<Vec<usize>> = Vec::new();
    for seed in 0..n {
        if component[seed] != u32::MAX {
            continue;
        }
        let id = parts.len() as u32;
        let mut members = vec![seed];
        component[seed] = id;
        let mut queue = VecDeque::from([seed]);
        while let Some(t) = queue.pop_front() {
            for k in 0..3 {
                let other = adjacency.neighbours[t][k];
                if other == NO_NEIGHBOUR {
                    continue;
                }
                let o = other as usize;
                let tri = mesh.triangles[t];
                // t runs a -> b in its original winding, b -> a once flipped.
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let o_runs_a_b = directed_edge_position(mesh.triangles[o], a, b).is_some();
                // Consistent when o's actual direction is the reverse of t's.
                let o_flip_needed = o_runs_a_b != flipped[t];
                if component[o] == u32::MAX {
                    component[o] = id;
                    flipped[o] = o_flip_needed;
                    members.push(o);
                    queue.push_back(o);
                } else if flipped[o] != o_flip_needed {
                    let line = lines.get(o).copied().filter(|&l| l > 0);
                    return Err(MeshError::NonOrientable {
                        place: place.to_string(),
                        line: line.map(|l| format!(" at {word} {l}")).unwrap_or_default(),
                    });
                }
            }
        }
        parts.push(members);
    }
    Ok((flipped, parts))
}

/// Closes every boundary loop of the consistently oriented `mesh` with a fan about a new
/// vertex at the loop's centroid; returns how many loops were closed. A loop that passes a
/// vertex twice is split there into simple loops, so the fans keep every edge manifold.
fn fill_holes(mesh: &mut TriMesh, adjacency: &Adjacency) -> usize {
    // Boundary edges a -> b as the triangles run them, by start vertex (sorted: the fill
    // is deterministic).
    let mut from: std::collections::BTreeMap<u32, Vec<u32>> = std::collections::BTreeMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            if adjacency.neighbours[t][k] == NO_NEIGHBOUR {
                from.entry(tri[k]).or_default().push(tri[(k + 1) % 3]);
            }
        }
    }
    for ends in from.values_mut() {
        ends.sort_unstable();
        ends.reverse();
    }
    let mut loops: Vec<Vec<u32>> = Vec::new();
    let starts: Vec<u32> = from.keys().copied().collect();
    for start in starts {
        // Walk on from `start` while it has unused boundary edges; a vertex met again
        // closes the loop since its last visit.
        let mut path = vec![start];
        let mut at = start;
        while let Some(next) = from.get_mut(&at).and_then(Vec::pop) {
            if let Some(i) = path.iter().position(|&v| v == next) {
                loops.push(path.split_off(i));
            }
            path.push(next);
            at = next;
        }
    }
    let mut filled = 0;
    for l in loops.iter().filter(|l| l.len() >= 3) {
        let centre = l.iter().map(|&v| mesh.positions[v as usize]).sum::<glam::DVec3>() / l.len() as f64;
        let c = mesh.positions.len() as u32;
        mesh.positions.push(centre);
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            // The mesh runs a -> b; the fan runs it back.
            mesh.triangles.push([b, a, c]);
        }
        filled += 1;
    }
    filled
}

/// Where the directed edge `a -> b` runs in `tri`, if it does.
fn directed_edge_position(tri: [u32; 3], a: u32, b: u32) -> Option<usize> {
    (0..3).find(|&k| tri[k] == a && tri[(k + 1) % 3] == b)
}
