//! A flat bounding-volume tree for the body's nearest-point queries and its walks along
//! rays and segments: binned-SAH splits (at the median below a depth, so that no descent
//! outgrows its stack), two triangles a leaf with their corners stored in leaf order (no
//! lookup through the mesh), laid out twice. The nearest-point descent reads it binary (two
//! siblings in one cache line), goes down the nearer side at once and drops a deferred node
//! when it is taken back off the stack if the best distance found meanwhile has passed it.
//! The walks, which look at every box they pass, read it four lanes wide: each node's four
//! children's boxes are tested against the ray in one pass of four-lane arithmetic.
//!
//! The tree only decides which triangles are looked at: the caller measures each one and
//! returns the bound (squared, `f32`) that prunes the rest, or says whether the ray meets
//! it, so a query gives exactly the answer of a scan over every triangle as long as the
//! boxes hold their triangles (they are the callers' boxes, widened against `f32`
//! rounding) and the bound is never below the best distance.
//!
//! Files: the types here; `build` (binned-SAH build, the four-wide layout, reading back),
//! `nearest` (the nearest-point descent and the gather within a bound), `walks` (segments,
//! boxes and rays), `words` (the stored form), `tests`.

use glam::{DVec3, Vec3, Vec3A, Vec4};

/// Most triangles in a leaf.
const LEAF: usize = 2;
/// Bins of a split.
const BINS: usize = 12;
/// Below this depth of the binary build, splits are at the median (at most `log2 n` more
/// levels), so that no descent is deeper than its stack.
const MEDIAN_BELOW: usize = 48;
/// Stack of a four-wide walk: up to three deferred children a level.
const STACK: usize = 256;
/// Stack of the binary nearest-point descent: one deferred child a level. A built tree is
/// at most `MEDIAN_BELOW` levels of SAH splits and then 31 of median splits deep (2^32
/// triangles halved down to leaves of two); a tree read back deeper is refused. (A smaller
/// stack is less to clear a query.)
const NEAREST_STACK: usize = MEDIAN_BELOW + 32;
/// A child that is a leaf: this bit, its first slot times 4 and its count less one.
const LEAF_BIT: u32 = 1 << 31;
/// No child.
const NONE: u32 = u32::MAX;

/// A node of the binary tree: its box, and either its two children (`count == 0`: at
/// `first` and `first + 1`, an even index) or its triangles (`first..first + count` in leaf
/// order).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
struct Node {
    lo: Vec3,
    first: u32,
    hi: Vec3,
    count: u32,
}

/// Two sibling nodes in one cache line.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(64))]
struct Pair([Node; 2]);

impl Node {
    /// Squared distance from `q` to the box (zero inside).
    #[inline(always)]
    fn distance_squared(&self, q: Vec3A) -> f32 {
        (Vec3A::from(self.lo) - q)
            .max(q - Vec3A::from(self.hi))
            .max(Vec3A::ZERO)
            .length_squared()
    }
}

/// A node of the tree: the boxes of up to four children, lane by lane (`lo[axis]`,
/// `hi[axis]`), and each child (a node's index, a leaf with [`LEAF_BIT`], or [`NONE`],
/// whose box is empty: `lo` infinite, `hi` minus infinite).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
struct Wide {
    lo: [Vec4; 3],
    hi: [Vec4; 3],
    child: [u32; 4],
}

/// The tree over a set of triangles, laid out twice: binary for the nearest-point descent
/// (which goes down the nearer side at once, testing its leaves as it meets them), four
/// lanes wide for the walks along rays and segments (which look at every box they pass).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NearTree {
    /// The binary nodes by pairs of siblings: node `i` is `pairs[i / 2].0[i % 2]`; the root
    /// is node 0 (node 1 is unused). Stored as their 32-bit words (see [`words`]).
    #[serde(with = "words")]
    pairs: Vec<Pair>,
    /// The wide nodes; the root is the first. Stored as their 32-bit words.
    #[serde(with = "words")]
    nodes: Vec<Wide>,
    /// Triangle of each leaf slot.
    triangles: Vec<u32>,
    /// Corners of each leaf slot's triangle, m (not stored: [`Self::restore`] makes them again).
    #[serde(skip)]
    corners: Vec<[DVec3; 3]>,
    /// The parent of each pair of binary siblings (the root's: [`NONE`]); not stored.
    #[serde(skip)]
    up: Vec<u32>,
}

/// One triangle to build from: its id, corners and (widened) box.
struct Item {
    triangle: u32,
    lo: Vec3,
    hi: Vec3,
    centre: Vec3,
}

mod build;
mod nearest;
#[cfg(test)]
mod tests;
mod walks;
mod words;

impl NearTree {
    /// The depth of the four-wide layout's deepest node (children after their parents).
    fn wide_depth(&self) -> usize {
        // Saturating: far beyond any stack.
        let mut depth = vec![0u8; self.nodes.len()];
        let mut deepest = 0u8;
        for (i, w) in self.nodes.iter().enumerate() {
            let below = depth[i].saturating_add(1);
            for &c in &w.child {
                if c != NONE && c & LEAF_BIT == 0 && (c as usize) < depth.len() {
                    depth[c as usize] = below;
                    deepest = deepest.max(below);
                }
            }
        }
        deepest as usize
    }

    /// The triangles of leaf `child` (a child with [`LEAF_BIT`]), with their corners.
    #[inline(always)]
    fn leaf(&self, child: u32) -> impl Iterator<Item = (u32, &[DVec3; 3])> {
        let first = ((child & !LEAF_BIT) >> 2) as usize;
        let slots = first..first + (child & 3) as usize + 1;
        self.triangles[slots.clone()].iter().copied().zip(&self.corners[slots])
    }

    /// Node `i` of the binary layout.
    #[inline(always)]
    fn node(&self, i: usize) -> &Node {
        &self.pairs[i >> 1].0[i & 1]
    }
}
