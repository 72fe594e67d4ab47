//! M1, the display mesh (\[collide\] section 3; docs/design.md section 7): M0 with the patches that
//! need it refined by interpolating sqrt(3) subdivision, collided with the body only where
//! it differs from M0, and the style (cut) lines drawn on it, stored on M0.
//!
//! Data flow of one step (after M0's collision): [`select()`] (which patches, by which
//! rule) -> [`subdivide`] (one or two [`sqrt3_step`]s of the selected patches over the collided
//! M0; the last step's shape kept when its inputs are equal, only its vertices placed again) -> [`collide_m1_patches`] (only the vertices M0 does not have, each refined patch
//! alone, a patch whose input is unchanged taken from the step before: detection,
//! response, edge rounds that leave M0's vertices where they are; then the exact check over
//! all of M1) ->
//! [`cut::rebuild`] of the stored cut lines on the new M1.

pub mod collide;
pub mod cut;
pub mod every_patch;
mod kept;
mod numbering;
pub mod patches;
pub mod reshape;
pub mod select;
pub mod select_rules;
pub mod sqrt3;

pub use collide::{M0Collided, M1Collision, RefinedInput, collide_refined, partition_through};
pub use cut::{CutLine, CutPlane, CutPoint, StoredCut, StoredPoint};
pub use patches::{M1Reuse, PatchCounts, PatchInput, PatchShape, collide_m1, collide_m1_patches};
pub use reshape::{M1Shape, Made, subdivide};
pub use select::{Rule, SelectInput, SelectOptions, Selection};
pub use select_rules::{SelectMemory, select, select_keeping};
pub use sqrt3::{Origin, Smoothing, Step, kobbelt_alpha, sqrt3_step};

use std::sync::Arc;

use crate::mesh::TriMesh;

/// M1 settings (the session's `m1` scene statement).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct M1Options {
    /// Which patches (default: the four rules with their default thresholds).
    pub select: SelectOptions,
    /// Refine every patch, not only the selected ones (for comparison; default off).
    pub all_patches: bool,
    /// sqrt(3) steps, 1 or 2 (default 1: three times the faces of a refined patch).
    pub steps: usize,
    /// Old vertices: kept (default) or smoothed.
    pub smoothing: Smoothing,
}

impl Default for M1Options {
    fn default() -> Self {
        Self {
            select: SelectOptions::default(),
            all_patches: false,
            steps: 1,
            smoothing: Smoothing::None,
        }
    }
}

/// M1 before its collision. What depends on its shape alone (the patches of its faces, its
/// first step, its edges and anchors) is shared with every later M1 of the same shape
/// ([`subdivide`]), so a drag that keeps the shape copies only its positions and faces.
#[derive(Clone, Debug, PartialEq)]
pub struct M1 {
    /// The refined mesh: M0's vertices first (same indices), then the new ones.
    pub mesh: TriMesh,
    /// Patch of each face.
    pub face_patch: Arc<Vec<u32>>,
    /// Which patches were refined, by which rules.
    pub selection: Selection,
    /// M0's vertex count: vertices from here on are new.
    pub m0_vertices: usize,
    /// Old vertices the smoothing moved (not where M0 has them).
    pub smoothed: Vec<u32>,
    /// The first step's result (the layer cut lines are stored through), without its
    /// positions (its vertices are M1's first `first_vertices`) and, when it is M1's only
    /// step, without its faces and their patches, which are M1's ([`Self::first_triangles`]).
    pub first: Arc<Step>,
    /// Vertex count after the first step (its vertices keep their indices in `mesh`).
    pub first_vertices: usize,
    /// Undirected edges, each once, sorted.
    pub edges: Arc<Vec<[u32; 2]>>,
    /// An M0 vertex each M1 vertex descends from (itself for M0's; a corner of the face it
    /// is the centroid of, recursively, for new ones): its partition and roles.
    pub anchor: Arc<Vec<u32>>,
}

impl M1 {
    /// Undirected edges of M1, sorted.
    pub fn edges(&self) -> &[[u32; 2]] {
        &self.edges
    }

    /// The faces of the first step: its own, or M1's when it is M1's only step.
    pub fn first_triangles(&self) -> &[[u32; 3]] {
        if self.first.mesh.triangles.is_empty() {
            &self.mesh.triangles
        } else {
            &self.first.mesh.triangles
        }
    }
}

/// Builds M1 from the collided M0: `steps` sqrt(3) steps over the patches `selection`
/// refines.
pub fn build(m0: &TriMesh, face_patch: &[u32], selection: Selection, options: &M1Options) -> M1 {
    build_traced(m0, face_patch, selection, options).0
}

/// [`build`], with the corners of every new vertex in order (the face of the mesh before its
/// step whose centroid it is; the corners' indices are M1's, earlier than its own).
pub(crate) fn build_traced(
    m0: &TriMesh,
    face_patch: &[u32],
    selection: Selection,
    options: &M1Options,
) -> (M1, Vec<[u32; 3]>) {
    let refine = selection.refined();
    let first = sqrt3_step(m0, face_patch, &refine, options.smoothing);
    let second = (options.steps >= 2).then(|| sqrt3_step(&first.mesh, &first.face_patch, &refine, options.smoothing));
    let edges = crate::mesh::topology::undirected_edges(second.as_ref().map_or(&first.mesh, |s| &s.mesh));
    of_steps(m0.positions.len(), (first, second), edges, selection)
}

/// M1 of its sqrt(3) steps over M0 of `m0_vertices` vertices, with its `edges`; and the
/// corners of every new vertex in order.
pub(crate) fn of_steps(
    m0_vertices: usize,
    (first, second): (Step, Option<Step>),
    edges: Vec<[u32; 2]>,
    selection: Selection,
) -> (M1, Vec<[u32; 3]>) {
    let mut first = first;
    let first_vertices = first.mesh.positions.len();
    let mut smoothed = first.smoothed.clone();
    let mut anchor: Vec<u32> = (0..m0_vertices as u32).collect();
    let mut corners = Vec::new();
    let mut extend = |step: &Step, anchor: &mut Vec<u32>| {
        for o in &step.origin[anchor.len()..] {
            if let Origin::Centroid(c) = o {
                anchor.push(anchor[c[0] as usize]);
                corners.push(*c);
            }
        }
    };
    extend(&first, &mut anchor);
    let (mesh, patches) = match second {
        Some(second) => {
            extend(&second, &mut anchor);
            smoothed.extend(second.smoothed.iter().copied().filter(|&v| (v as usize) < m0_vertices));
            (second.mesh, second.face_patch)
        }
        // M1 is the one step: it takes the step's faces and their patches.
        None => (
            TriMesh {
                positions: std::mem::take(&mut first.mesh.positions),
                triangles: std::mem::take(&mut first.mesh.triangles),
            },
            std::mem::take(&mut first.face_patch),
        ),
    };
    // Its vertices are M1's first: their positions are read from M1 (whose shape a later
    // M1 shares with this step, at other positions).
    first.mesh.positions = Vec::new();
    smoothed.sort_unstable();
    smoothed.dedup();
    let m1 = M1 {
        edges: Arc::new(edges),
        mesh,
        face_patch: Arc::new(patches),
        selection,
        m0_vertices,
        smoothed,
        first: Arc::new(first),
        first_vertices,
        anchor: Arc::new(anchor),
    };
    (m1, corners)
}
