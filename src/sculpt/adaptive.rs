//! Adaptive Loop subdivision with red-green closure ([sculpt] section 3; Amresh, Farin
//! and Razdan, "Adaptive subdivision schemes for triangle meshes", 2003).
//!
//! A face of the region is **active** while its longest edge exceeds `epsilon`. Each
//! level works on a conforming mesh and leaves one:
//!
//! 1. **Red faces** are the active ones. Closure: a face with two or three of its edges
//!    split by red neighbours turns red too, until none is left with more than one.
//! 2. **Edge points** on every split edge by Loop's edge mask on the current mesh.
//! 3. **Old vertices** whose every face is red move by Loop's vertex rule with the tunable
//!    weight; the others stay, so the refined region meets the rest of the mesh where it
//!    was.
//! 4. **Split**: red faces 1 -> 4, faces with exactly one split edge 1 -> 2 (green, from
//!    the split point to the opposite corner). Every split edge is split on both its
//!    sides, so the result is conforming: no T-junctions.
//!
//! Green faces stay as they are at the next level (a split into a green pair is final).
//! Taking them back to their parent before refining further (Bank's rule, which keeps
//! angles from thinning) needs the refinement kept one level apart across every hanging
//! edge; it is left out, and the smallest angle is measured and reported instead.
//!
//! It stops when no face is active, or at the level limit (then [`Refined::limited`]).
//! Children inherit the region flag, so refinement stays where the drag stretched the
//! mesh; faces outside the region turn red or green only to close the region's
//! T-junctions.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use super::loop_rules::{EdgeTable, key, quarter};
use crate::mesh::TriMesh;

/// Adaptive refinement settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveOptions {
    /// A region face is active while its longest edge exceeds this, m.
    pub epsilon: f64,
    /// At most this many levels (default 6: up to 4096 faces from one).
    pub max_levels: usize,
    /// Loop's vertex-rule weight (default 1: Loop's scheme; 0: interpolating).
    pub weight: f64,
}

impl AdaptiveOptions {
    /// The default level limit.
    pub const MAX_LEVELS: usize = 6;

    /// Refinement to `epsilon` with the default limit and weight.
    pub fn new(epsilon: f64) -> Self {
        Self {
            epsilon,
            max_levels: Self::MAX_LEVELS,
            weight: 1.0,
        }
    }
}

/// What one level did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Level {
    /// The active faces at the start of the level (their corners).
    pub active: Vec<[DVec3; 3]>,
    /// Faces split 1 -> 4 (active ones and those the closure added).
    pub red: usize,
    /// Faces bisected to close T-junctions.
    pub green: usize,
}

/// A refined mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Refined {
    /// The mesh: the input's vertices first (same indices), then the new ones.
    pub mesh: TriMesh,
    /// Per face: descends from a region face.
    pub region: Vec<bool>,
    /// A vertex of the input each vertex descends from (itself for the input's).
    pub anchor: Vec<u32>,
    /// The input's vertex count.
    pub base_vertices: usize,
    /// Input vertices the vertex rule moved, sorted.
    pub smoothed: Vec<u32>,
    /// The levels run.
    pub levels: Vec<Level>,
    /// Stopped at the level limit with faces still active.
    pub limited: bool,
}

/// A face of the working mesh.
#[derive(Clone, Copy, Debug)]
struct Face {
    v: [u32; 3],
    region: bool,
}

/// The longest edge of triangle `[a, b, c]` at positions `p`.
pub(crate) fn face_longest_edge(p: &[DVec3], [a, b, c]: [u32; 3]) -> f64 {
    let (a, b, c) = (p[a as usize], p[b as usize], p[c as usize]);
    a.distance(b).max(b.distance(c)).max(c.distance(a))
}

fn edges_of(v: [u32; 3]) -> [(u32, u32); 3] {
    [key(v[0], v[1]), key(v[1], v[2]), key(v[2], v[0])]
}

/// Refines `mesh` where `region` (per face) says, until no region face's longest edge
/// exceeds `options.epsilon` or the level limit.
pub fn refine(mesh: &TriMesh, region: &[bool], options: &AdaptiveOptions) -> Refined {
    let mut positions = mesh.positions.clone();
    let mut anchor: Vec<u32> = (0..positions.len() as u32).collect();
    let mut faces: Vec<Face> = mesh
        .triangles
        .iter()
        .zip(region)
        .map(|(&v, &region)| Face { v, region })
        .collect();
    let mut smoothed: BTreeSet<u32> = BTreeSet::new();
    let mut levels = Vec::new();
    let mut limited = false;
    loop {
        let current = faces;
        // Active faces, then the closure. When none is left (or at the limit) the mesh stays
        // as it is.
        let active: Vec<bool> = current
            .iter()
            .map(|f| f.region && face_longest_edge(&positions, f.v) > options.epsilon)
            .collect();
        if !active.contains(&true) {
            faces = current;
            break;
        }
        if levels.len() == options.max_levels {
            limited = true;
            faces = current;
            break;
        }
        let (red, split) = red_green_closure(&current, &active);
        // Edge points on the current mesh.
        let table = EdgeTable::new(current.iter().map(|f| &f.v));
        let old_positions = positions.clone();
        let mut midpoints: BTreeMap<(u32, u32), u32> = BTreeMap::new();
        for &(a, b) in &split {
            midpoints.insert((a, b), positions.len() as u32);
            positions.push(table.edge_point(&old_positions, a, b));
            anchor.push(anchor[a as usize]);
        }
        // Old vertices with every face red.
        let n_old = old_positions.len();
        let mut eligible = vec![false; n_old];
        let mut barred = vec![false; n_old];
        for (f, r) in current.iter().zip(&red) {
            for &v in &f.v {
                if *r {
                    eligible[v as usize] = true;
                } else {
                    barred[v as usize] = true;
                }
            }
        }
        for &(a, b) in table.opposite.keys() {
            if !split.contains(&(a, b)) {
                barred[a as usize] = true;
                barred[b as usize] = true;
            }
        }
        let (ring, along) = table.rings(n_old);
        for v in (0..n_old as u32).filter(|&v| eligible[v as usize] && !barred[v as usize]) {
            if let Some(p) =
                EdgeTable::vertex_point(&old_positions, v, &ring[v as usize], &along[v as usize], options.weight)
                && p != old_positions[v as usize]
            {
                positions[v as usize] = p;
                if (v as usize) < mesh.positions.len() {
                    smoothed.insert(v);
                }
            }
        }
        // Split.
        let mut level = Level {
            active: current
                .iter()
                .zip(&active)
                .filter(|(_, a)| **a)
                .map(|(f, _)| f.v.map(|v| old_positions[v as usize]))
                .collect(),
            ..Level::default()
        };
        let next = split_faces(&current, &red, &midpoints, &mut level);
        levels.push(level);
        faces = next;
    }
    Refined {
        mesh: TriMesh {
            positions,
            triangles: faces.iter().map(|f| f.v).collect(),
        },
        region: faces.iter().map(|f| f.region).collect(),
        anchor,
        base_vertices: mesh.positions.len(),
        smoothed: smoothed.into_iter().collect(),
        levels,
        limited,
    }
}

/// The faces to split red (every edge split): the active ones, and every face two of whose
/// edges come to be split (the closure); with the edges split.
fn red_green_closure(current: &[Face], active: &[bool]) -> (Vec<bool>, BTreeSet<(u32, u32)>) {
    let mut red = active.to_vec();
    let mut split: BTreeSet<(u32, u32)> = BTreeSet::new();
    let mut on_edge: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    for (i, f) in current.iter().enumerate() {
        for e in edges_of(f.v) {
            on_edge.entry(e).or_default().push(i);
        }
    }
    let count =
        |i: usize, split: &BTreeSet<(u32, u32)>| edges_of(current[i].v).iter().filter(|e| split.contains(e)).count();
    let mut queue: Vec<usize> = (0..current.len()).filter(|&i| red[i]).collect();
    while let Some(i) = queue.pop() {
        for e in edges_of(current[i].v) {
            if !split.insert(e) {
                continue;
            }
            let mut turn_red: Vec<usize> = on_edge[&e].iter().copied().filter(|&j| !red[j]).collect();
            turn_red.retain(|&j| count(j, &split) >= 2);
            for j in turn_red {
                if !red[j] {
                    red[j] = true;
                    queue.push(j);
                }
            }
        }
    }
    (red, split)
}

/// The next level's faces: a red face in four, a face with one split edge in two (green),
/// the others kept; counts the red and green faces in `level`.
fn split_faces(current: &[Face], red: &[bool], midpoints: &BTreeMap<(u32, u32), u32>, level: &mut Level) -> Vec<Face> {
    let mut next = Vec::with_capacity(current.len() + 3 * level.active.len());
    for (f, r) in current.iter().zip(red) {
        let mid = |a: u32, b: u32| midpoints.get(&key(a, b)).copied();
        let [a, b, c] = f.v;
        if *r {
            level.red += 1;
            let (Some(ab), Some(bc), Some(ca)) = (mid(a, b), mid(b, c), mid(c, a)) else {
                unreachable!("a red face has all three edges split");
            };
            next.extend(quarter(f.v, [ab, bc, ca]).map(|v| Face { v, region: f.region }));
            continue;
        }
        let splits: Vec<(usize, u32)> = (0..3)
            .filter_map(|k| mid(f.v[k], f.v[(k + 1) % 3]).map(|m| (k, m)))
            .collect();
        match splits.as_slice() {
            [(k, m)] => {
                level.green += 1;
                let (p, q, o) = (f.v[*k], f.v[(k + 1) % 3], f.v[(k + 2) % 3]);
                for v in [[p, *m, o], [*m, q, o]] {
                    next.push(Face { v, region: f.region });
                }
            }
            _ => next.push(*f),
        }
    }
    next
}
