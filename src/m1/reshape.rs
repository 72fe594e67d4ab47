//! M1 over a moved M0 of the same shape (docs/design.md section 7): what a step keeps of
//! the last subdivision.
//!
//! With the old vertices kept where they are ([`Smoothing::None`], the default), M1 is two
//! things: its shape (faces, their patches, the flipped edges, every new vertex's origin,
//! the edges and anchors), which depends only on M0's faces, their patches, which patches
//! are refined and how many steps; and its positions, which are M0's followed by one
//! centroid per split face, each `(a + b + c) / 3` of earlier vertices. A drag moves M0's
//! vertices but mostly leaves all four inputs of the shape as they were, so [`subdivide`]
//! keeps the shape of the last M1 whose inputs are equal and only places its vertices again,
//! in the order and with the arithmetic of [`super::sqrt3_step`]: the same M1 as a full
//! build, bit for bit, by construction. When only the refined patches differ (a drag that
//! refines a patch more or less), M1 is read from one step over every patch
//! ([`EveryPatch`], made the first time the refinement changes over the same M0 faces and
//! kept while they stay), with no sort. Any other input (a dimension edit that changes M0's
//! layout, two sqrt(3) steps, Kobbelt's smoothing, which moves old vertices by their
//! neighbours) builds M1 whole.

use std::sync::Arc;

use super::every_patch::EveryPatch;
use super::select::EdgeFaces;
use super::{M1, M1Options, Selection, Smoothing, build_traced, of_steps};
use crate::mesh::TriMesh;

/// An M1's shape and what it was made from.
#[derive(Debug)]
pub struct M1Shape {
    /// M0's faces, with their edges (the same `Arc` while M0's faces stay the same: see
    /// [`EdgeFaces::of`]).
    m0_edges: Arc<EdgeFaces>,
    /// The patch of each of M0's faces.
    face_patch: Vec<u32>,
    /// Which patches are refined.
    refined: Vec<bool>,
    /// Whether a second sqrt(3) step was made.
    two_steps: bool,
    /// Corners of each new vertex, in order (indices of earlier vertices).
    corners: Vec<[u32; 3]>,
    /// The M1 it was made for, shared with its owner (any M1 of this shape would do: a copy
    /// of it has its positions placed again).
    m1: Arc<M1>,
    /// One step over every patch of these M0 faces, once the refinement has changed over
    /// them.
    every: Option<Arc<EveryPatch>>,
}

/// How [`subdivide`] made M1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Made {
    /// The last M1's shape, its vertices placed again.
    ShapeKept,
    /// Read from one step over every patch (the refinement changed, M0's faces did not).
    EveryPatch,
    /// Built whole.
    Whole,
}

impl M1Shape {
    /// The M1 it was made for (its positions those of that step).
    pub(super) fn m1(&self) -> &M1 {
        &self.m1
    }

    /// Whether `other` was made, as this one, by one step over the same M0 faces and
    /// patches (whatever patches each refines; neither is smoothed, as no smoothed M1 has a
    /// shape). Then a patch both refine has the same faces, edges and anchors in its own
    /// numbering in both: what a split face becomes depends on its own patch alone, and its
    /// centroids keep their order, only renumbered ([`super::every_patch`]).
    pub(super) fn renumbers(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.m0_edges, &other.m0_edges)
            && self.face_patch == other.face_patch
            && !self.two_steps
            && !other.two_steps
            && self.m1.m0_vertices == other.m1.m0_vertices
    }

    /// Whether an M1 over `m0` with these patches and this refinement has this shape.
    fn fits(
        &self,
        m0: &TriMesh,
        edges: &Arc<EdgeFaces>,
        face_patch: &[u32],
        refined: &[bool],
        options: &M1Options,
    ) -> bool {
        options.smoothing == Smoothing::None
            && self.two_steps == (options.steps >= 2)
            && self.m1.m0_vertices == m0.positions.len()
            && self.refined == refined
            && self.face_patch == face_patch
            && Arc::ptr_eq(&self.m0_edges, edges)
    }

    /// M1 of this shape over `m0`: M0's positions, then each centroid in order.
    fn place(&self, m0: &TriMesh, selection: Selection) -> M1 {
        let mut m1 = M1::clone(&self.m1);
        let positions = &mut m1.mesh.positions;
        positions.clear();
        positions.extend_from_slice(&m0.positions);
        for corners in &self.corners {
            let [a, b, c] = corners.map(|v| positions[v as usize]);
            positions.push((a + b + c) / 3.0);
        }
        m1.selection = selection;
        m1
    }
}

/// M1 over the collided M0 (as [`super::build`] makes it), and the shape the next step may
/// keep: `previous`'s shape when it fits (a copy of its M1 placed over `m0`), M1 read from
/// one step over every patch when only the refinement changed, or a new build (whose shape
/// shares the M1, not a copy). `edges` are M0's, as [`EdgeFaces::of`] keeps them from step
/// to step.
pub fn subdivide(
    m0: &TriMesh,
    edges: &Arc<EdgeFaces>,
    face_patch: &[u32],
    selection: Selection,
    options: &M1Options,
    previous: Option<&Arc<M1Shape>>,
) -> (Arc<M1>, Option<Arc<M1Shape>>, Made) {
    let refined = selection.refined();
    if let Some(shape) = previous.filter(|s| s.fits(m0, edges, face_patch, &refined, options)) {
        return (
            Arc::new(shape.place(m0, selection)),
            Some(Arc::clone(shape)),
            Made::ShapeKept,
        );
    }
    let one_step = options.smoothing == Smoothing::None && options.steps < 2;
    // The step over every patch, kept, or made when the last M1 was over the same faces.
    let every = previous.filter(|_| one_step).and_then(|s| match &s.every {
        Some(every) if every.fits(m0, edges, face_patch) => Some(Arc::clone(every)),
        _ if Arc::ptr_eq(&s.m0_edges, edges) && s.face_patch == face_patch => {
            Some(Arc::new(EveryPatch::new(m0, edges, face_patch)))
        }
        _ => None,
    });
    let (made, (m1, corners)) = match &every {
        Some(every) => {
            let (first, m1_edges) = every.step(m0, &refined);
            (
                Made::EveryPatch,
                of_steps(m0.positions.len(), (first, None), m1_edges, selection),
            )
        }
        None => (Made::Whole, build_traced(m0, face_patch, selection, options)),
    };
    let m1 = Arc::new(m1);
    let shape = (options.smoothing == Smoothing::None).then(|| {
        Arc::new(M1Shape {
            m0_edges: Arc::clone(edges),
            face_patch: face_patch.to_vec(),
            refined,
            two_steps: options.steps >= 2,
            corners,
            m1: Arc::clone(&m1),
            every,
        })
    });
    (m1, shape, made)
}
