//! Style (cut) lines (\[collide\] section 3.2, figure 6): drawn on M1 as the section of M1
//! by a plane, stored on M0 by barycentric coordinates, rebuilt on a new M1 after M0 deforms.
//!
//! A cut line is a polyline of points on M1's edges (where the plane crosses them). It is
//! traced on M1's first sqrt(3) layer (the layer whose vertices M0 and the face centroids
//! are; with two steps the second layer's vertices lie on it up to their collision). Each
//! point is stored by the kind of edge it lies on:
//! - an edge of M0 (not flipped) or a spoke from a corner of an M0 face to that face's
//!   centroid: inside (or on) the M0 face, by its barycentric coordinates there
//!   ([`StoredPoint::Face`]);
//! - a flipped edge `DE` that replaced M0's edge `BC` (`D`, `E` the centroids of the two
//!   faces on `BC`): the plane through `DE`'s midpoint `F` whose normal is the mean of the
//!   two faces' normals meets `BC` at `G`; the point is stored by its barycentric
//!   coordinates in the triangle `DEG` ([`StoredPoint::Flipped`]).
//!
//! Rebuilding evaluates the same constructions on the new M0 and M1: a point in an M0 face
//! lies in one of the face's three sub-triangles (the one opposite the smallest
//! coordinate), evaluated with M1's positions of its corners and centroid; a flipped-edge
//! point from the new `D`, `E` and `G`. On the M1 it was drawn on, the rebuilt line is the
//! drawn line (to rounding).

use std::collections::BTreeMap;

use glam::DVec3;

use super::{M1, Origin};
use crate::mesh::TriMesh;

/// The plane a cut line is drawn with: the points `p` with `(p - point) . normal = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutPlane {
    /// A point of the plane, m (world frame).
    pub point: DVec3,
    /// Its normal (any length but zero).
    pub normal: DVec3,
}

/// A point of a cut line on M1: on the edge `[a, b]` (M1 vertices, `a < b`) at `t` from `a`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutPoint {
    /// The edge's ends.
    pub edge: [u32; 2],
    /// Parameter from `edge[0]` to `edge[1]`.
    pub t: f64,
    /// Where, m (world frame).
    pub position: DVec3,
}

/// A cut line on M1: one polyline per piece of the section.
#[derive(Clone, Debug, PartialEq)]
pub struct CutLine {
    /// The pieces: points in order, and whether the piece closes on itself.
    pub pieces: Vec<(Vec<CutPoint>, bool)>,
}

/// A cut point stored on M0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StoredPoint {
    /// In (or on) M0's face `face`, by barycentric coordinates.
    Face {
        /// M0 face.
        face: u32,
        /// Barycentric coordinates over its corners.
        bary: [f64; 3],
    },
    /// On the flipped edge between the centroids of M0's faces `faces` that share the edge
    /// `edge` (`faces[0]` has the directed edge `edge[0] -> edge[1]`): barycentric
    /// coordinates in the triangle `D E G`.
    Flipped {
        /// The two M0 faces (`D` is the first's centroid, `E` the second's).
        faces: [u32; 2],
        /// M0's edge `BC` the flip replaced.
        edge: [u32; 2],
        /// Barycentric coordinates over `D`, `E`, `G`.
        bary: [f64; 3],
    },
}

/// A cut line as stored: its plane (for the record) and its pieces on M0.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredCut {
    /// Its name.
    pub name: String,
    /// The plane it was drawn with.
    pub plane: CutPlane,
    /// The pieces: stored points in order, and whether the piece closes.
    pub pieces: Vec<(Vec<StoredPoint>, bool)>,
}

/// The first layer of M1 with M1's current positions of its vertices.
fn first_layer(m1: &M1, positions: &[DVec3]) -> TriMesh {
    TriMesh {
        positions: positions[..m1.first_vertices].to_vec(),
        triangles: m1.first_triangles().to_vec(),
    }
}

/// The section of M1 (its first layer, at `positions`) by `plane`, as polylines on its
/// edges. A vertex exactly on the plane counts as on its positive side (so every crossing
/// is on an edge's interior or at its negative end's opposite, never doubled).
pub fn draw(m1: &M1, positions: &[DVec3], plane: &CutPlane) -> CutLine {
    let mesh = first_layer(m1, positions);
    let side: Vec<f64> = mesh
        .positions
        .iter()
        .map(|p| (*p - plane.point).dot(plane.normal))
        .collect();
    let positive = |v: u32| side[v as usize] >= 0.0;
    let key = |a: u32, b: u32| [a.min(b), a.max(b)];
    // Each crossed edge: the (one or two) faces whose segments end on it.
    let mut at_edge: BTreeMap<[u32; 2], Vec<usize>> = BTreeMap::new();
    let mut segments: Vec<[[u32; 2]; 2]> = Vec::new();
    for t in &mesh.triangles {
        let crossed: Vec<[u32; 2]> = (0..3)
            .map(|k| (t[k], t[(k + 1) % 3]))
            .filter(|&(a, b)| positive(a) != positive(b))
            .map(|(a, b)| key(a, b))
            .collect();
        if let [e, f] = crossed[..] {
            let s = segments.len();
            segments.push([e, f]);
            at_edge.entry(e).or_default().push(s);
            at_edge.entry(f).or_default().push(s);
        }
    }
    let point = |[a, b]: [u32; 2]| {
        let (sa, sb) = (side[a as usize], side[b as usize]);
        let t = sa / (sa - sb);
        CutPoint {
            edge: [a, b],
            t,
            position: mesh.positions[a as usize].lerp(mesh.positions[b as usize], t),
        }
    };
    // Chain the segments: open pieces from edges with one segment (on an opening), then
    // the closed loops, each started at its smallest edge (deterministic).
    let mut used = vec![false; segments.len()];
    let mut pieces = Vec::new();
    let starts: Vec<[u32; 2]> = at_edge
        .iter()
        .filter(|(_, s)| s.len() == 1)
        .map(|(e, _)| *e)
        .chain(at_edge.keys().copied())
        .collect();
    for start in starts {
        let Some(&first) = at_edge[&start].iter().find(|&&s| !used[s]) else {
            continue;
        };
        let mut edges = vec![start];
        let (mut s, mut at) = (first, start);
        loop {
            used[s] = true;
            let next = if segments[s][0] == at {
                segments[s][1]
            } else {
                segments[s][0]
            };
            edges.push(next);
            at = next;
            match at_edge[&at].iter().find(|&&o| !used[o]) {
                Some(&o) => s = o,
                None => break,
            }
        }
        let closed = edges.len() > 2 && edges.first() == edges.last();
        if closed {
            edges.pop();
        }
        pieces.push((edges.into_iter().map(point).collect(), closed));
    }
    CutLine { pieces }
}

/// The unit normal of M0's face `f` at `positions`.
fn face_normal(m0: &[[u32; 3]], positions: &[DVec3], f: u32) -> DVec3 {
    let [a, b, c] = m0[f as usize].map(|v| positions[v as usize]);
    (b - a).cross(c - a).normalize_or_zero()
}

/// The M1 vertex at the centroid of M0's face `f`, if `f` is refined (never, on M0 alone).
fn centroid_vertex(m1: Option<&M1>, f: u32) -> Option<u32> {
    m1.and_then(|m1| m1.first.centroid_of.get(f as usize).copied().flatten())
}

/// The centroid of M0's face `f` as M1 has it (its vertex, collided), or the flat centroid
/// where the face is not refined (or on M0 alone, `m1` `None`).
fn centroid(m1: Option<&M1>, m0: &[[u32; 3]], positions: &[DVec3], f: u32) -> DVec3 {
    match centroid_vertex(m1, f) {
        Some(m) => positions[m as usize],
        None => m0[f as usize].map(|v| positions[v as usize]).into_iter().sum::<DVec3>() / 3.0,
    }
}

/// `G`: where the plane through `DE`'s midpoint with the faces' mean normal meets `BC`.
fn plane_point(d: DVec3, e: DVec3, normal: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let f = 0.5 * (d + e);
    let along = (c - b).dot(normal);
    let s = if along.abs() > 1e-12 * (c - b).length() {
        ((f - b).dot(normal) / along).clamp(0.0, 1.0)
    } else {
        0.5
    };
    b.lerp(c, s)
}

/// Barycentric coordinates of `p` in the triangle `abc` (of `p`'s projection on its plane).
fn barycentric(p: DVec3, [a, b, c]: [DVec3; 3]) -> [f64; 3] {
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let (d00, d01, d11) = (v0.dot(v0), v0.dot(v1), v1.dot(v1));
    let (d20, d21) = (v2.dot(v0), v2.dot(v1));
    let den = d00 * d11 - d01 * d01;
    if den.abs() <= f64::EPSILON * d00 * d11 {
        // Degenerate (G on DE): along the longest side.
        let t = if d00 > 0.0 { (d20 / d00).clamp(0.0, 1.0) } else { 0.0 };
        return [1.0 - t, t, 0.0];
    }
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    [1.0 - v - w, v, w]
}

/// The stored form of a cut point of M1: `m0` are M0's triangles, `positions` M1's.
fn store_point(m1: &M1, m0: &[[u32; 3]], positions: &[DVec3], p: &CutPoint) -> Option<StoredPoint> {
    let n0 = m1.m0_vertices as u32;
    let [a, b] = p.edge;
    let origin = |v: u32| m1.first.origin.get(v as usize).copied();
    let face_of = |m: u32| {
        m1.first
            .centroid_of
            .iter()
            .position(|&c| c == Some(m))
            .map(|f| f as u32)
    };
    if a < n0 && b < n0 {
        // An edge of M0: in the first face that has it.
        let f = m0.iter().position(|t| t.contains(&a) && t.contains(&b))? as u32;
        let mut bary = [0.0; 3];
        for (k, &v) in m0[f as usize].iter().enumerate() {
            bary[k] = if v == a {
                1.0 - p.t
            } else if v == b {
                p.t
            } else {
                0.0
            };
        }
        return Some(StoredPoint::Face { face: f, bary });
    }
    if a < n0 || b < n0 {
        // A spoke: from corner `old` of a face to its centroid.
        let (old, m, t) = if a < n0 { (a, b, p.t) } else { (b, a, 1.0 - p.t) };
        let Some(Origin::Centroid(_)) = origin(m) else {
            return None;
        };
        let f = face_of(m)?;
        let mut bary = [t / 3.0; 3];
        for (k, &v) in m0[f as usize].iter().enumerate() {
            if v == old {
                bary[k] += 1.0 - t;
            }
        }
        return Some(StoredPoint::Face { face: f, bary });
    }
    // A flipped edge between two centroids.
    let (fa, fb) = (face_of(a)?, face_of(b)?);
    let &(edge, faces) = m1
        .first
        .flips
        .iter()
        .find(|(_, faces)| (faces[0] == fa && faces[1] == fb) || (faces[0] == fb && faces[1] == fa))?;
    let (d, e, g) = flipped_triangle(Some(m1), m0, positions, faces, edge);
    Some(StoredPoint::Flipped {
        faces,
        edge,
        bary: barycentric(p.position, [d, e, g]),
    })
}

/// Whether `m1` flipped M0's edge `edge` between `faces` (so that its edge `DE` joins the
/// faces' centroids). The first step's flips are sorted by their edge, each edge given
/// with its lower vertex first ([`super::Step::flips`]), so the edge is found by bisection.
fn flipped_in(m1: Option<&M1>, faces: [u32; 2], edge: [u32; 2]) -> bool {
    m1.is_some_and(|m1| {
        let key = [edge[0].min(edge[1]), edge[0].max(edge[1])];
        let flips = &m1.first.flips;
        let from = flips.partition_point(|(e, _)| *e < key);
        (flips[from..].iter())
            .take_while(|(e, _)| *e == key)
            .any(|&(_, f)| f == faces || f == [faces[1], faces[0]])
    })
}

/// `D`, `E` and `G` of a flipped edge.
fn flipped_triangle(
    m1: Option<&M1>,
    m0: &[[u32; 3]],
    positions: &[DVec3],
    faces: [u32; 2],
    edge: [u32; 2],
) -> (DVec3, DVec3, DVec3) {
    let d = centroid(m1, m0, positions, faces[0]);
    let e = centroid(m1, m0, positions, faces[1]);
    let normal = (face_normal(m0, positions, faces[0]) + face_normal(m0, positions, faces[1])).normalize_or_zero();
    let g = plane_point(d, e, normal, positions[edge[0] as usize], positions[edge[1] as usize]);
    (d, e, g)
}

/// Stores a cut line drawn on M1 (at `positions`) on M0 (`m0`, its triangles). Points on
/// edges the scheme cannot place (none, on a mesh built by [`super::build`]) are dropped.
pub fn store(m1: &M1, m0: &[[u32; 3]], positions: &[DVec3], name: &str, plane: CutPlane, line: &CutLine) -> StoredCut {
    StoredCut {
        name: name.to_string(),
        plane,
        pieces: line
            .pieces
            .iter()
            .map(|(points, closed)| {
                (
                    points
                        .iter()
                        .filter_map(|p| store_point(m1, m0, positions, p))
                        .collect(),
                    *closed,
                )
            })
            .collect(),
    }
}

/// Where a stored point lies on M1 (at `positions`; `m0` M0's triangles), or on M0 itself
/// with `m1` `None` (its stored form drawn on M0: `positions` M0's).
pub fn rebuild_point(m1: Option<&M1>, m0: &[[u32; 3]], positions: &[DVec3], point: &StoredPoint) -> DVec3 {
    match *point {
        StoredPoint::Face { face, bary } => {
            let corners = m0[face as usize].map(|v| positions[v as usize]);
            match centroid_vertex(m1, face) {
                None => corners[0] * bary[0] + corners[1] * bary[1] + corners[2] * bary[2],
                Some(m) => {
                    // The sub-triangle opposite the smallest coordinate j:
                    // p = (l_i - l_j) P_i + (l_k - l_j) P_k + 3 l_j M.
                    let j = (0..3).min_by(|&x, &y| bary[x].total_cmp(&bary[y])).unwrap_or(0);
                    let mut p = positions[m as usize] * (3.0 * bary[j]);
                    for k in (0..3).filter(|&k| k != j) {
                        p += corners[k] * (bary[k] - bary[j]);
                    }
                    p
                }
            }
        }
        StoredPoint::Flipped { faces, edge, bary } => {
            let (d, e, g) = flipped_triangle(m1, m0, positions, faces, edge);
            if flipped_in(m1, faces, edge) {
                return d * bary[0] + e * bary[1] + g * bary[2];
            }
            // The edge `DE` is not in this mesh (the faces are not refined, or not flipped,
            // or the line is placed on M0): the surface between the two centroids runs
            // through `G` on the faces' shared edge. The point keeps its fraction of the way.
            let s = bary[1] / (bary[0] + bary[1]);
            let (first, second) = (d.distance(g), g.distance(e));
            let at = s * (first + second);
            if at <= first && first > 0.0 {
                d.lerp(g, at / first)
            } else if second > 0.0 {
                g.lerp(e, ((at - first) / second).clamp(0.0, 1.0))
            } else {
                g
            }
        }
    }
}

/// A stored cut line rebuilt on M1 (or placed on M0, `m1` `None`): one polyline of
/// positions per piece.
pub fn rebuild(m1: Option<&M1>, m0: &[[u32; 3]], positions: &[DVec3], cut: &StoredCut) -> Vec<(Vec<DVec3>, bool)> {
    cut.pieces
        .iter()
        .map(|(points, closed)| {
            (
                points.iter().map(|p| rebuild_point(m1, m0, positions, p)).collect(),
                *closed,
            )
        })
        .collect()
}
