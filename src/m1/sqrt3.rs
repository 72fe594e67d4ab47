//! Interpolating sqrt(3) subdivision of selected patches (Kobbelt 2000, "sqrt(3)-
//! subdivision", SIGGRAPH; \[collide\] section 3.2).
//!
//! One step: every face of a selected patch gets a new vertex at its centroid
//! `(a + b + c) / 3` and is split into three; then every old edge between two split faces
//! of the same patch is flipped, so that it joins the two centroids instead of the two old
//! vertices. Edges on a patch's border (between two patches, or on an opening) are never
//! flipped: the border triangles keep the old edge, so the refined patch meets its
//! unrefined neighbour edge to edge, with no T-junction. A split face contributes three
//! triangles, so one step triples a refined patch's faces and two steps make nine.
//!
//! Old vertices stay where they are by default (the paper's choice: the fixed-topology
//! mesh M0 is already smooth, and the two layers map onto each other more simply). With
//! [`Smoothing::Kobbelt`] an old vertex inside a refined patch (every face round it split,
//! none of its edges on a border) moves to `(1 - alpha_n) p + alpha_n / n * sum(p_i)` over
//! its `n` neighbours, `alpha_n = (4 - 2 cos(2 pi / n)) / 9` (Kobbelt's rule; at valence 6
//! it is `(1 - 6 beta) p + beta sum(p_i)` with `beta = 1/18`, the paper's formula (1)).

use glam::DVec3;

use crate::mesh::TriMesh;
use crate::mesh::topology::group_by_vertex;

/// What happens to the old vertices of a refined patch.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Smoothing {
    /// They stay where they are (interpolating; the default).
    #[default]
    None,
    /// Kobbelt's smoothing rule with `alpha_n`.
    Kobbelt,
}

impl Smoothing {
    /// Name in sessions: `none` or `kobbelt`.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Kobbelt => "kobbelt",
        }
    }

    /// From a session name.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "none" => Some(Self::None),
            "kobbelt" => Some(Self::Kobbelt),
            _ => None,
        }
    }
}

/// Where a vertex of the refined mesh comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// A vertex of the mesh before the step (same index).
    Old,
    /// The centroid of a face of the mesh before the step, whose corners these are.
    Centroid([u32; 3]),
}

/// One sqrt(3) step's result.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The refined mesh; the vertices before the step keep their indices and come first.
    pub mesh: TriMesh,
    /// Patch of each face.
    pub face_patch: Vec<u32>,
    /// Origin of each vertex.
    pub origin: Vec<Origin>,
    /// For each face before the step, the vertex at its centroid, if it was split.
    pub centroid_of: Vec<Option<u32>>,
    /// Flipped edges, sorted by the old edge: the old edge `[b, c]` (`b < c`) and the two
    /// faces `[f1, f2]` whose centroids the new edge joins (`f1` has the directed edge
    /// `b -> c`).
    pub flips: Vec<([u32; 2], [u32; 2])>,
    /// Old vertices that moved (smoothing).
    pub smoothed: Vec<u32>,
}

/// `alpha_n` of Kobbelt's smoothing rule for valence `n`: `(4 - 2 cos(2 pi / n)) / 9`.
pub fn kobbelt_alpha(n: usize) -> f64 {
    (4.0 - 2.0 * (2.0 * std::f64::consts::PI / n as f64).cos()) / 9.0
}

/// One sqrt(3) step over the faces whose patch `refine` selects.
pub fn sqrt3_step(mesh: &TriMesh, face_patch: &[u32], refine: &[bool], smoothing: Smoothing) -> Step {
    let n0 = mesh.positions.len();
    let split = |f: usize| refine.get(face_patch[f] as usize).copied().unwrap_or(false);
    let directed = Directed::new(mesh);
    let mut positions = mesh.positions.clone();
    let mut origin = vec![Origin::Old; n0];
    let mut centroid_of = vec![None; mesh.triangles.len()];
    for (f, t) in mesh.triangles.iter().enumerate() {
        if split(f) {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
            centroid_of[f] = Some(positions.len() as u32);
            positions.push((a + b + c) / 3.0);
            origin.push(Origin::Centroid(*t));
        }
    }
    let split_faces = split_faces(mesh, face_patch, &split, &directed, &centroid_of);
    let mut flips = split_faces.flips;
    keep_last_flip_of_each_edge(&mut flips);
    let mut smoothed = Vec::new();
    if smoothing == Smoothing::Kobbelt {
        let flips_with = |f: usize, b: u32, c: u32| flips_with(face_patch, &split, &directed, (f, b, c));
        let moved = smooth_old(mesh, &directed, &split, &flips_with);
        for (v, p) in moved {
            positions[v as usize] = p;
            smoothed.push(v);
        }
    }
    Step {
        mesh: TriMesh {
            positions,
            triangles: split_faces.triangles,
        },
        face_patch: split_faces.patches,
        origin,
        centroid_of,
        flips,
        smoothed,
    }
}

/// The faces one step makes, each face's in turn.
pub(super) struct SplitFaces {
    /// The faces, those of face `f` of the mesh before the step at `start[f]..start[f + 1]`.
    pub triangles: Vec<[u32; 3]>,
    /// Patch of each.
    pub patches: Vec<u32>,
    /// Where each face's faces begin, and one past the last.
    pub start: Vec<u32>,
    /// The flipped edges as met (see [`Step::flips`]), sorted by edge (stably: an edge met
    /// twice keeps both, in the order met).
    pub flips: Vec<([u32; 2], [u32; 2])>,
}

/// The face across the directed edge `b -> c` of face `f`, when the edge flips: both faces
/// split, in the same patch.
fn flips_with(
    face_patch: &[u32],
    split: &dyn Fn(usize) -> bool,
    directed: &Directed,
    (f, b, c): (usize, u32, u32),
) -> Option<usize> {
    let g = directed.get(c, b)?;
    (split(f) && split(g) && face_patch[f] == face_patch[g]).then_some(g)
}

/// The faces of one step: a face not split stays, a split one makes three faces round its
/// centroid (`centroid_of`), and an edge between two split faces of the same patch flips.
pub(super) fn split_faces(
    mesh: &TriMesh,
    face_patch: &[u32],
    split: &dyn Fn(usize) -> bool,
    directed: &Directed,
    centroid_of: &[Option<u32>],
) -> SplitFaces {
    let mut triangles = Vec::with_capacity(mesh.triangles.len() * 3);
    let mut patches = Vec::with_capacity(mesh.triangles.len() * 3);
    let mut start = Vec::with_capacity(mesh.triangles.len() + 1);
    let mut flips = Vec::new();
    for (f, t) in mesh.triangles.iter().enumerate() {
        start.push(triangles.len() as u32);
        let patch = face_patch[f];
        let Some(m1) = centroid_of[f] else {
            triangles.push(*t);
            patches.push(patch);
            continue;
        };
        for k in 0..3 {
            let (b, c) = (t[k], t[(k + 1) % 3]);
            match flips_with(face_patch, split, directed, (f, b, c)) {
                // Each flipped edge once, from the face with the lower index.
                Some(g) if f < g => {
                    let m2 = centroid_of[g].unwrap_or(m1);
                    // Faces (b, c, m1) and (c, b, m2) become (m1, b, m2) and (m2, c, m1).
                    triangles.push([m1, b, m2]);
                    triangles.push([m2, c, m1]);
                    patches.extend([patch, patch]);
                    flips.push((
                        [b.min(c), b.max(c)],
                        if b < c {
                            [f as u32, g as u32]
                        } else {
                            [g as u32, f as u32]
                        },
                    ));
                }
                Some(_) => {}
                None => {
                    triangles.push([b, c, m1]);
                    patches.push(patch);
                }
            }
        }
    }
    start.push(triangles.len() as u32);
    flips.sort_by_key(|&(edge, _)| edge);
    SplitFaces {
        triangles,
        patches,
        start,
        flips,
    }
}

/// Of flips sorted by edge, the last of each edge (an edge given twice, only where the mesh
/// is not manifold, keeps its last faces, as a map would).
pub(super) fn keep_last_flip_of_each_edge(flips: &mut Vec<([u32; 2], [u32; 2])>) {
    flips.reverse();
    flips.dedup_by_key(|(edge, _)| *edge);
    flips.reverse();
}

/// Directed edge -> face: the directed edges of a mesh sorted by start vertex, then end
/// vertex, with where each start vertex's run begins. Where a directed edge repeats (two
/// faces running the same way, a mesh folded over itself) the later face counts.
pub(super) struct Directed {
    /// Per vertex, and one past the last: where its run of edges begins.
    first: Vec<usize>,
    /// End vertex and face of each edge.
    edges: Vec<(u32, u32)>,
}

impl Directed {
    pub(super) fn new(mesh: &TriMesh) -> Self {
        let n = mesh.positions.len();
        let records: Vec<(u32, (u32, u32))> = (mesh.triangles.iter().enumerate())
            .flat_map(|(f, t)| (0..3).map(move |k| (t[k], (t[(k + 1) % 3], f as u32))))
            .collect();
        let (mut first, mut grouped) = group_by_vertex(n, &records);
        // Each run by end vertex (faces stay in order), then the later face of a repeat.
        let mut edges = Vec::with_capacity(grouped.len());
        for v in 0..n {
            let run = &mut grouped[first[v]..first[v + 1]];
            run.sort_by_key(|e| e.0);
            first[v] = edges.len();
            for (i, &e) in run.iter().enumerate() {
                if run.get(i + 1).is_none_or(|next| next.0 != e.0) {
                    edges.push(e);
                }
            }
        }
        first[n] = edges.len();
        Self { first, edges }
    }

    /// The face with the directed edge `b -> c`.
    fn get(&self, b: u32, c: u32) -> Option<usize> {
        let v = b as usize;
        let run = &self.edges[*self.first.get(v)?..*self.first.get(v + 1)?];
        run.iter().find(|e| e.0 == c).map(|e| e.1 as usize)
    }

    /// Every directed edge `(b, c, face)`, by `b` then `c`.
    fn iter(&self) -> impl Iterator<Item = (u32, u32, usize)> + '_ {
        self.first.windows(2).enumerate().flat_map(move |(b, w)| {
            self.edges[w[0]..w[1]]
                .iter()
                .map(move |&(c, f)| (b as u32, c, f as usize))
        })
    }
}

/// Kobbelt's rule for the old vertices whose every edge flips (inside a refined patch).
fn smooth_old(
    mesh: &TriMesh,
    directed: &Directed,
    split: &dyn Fn(usize) -> bool,
    flips_with: &dyn Fn(usize, u32, u32) -> Option<usize>,
) -> Vec<(u32, DVec3)> {
    let n = mesh.positions.len();
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut inner = vec![true; n];
    let mut touched = vec![false; n];
    for (b, c, f) in directed.iter() {
        neighbours[b as usize].push(c);
        touched[b as usize] |= split(f);
        if flips_with(f, b, c).is_none() {
            inner[b as usize] = false;
            inner[c as usize] = false;
        }
    }
    (0..n)
        .filter(|&v| touched[v] && inner[v] && !neighbours[v].is_empty())
        .map(|v| {
            let ring = &neighbours[v];
            let alpha = kobbelt_alpha(ring.len());
            let sum: DVec3 = ring.iter().map(|&u| mesh.positions[u as usize]).sum();
            let p = mesh.positions[v];
            (v as u32, (1.0 - alpha) * p + alpha / ring.len() as f64 * sum)
        })
        .collect()
}
