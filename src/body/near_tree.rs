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

/// The binary build: nodes, and the triangles in leaf order.
#[derive(Default)]
struct Binary {
    nodes: Vec<Node>,
    triangles: Vec<u32>,
}

impl Binary {
    /// Fills node `at` with `items` (whose first leaf slot is `base`), `depth` levels down.
    fn split(&mut self, at: usize, items: &mut [Item], base: usize, depth: usize) {
        let (lo, hi) = items
            .iter()
            .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), i| {
                (lo.min(i.lo), hi.max(i.hi))
            });
        self.nodes[at].lo = lo;
        self.nodes[at].hi = hi;
        if items.len() <= LEAF {
            self.nodes[at].first = base as u32;
            self.nodes[at].count = items.len() as u32;
            self.triangles.extend(items.iter().map(|i| i.triangle));
            return;
        }
        let mid = sah_split(items, depth >= MEDIAN_BELOW);
        let first = self.nodes.len();
        self.nodes.push(Node::default());
        self.nodes.push(Node::default());
        self.nodes[at].first = first as u32;
        let (left, right) = items.split_at_mut(mid);
        self.split(first, left, base, depth + 1);
        self.split(first + 1, right, base + mid, depth + 1);
    }
}

impl NearTree {
    /// The tree over `triangles` (ids), `corners(t)` their corners, `bounds(t)` their
    /// boxes (each must hold its triangle in `f32`, with room for rounding).
    pub fn new(triangles: &[u32], corners: impl Fn(u32) -> [DVec3; 3], bounds: impl Fn(u32) -> (Vec3, Vec3)) -> Self {
        let mut items: Vec<Item> = triangles
            .iter()
            .map(|&t| {
                let (lo, hi) = bounds(t);
                Item {
                    triangle: t,
                    lo,
                    hi,
                    centre: 0.5 * (lo + hi),
                }
            })
            .collect();
        let mut tree = Self::default();
        if items.is_empty() {
            return tree;
        }
        let mut binary = Binary {
            // Node 1 unused: every pair of children starts at an even index.
            nodes: vec![Node::default(); 2],
            triangles: Vec::with_capacity(items.len()),
        };
        binary.split(0, &mut items, 0, 0);
        tree.triangles = std::mem::take(&mut binary.triangles);
        tree.nodes = widen(&binary.nodes);
        tree.pairs = binary.nodes.chunks(2).map(|c| Pair([c[0], c[1]])).collect();
        tree.corners = tree.triangles.iter().map(|&t| corners(t)).collect();
        tree.link(true);
        tree
    }

    /// The depth of the binary layout's deepest node, and with `parents`, [`Self::up`]
    /// made; `None` if the layout does not hold together (a leaf outside the slots, a
    /// child outside the nodes or not after its parent).
    fn link(&mut self, parents: bool) -> Option<usize> {
        let count = self.pairs.len() * 2;
        let slots = self.triangles.len();
        let mut up = if parents {
            vec![NONE; self.pairs.len()]
        } else {
            Vec::new()
        };
        // Depths by pair of siblings (saturating: far beyond any stack).
        let mut depth = vec![0u8; self.pairs.len()];
        let mut deepest = 0u8;
        for i in (0..count).filter(|&i| i != 1) {
            let n = *self.node(i);
            let first = n.first as usize;
            if n.count > 0 {
                if first + n.count as usize > slots {
                    return None;
                }
                continue;
            }
            // Children after their parent: no descent can loop.
            if !first.is_multiple_of(2) || first <= i || first >= count {
                return None;
            }
            if let Some(u) = up.get_mut(first >> 1) {
                *u = i as u32;
            }
            let below = depth[i >> 1].saturating_add(1);
            depth[first >> 1] = below;
            deepest = deepest.max(below);
        }
        self.up = up;
        Some(deepest as usize)
    }

    /// Makes the corners of a tree read back from storage again (`corners(t)`: triangle
    /// `t`'s corners, as given to [`Self::new`], for `t` below `count`), and with `parents`
    /// the links [`Self::nearest_from`] climbs (without them it searches from the root);
    /// `false`, and the tree unchanged, if the tree read back does not hold together (a
    /// child or a leaf outside its arrays or not after its parent, a triangle not below
    /// `count`, deeper than a query's stack), so that no query can index out of bounds or
    /// loop.
    pub fn restore(&mut self, count: usize, corners: impl Fn(u32) -> [DVec3; 3], parents: bool) -> bool {
        let slots = self.triangles.len();
        let leaf_fits = |first: usize, count: usize| count >= 1 && first + count <= slots;
        let wide = self.nodes.iter().enumerate().all(|(i, w)| {
            w.child.iter().all(|&c| {
                c == NONE
                    || if c & LEAF_BIT != 0 {
                        leaf_fits(((c & !LEAF_BIT) >> 2) as usize, (c & 3) as usize + 1)
                    } else {
                        c as usize > i && (c as usize) < self.nodes.len()
                    }
            })
        });
        let empty = self.pairs.is_empty() && self.nodes.is_empty();
        let rooted = empty || (!self.pairs.is_empty() && !self.nodes.is_empty());
        let fits = wide && self.wide_depth() * 3 + 4 <= STACK;
        if !(fits && rooted && self.triangles.iter().all(|&t| (t as usize) < count)) {
            return false;
        }
        if self.link(parents).is_none_or(|depth| depth > NEAREST_STACK) {
            self.up = Vec::new();
            return false;
        }
        self.corners = self.triangles.iter().map(|&t| corners(t)).collect();
        true
    }

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

    /// Visits the triangles whose boxes lie nearer `q` than the bound: `bound` (squared,
    /// `f32`) to start with, then the least that `leaf(triangle, corners)` returned so far
    /// (`None`: the bound stands). Nearer children first; a deferred child is dropped when
    /// it is taken off the stack if the bound has passed it. Returns the leaf (a binary
    /// node) where the bound last fell, if it fell: where the winner lies.
    #[inline]
    pub fn nearest(&self, q: Vec3, bound: f32, leaf: impl FnMut(u32, &[DVec3; 3]) -> Option<f32>) -> Option<usize> {
        self.nearest_from(q, bound, None, leaf)
    }

    /// [`Self::nearest`], starting at leaf `start` (where the winner of a search for a point
    /// nearby lay, as [`Self::nearest`] returns it) and going up from it: at each ancestor,
    /// the subtree of its other child is searched (from the top, as [`Self::nearest`])
    /// where its box lies within the bound. Those subtrees and the leaf are the whole tree,
    /// so the same triangles can win; the path down from the root is not walked. Without
    /// `start`, with one that is not a leaf of this tree, or on a tree read back without its
    /// parents, from the root.
    #[inline]
    pub fn nearest_from(
        &self,
        q: Vec3,
        mut bound: f32,
        start: Option<usize>,
        mut leaf: impl FnMut(u32, &[DVec3; 3]) -> Option<f32>,
    ) -> Option<usize> {
        let q = Vec3A::from(q);
        let root = self.pairs.first().map(|p| &p.0[0])?;
        if root.distance_squared(q) >= bound {
            return None;
        }
        let mut fell = None;
        let start =
            start.filter(|&n| n != 1 && n < 2 * self.pairs.len() && self.node(n).count > 0 && !self.up.is_empty());
        let Some(mut below) = start else {
            self.descend(q, 0, &mut bound, &mut fell, &mut leaf);
            return fell;
        };
        self.descend(q, below, &mut bound, &mut fell, &mut leaf);
        while below > 1 {
            let other = below ^ 1;
            if self.node(other).distance_squared(q) < bound {
                self.descend(q, other, &mut bound, &mut fell, &mut leaf);
            }
            below = self.up[below >> 1] as usize;
        }
        fell
    }

    /// The depth-first descent of [`Self::nearest`] through the subtree at binary node `at`.
    #[inline(always)]
    fn descend(
        &self,
        q: Vec3A,
        mut at: usize,
        bound: &mut f32,
        fell: &mut Option<usize>,
        leaf: &mut impl FnMut(u32, &[DVec3; 3]) -> Option<f32>,
    ) {
        let mut stack = [(0u32, 0f32); NEAREST_STACK];
        let mut depth = 0usize;
        loop {
            let node = *self.node(at);
            if node.count > 0 {
                let first = node.first as usize;
                let slots = first..first + node.count as usize;
                for (&t, corners) in self.triangles[slots.clone()].iter().zip(&self.corners[slots]) {
                    if let Some(b) = leaf(t, corners)
                        && b < *bound
                    {
                        *bound = b;
                        *fell = Some(at);
                    }
                }
            } else {
                let c = node.first as usize;
                let [a, b] = &self.pairs[c >> 1].0;
                let (da, db) = (a.distance_squared(q), b.distance_squared(q));
                let (near, dn, far, df) = if da <= db {
                    (c, da, c + 1, db)
                } else {
                    (c + 1, db, c, da)
                };
                if dn < *bound {
                    if df < *bound {
                        stack[depth] = (far as u32, df);
                        depth += 1;
                    }
                    at = near;
                    continue;
                }
            }
            // Back up to the nearest deferred node still within the bound.
            loop {
                if depth == 0 {
                    return;
                }
                depth -= 1;
                let (n, d) = stack[depth];
                if d < *bound {
                    at = n as usize;
                    break;
                }
            }
        }
    }
}

impl NearTree {
    /// Whether `test(triangle, corners)` holds for any triangle whose box the segment
    /// `a..b` meets: the boxes are tested in `f32` over the parameter range
    /// `[-pad, 1 + pad]`, so that rounding never drops a box the segment passes through.
    pub fn any_on_segment(&self, a: DVec3, b: DVec3, pad: f64, test: impl FnMut(u32, &[DVec3; 3]) -> bool) -> bool {
        self.any_on_ray(a, b - a, [-pad, 1.0 + pad], test)
    }

    /// Whether `test(triangle, corners)` holds for any triangle whose box meets the box
    /// `lo..hi` (tested in `f32`: widen the box by what rounding may take).
    pub fn any_in_box(&self, lo: DVec3, hi: DVec3, test: impl FnMut(u32, &[DVec3; 3]) -> bool) -> bool {
        let mut test = test;
        if self.nodes.is_empty() {
            return false;
        }
        let (qlo, qhi) = (
            lo.as_vec3().to_array().map(Vec4::splat),
            hi.as_vec3().to_array().map(Vec4::splat),
        );
        self.walk(
            |w| {
                let mut meets = Vec4::ONE.cmpeq(Vec4::ONE);
                for axis in 0..3 {
                    meets &= w.lo[axis].cmple(qhi[axis]) & w.hi[axis].cmpge(qlo[axis]);
                }
                meets.bitmask()
            },
            |leaf| self.leaf(leaf).any(|(t, corners)| test(t, corners)),
        )
    }

    /// Whether `test(triangle, corners)` holds for any triangle whose box the ray
    /// `a + t d` meets with `t` in `range` (tested in `f32`: widen the range by what
    /// rounding may take).
    pub fn any_on_ray(
        &self,
        a: DVec3,
        d: DVec3,
        range: [f64; 2],
        mut test: impl FnMut(u32, &[DVec3; 3]) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let (o, inv) = ray_lanes(a, d);
        let (t0, t1) = (Vec4::splat(range[0] as f32), Vec4::splat(range[1] as f32));
        self.walk(
            |w| {
                let (lo, hi) = slabs(w, o, inv, t0, t1);
                lo.cmple(hi).bitmask()
            },
            |leaf| self.leaf(leaf).any(|(t, corners)| test(t, corners)),
        )
    }

    /// The four-wide walk: from the root, into the children of each node whose lanes
    /// `lanes(node)` sets (a bit a lane), handing each leaf reached (a child with
    /// [`LEAF_BIT`]) to `leaf`, which stops the walk by returning true (and so does the
    /// walk).
    #[inline(always)]
    fn walk(&self, mut lanes: impl FnMut(&Wide) -> u32, mut leaf: impl FnMut(u32) -> bool) -> bool {
        let mut stack = [0u32; STACK];
        let mut depth = 1usize;
        while depth > 0 {
            depth -= 1;
            let child = stack[depth];
            if child & LEAF_BIT != 0 {
                if leaf(child) {
                    return true;
                }
                continue;
            }
            let w = &self.nodes[child as usize];
            let meets = lanes(w);
            for k in 0..4 {
                if meets & (1 << k) != 0 && w.child[k] != NONE {
                    stack[depth] = w.child[k];
                    depth += 1;
                }
            }
        }
        false
    }
}

impl NearTree {
    /// Visits every triangle whose box lies nearer `q` than `bound` (squared, `f32`), and
    /// the others of their leaves, each once, as `visit(triangle, corners)`, in no
    /// particular order: the walk reads the tree four
    /// lanes wide (a gather has no bound to tighten, so the binary descent's nearer-first
    /// order buys nothing).
    pub fn within(&self, q: Vec3, bound: f32, mut visit: impl FnMut(u32, &[DVec3; 3])) {
        if self.nodes.is_empty() {
            return;
        }
        let q = q.to_array().map(Vec4::splat);
        let bound = Vec4::splat(bound);
        self.walk(
            |w| {
                let mut d2 = Vec4::ZERO;
                for ((lo, hi), q) in w.lo.iter().zip(&w.hi).zip(&q) {
                    let gap = (*lo - *q).max(*q - *hi).max(Vec4::ZERO);
                    d2 += gap * gap;
                }
                d2.cmplt(bound).bitmask()
            },
            |leaf| {
                for (t, corners) in self.leaf(leaf) {
                    visit(t, corners);
                }
                false
            },
        );
    }

    /// The first hit along the ray `a + t d`, `t` in `range`: `hit(triangle, corners)` gives
    /// a triangle's parameter where the ray meets it; the least parameter wins, the lowest
    /// triangle among equals. Boxes are tested in `f32` over `range` and let through while
    /// they begin no later than the best parameter so far plus `pad` (widen both by what
    /// rounding may take), in lane order: sorting the lanes by where the ray enters them
    /// was measured slower (0.37 against 0.28 µs a ray that meets the body, behind the
    /// plain walk of [`BodyIndex::cast_ray`](super::index::BodyIndex::cast_ray)).
    pub fn first_on_ray(
        &self,
        a: DVec3,
        d: DVec3,
        range: [f64; 2],
        pad: f64,
        corners_hit: impl FnMut(u32, &[DVec3; 3]) -> Option<f64>,
    ) -> Option<(f64, u32)> {
        let mut hit = corners_hit;
        if self.nodes.is_empty() {
            return None;
        }
        let (o, inv) = ray_lanes(a, d);
        let (t0, t1) = (Vec4::splat(range[0] as f32), Vec4::splat(range[1] as f32));
        let mut best: Option<(f64, u32)> = None;
        let limit = |best: Option<(f64, u32)>| best.map_or(f32::INFINITY, |(t, _)| (t + pad) as f32);
        let mut stack = [(0u32, 0f32); STACK];
        let mut depth = 1usize;
        stack[0] = (0, range[0] as f32);
        while depth > 0 {
            depth -= 1;
            let (child, entry) = stack[depth];
            if entry > limit(best) {
                continue;
            }
            if child & LEAF_BIT != 0 {
                for (t, corners) in self.leaf(child) {
                    if let Some(at) = hit(t, corners) {
                        let better = best.is_none_or(|(bt, bi)| at < bt || (at == bt && t < bi));
                        if better {
                            best = Some((at, t));
                        }
                    }
                }
                continue;
            }
            let w = &self.nodes[child as usize];
            let (lo, hi) = slabs(w, o, inv, t0, t1);
            let meets = lo.cmple(hi).bitmask();
            let lo = lo.to_array();
            // The lanes met, in lane order: no sorting, which would cost every ray (most meet
            // nothing) more than it saves the few that meet the body.
            for (k, (&child, &entry)) in w.child.iter().zip(&lo).enumerate() {
                if meets & (1 << k) != 0 && child != NONE && entry <= limit(best) {
                    stack[depth] = (child, entry);
                    depth += 1;
                }
            }
        }
        best
    }
}

/// The ray's origin and inverse direction, each coordinate in four lanes (a zero direction
/// component made the least positive float: no 0 x infinity in the slab tests, and the box
/// test along that axis is unchanged, the ray staying inside or outside the slab).
fn ray_lanes(a: DVec3, d: DVec3) -> ([Vec4; 3], [Vec4; 3]) {
    let inv = d
        .as_vec3()
        .to_array()
        .map(|x| 1.0 / if x == 0.0 { f32::MIN_POSITIVE } else { x });
    (a.as_vec3().to_array().map(Vec4::splat), inv.map(Vec4::splat))
}

/// Where the ray enters and leaves each of `w`'s four boxes, clipped to `[t0, t1]` (met
/// where entry <= exit).
#[inline(always)]
fn slabs(w: &Wide, o: [Vec4; 3], inv: [Vec4; 3], t0: Vec4, t1: Vec4) -> (Vec4, Vec4) {
    let (mut lo, mut hi) = (t0, t1);
    for axis in 0..3 {
        let s = (w.lo[axis] - o[axis]) * inv[axis];
        let e = (w.hi[axis] - o[axis]) * inv[axis];
        lo = lo.max(s.min(e));
        hi = hi.min(s.max(e));
    }
    (lo, hi)
}

/// Nodes stored as one byte string of their 32-bit words (little-endian), so that reading
/// them back is a copy, not a decode of every field.
mod words {
    use glam::{Vec3, Vec4};
    use serde::de::{Error, SeqAccess, Visitor};
    use serde::{Deserializer, Serializer};

    use super::{Node, Pair, Wide};

    /// A node as a fixed number of words.
    pub trait Words: Sized {
        /// How many.
        const N: usize;
        /// Its words.
        fn put(&self, out: &mut Vec<u32>);
        /// From its words (`w.len() == N`).
        fn take(w: &[u32]) -> Self;
    }

    fn f(w: u32) -> f32 {
        f32::from_bits(w)
    }

    impl Words for Pair {
        const N: usize = 16;
        fn put(&self, out: &mut Vec<u32>) {
            for n in &self.0 {
                out.extend(n.lo.to_array().map(f32::to_bits));
                out.push(n.first);
                out.extend(n.hi.to_array().map(f32::to_bits));
                out.push(n.count);
            }
        }
        fn take(w: &[u32]) -> Self {
            let node = |w: &[u32]| Node {
                lo: Vec3::new(f(w[0]), f(w[1]), f(w[2])),
                first: w[3],
                hi: Vec3::new(f(w[4]), f(w[5]), f(w[6])),
                count: w[7],
            };
            Pair([node(&w[..8]), node(&w[8..])])
        }
    }

    impl Words for Wide {
        const N: usize = 28;
        fn put(&self, out: &mut Vec<u32>) {
            for v in self.lo.iter().chain(&self.hi) {
                out.extend(v.to_array().map(f32::to_bits));
            }
            out.extend(self.child);
        }
        fn take(w: &[u32]) -> Self {
            let v = |k: usize| Vec4::new(f(w[4 * k]), f(w[4 * k + 1]), f(w[4 * k + 2]), f(w[4 * k + 3]));
            Wide {
                lo: [v(0), v(1), v(2)],
                hi: [v(3), v(4), v(5)],
                child: [w[24], w[25], w[26], w[27]],
            }
        }
    }

    pub fn serialize<T: Words, S: Serializer>(nodes: &[T], s: S) -> Result<S::Ok, S::Error> {
        let mut w = Vec::with_capacity(nodes.len() * T::N);
        for n in nodes {
            n.put(&mut w);
        }
        let bytes: Vec<u8> = w.into_iter().flat_map(u32::to_le_bytes).collect();
        s.serialize_bytes(&bytes)
    }

    /// Decodes the nodes straight from the byte string (one allocation: the nodes').
    struct Nodes<T>(std::marker::PhantomData<T>);

    fn decode<T: Words, E: Error>(bytes: &[u8]) -> Result<Vec<T>, E> {
        if !bytes.len().is_multiple_of(4 * T::N) {
            return Err(E::custom(format!("{} bytes of tree nodes", bytes.len())));
        }
        let mut w = vec![0u32; T::N];
        Ok(bytes
            .chunks_exact(4 * T::N)
            .map(|node| {
                for (x, b) in w.iter_mut().zip(node.chunks_exact(4)) {
                    *x = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                }
                T::take(&w)
            })
            .collect())
    }

    impl<'de, T: Words> Visitor<'de> for Nodes<T> {
        type Value = Vec<T>;
        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("a byte string of tree nodes")
        }
        fn visit_bytes<E: Error>(self, v: &[u8]) -> Result<Vec<T>, E> {
            decode(v)
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
            let mut bytes = Vec::new();
            while let Some(b) = seq.next_element()? {
                bytes.push(b);
            }
            decode(&bytes)
        }
    }

    pub fn deserialize<'de, T: Words, D: Deserializer<'de>>(d: D) -> Result<Vec<T>, D::Error> {
        d.deserialize_bytes(Nodes(std::marker::PhantomData))
    }
}

/// The wide nodes of the binary tree `nodes` (root 0, children at even indices).
fn widen(nodes: &[Node]) -> Vec<Wide> {
    let mut out = Vec::new();
    if nodes.is_empty() {
        return out;
    }
    if nodes[0].count > 0 {
        // A single leaf: a root with one child.
        out.push(empty());
        set_lane(&mut out, 0, 0, nodes, 0);
    } else {
        collapse(&mut out, nodes, 0);
    }
    out
}

/// A wide node with no child.
fn empty() -> Wide {
    Wide {
        lo: [Vec4::INFINITY; 3],
        hi: [Vec4::NEG_INFINITY; 3],
        child: [NONE; 4],
    }
}

/// Half the surface area of binary node `n`'s box.
fn area(n: &Node) -> f32 {
    let d = (n.hi - n.lo).max(Vec3::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// Lane `k` of wide node `w` holds binary node `b` (a leaf, or a wide node made for it).
fn set_lane(out: &mut Vec<Wide>, w: usize, k: usize, nodes: &[Node], b: usize) {
    let n = nodes[b];
    for axis in 0..3 {
        out[w].lo[axis][k] = n.lo[axis];
        out[w].hi[axis][k] = n.hi[axis];
    }
    out[w].child[k] = if n.count > 0 {
        LEAF_BIT | (n.first << 2) | (n.count - 1)
    } else {
        collapse(out, nodes, b) as u32
    };
}

/// A wide node for the binary interior node `b`: its two children, the largest of the
/// interior ones opened into its own two while there is room for four; its index.
fn collapse(out: &mut Vec<Wide>, nodes: &[Node], b: usize) -> usize {
    let mut lanes = [0usize; 4];
    lanes[0] = nodes[b].first as usize;
    lanes[1] = lanes[0] + 1;
    let mut n = 2;
    while n < 4 {
        let open = (0..n)
            .filter(|&k| nodes[lanes[k]].count == 0)
            .max_by(|&a, &c| area(&nodes[lanes[a]]).total_cmp(&area(&nodes[lanes[c]])));
        let Some(k) = open else { break };
        let first = nodes[lanes[k]].first as usize;
        lanes.copy_within(k + 1..n, k + 2);
        lanes[k] = first;
        lanes[k + 1] = first + 1;
        n += 1;
    }
    let w = out.len();
    out.push(empty());
    for (k, &lane) in lanes[..n].iter().enumerate() {
        set_lane(out, w, k, nodes, lane);
    }
    w
}

/// Sorts `items` into two non-empty runs by the cheapest binned surface-area split along
/// the longest axis of their centres (the median where the centres coincide); the split.
fn sah_split(items: &mut [Item], median_only: bool) -> usize {
    let (clo, chi) = items
        .iter()
        .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), i| {
            (lo.min(i.centre), hi.max(i.centre))
        });
    let extent = chi - clo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let median = |items: &mut [Item]| {
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |a, b| {
            a.centre[axis]
                .total_cmp(&b.centre[axis])
                .then(a.triangle.cmp(&b.triangle))
        });
        mid
    };
    if median_only || extent[axis] <= 0.0 {
        return median(items);
    }
    let bin_of = |c: f32| (((c - clo[axis]) / extent[axis] * BINS as f32) as usize).min(BINS - 1);
    let mut counts = [0usize; BINS];
    let mut boxes = [(Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)); BINS];
    for i in items.iter() {
        let b = bin_of(i.centre[axis]);
        counts[b] += 1;
        boxes[b] = (boxes[b].0.min(i.lo), boxes[b].1.max(i.hi));
    }
    let area = |(lo, hi): (Vec3, Vec3)| {
        let d = (hi - lo).max(Vec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    };
    let merge = |a: (Vec3, Vec3), b: (Vec3, Vec3)| (a.0.min(b.0), a.1.max(b.1));
    let empty = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    // Right-side areas and counts for every cut.
    let mut right = [(0.0f32, 0usize); BINS];
    let (mut acc, mut n) = (empty, 0);
    for b in (1..BINS).rev() {
        acc = merge(acc, boxes[b]);
        n += counts[b];
        right[b] = (area(acc), n);
    }
    let (mut acc, mut n) = (empty, 0);
    let mut best = (f32::INFINITY, 0);
    for b in 1..BINS {
        acc = merge(acc, boxes[b - 1]);
        n += counts[b - 1];
        let (ra, rn) = right[b];
        if n == 0 || rn == 0 {
            continue;
        }
        let cost = area(acc) * n as f32 + ra * rn as f32;
        if cost < best.0 {
            best = (cost, b);
        }
    }
    if best.1 == 0 {
        return median(items);
    }
    let cut = best.1;
    // In place, the same way every time (so the tree is the same for the same input).
    let mut mid = 0;
    for j in 0..items.len() {
        if bin_of(items[j].centre[axis]) < cut {
            items.swap(mid, j);
            mid += 1;
        }
    }
    mid
}

#[cfg(test)]
mod tests {
    use glam::{DVec3, Vec3};

    use super::{NEAREST_STACK, NearTree, Node, Pair};

    /// Whether segment `ab` meets triangle `t` (Möller-Trumbore, parameter in `[0, 1]`).
    fn crosses(a: DVec3, b: DVec3, [p, q, r]: [DVec3; 3]) -> bool {
        let (d, e1, e2) = (b - a, q - p, r - p);
        let h = d.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-300 {
            return false;
        }
        let s = a - p;
        let u = s.dot(h) / det;
        let w = s.cross(e1);
        let v = d.dot(w) / det;
        let t = e2.dot(w) / det;
        (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && (0.0..=1.0).contains(&t)
    }

    /// Numbers in `[0, 1)`.
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Distance from `p` to segment `ab`.
    fn to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
        let ab = b - a;
        let t = if ab.length_squared() > 0.0 {
            ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        p.distance(a + ab * t)
    }

    /// Distance from `p` to triangle `abc` (its plane where `p` projects inside it by the
    /// signs of the edges' cross products, else the nearest edge), written here apart from
    /// the library's closest point.
    fn to_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
        let n = (b - a).cross(c - a);
        if n.length_squared() > 0.0 {
            let q = p - n * ((p - a).dot(n) / n.length_squared());
            if [(a, b), (b, c), (c, a)]
                .iter()
                .all(|&(u, v)| (v - u).cross(q - u).dot(n) >= 0.0)
            {
                return p.distance(q);
            }
        }
        to_segment(p, a, b).min(to_segment(p, b, c)).min(to_segment(p, c, a))
    }

    /// Triangle soups the body never gives: a cluster of near-coincident triangles, a run
    /// shrinking geometrically towards a point (which drives surface-area splits deep), and
    /// triangles scattered at random. For each, the tree's nearest distance equals a scan
    /// of every triangle, at points near and far, searched from the root or from any
    /// triangle's leaf; a gather within a radius visits every triangle nearer than it; and
    /// its walk along a segment finds a
    /// crossing exactly when a scan does, with the caller's boxes widened as the body index
    /// widens its own.
    #[test]
    fn nearest_points_and_segment_walks_through_the_tree_equal_a_scan_of_every_triangle_on_awkward_soups() {
        let mut rng = Lcg(3);
        let mut jitter = |s: f64| DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * s;
        let mut soups: Vec<Vec<[DVec3; 3]>> = Vec::new();
        soups.push(
            (0..600)
                .map(|_| {
                    [
                        jitter(1e-4),
                        jitter(1e-4) + DVec3::X * 1e-3,
                        jitter(1e-4) + DVec3::Y * 1e-3,
                    ]
                })
                .collect(),
        );
        soups.push(
            (0..300)
                .map(|k| {
                    let s = 0.8f64.powi(k);
                    [DVec3::splat(s), DVec3::new(s, 0.0, 0.0) * 1.1, DVec3::new(0.0, s, s)]
                })
                .collect(),
        );
        soups.push(
            (0..2000)
                .map(|_| {
                    let c = jitter(2.0);
                    [c, c + jitter(0.05), c + jitter(0.05)]
                })
                .collect(),
        );
        for (k, soup) in soups.iter().enumerate() {
            let ids: Vec<u32> = (0..soup.len() as u32).collect();
            let slack = 1e-6;
            let tree = NearTree::new(
                &ids,
                |t| soup[t as usize],
                |t| {
                    let [a, b, c] = soup[t as usize];
                    let (lo, hi) = (
                        a.min(b).min(c) - DVec3::splat(slack),
                        a.max(b).max(c) + DVec3::splat(slack),
                    );
                    (lo.as_vec3(), hi.as_vec3())
                },
            );
            for _ in 0..300 {
                let p = jitter(if k == 2 { 5.0 } else { 0.01 });
                let truth = soup.iter().map(|&t| to_triangle(p, t)).fold(f64::INFINITY, f64::min);
                let mut best = f64::INFINITY;
                tree.nearest(p.as_vec3(), f32::INFINITY, |_, corners| {
                    let d = to_triangle(p, *corners);
                    best = best.min(d);
                    Some(((d + 1e-5) * (d + 1e-5)) as f32)
                });
                assert_eq!(best, truth, "soup {k}, {p}");
                // Started from any node (a leaf, an inner node or none of the tree's, which
                // start from the root): the same.
                let start = (jitter(1.0).x + 0.5) * (2 * tree.pairs.len() + 5) as f64;
                let mut best = f64::INFINITY;
                tree.nearest_from(p.as_vec3(), f32::INFINITY, Some(start as usize), |_, corners| {
                    let d = to_triangle(p, *corners);
                    best = best.min(d);
                    Some(((d + 1e-5) * (d + 1e-5)) as f32)
                });
                assert_eq!(best, truth, "soup {k}, {p}, from node {start}");
                // Gathering within a radius: every triangle nearer than it is visited, once.
                let radius = (truth + 1e-4) * (1.0 + 3.0 * jitter(1.0).x.abs());
                let mut visited = Vec::new();
                tree.within(p.as_vec3(), (radius * radius) as f32, |t, _| visited.push(t));
                visited.sort_unstable();
                let count = visited.len();
                visited.dedup();
                assert_eq!(visited.len(), count, "soup {k}, {p}: a triangle visited twice");
                for (t, &tri) in soup.iter().enumerate() {
                    let d = to_triangle(p, tri);
                    let seen = visited.binary_search(&(t as u32)).is_ok();
                    assert!(
                        seen || d >= radius,
                        "soup {k}, {p}: triangle {t} at {d} < {radius} missed"
                    );
                }
            }
            // Segments: the walk may look at more triangles than it must, never at fewer.
            let mut hits = 0;
            for _ in 0..300 {
                let a = jitter(if k == 2 { 5.0 } else { 0.01 });
                // Through the middle of the small soups; anywhere in the scattered one.
                let b = if k == 2 {
                    // Through a triangle's centre, a little off it.
                    let [p, q, r] = soup[(a.x.abs() * 1e4) as usize % soup.len()];
                    2.0 * (p + q + r) / 3.0 - a + jitter(0.02)
                } else {
                    2.0 * DVec3::new(5e-4, 5e-4, 0.0) - a + jitter(1e-3)
                };
                let truth = soup.iter().any(|&t| crosses(a, b, t));
                let walked = tree.any_on_segment(a, b, 1e-5, |_, c| crosses(a, b, *c));
                assert_eq!(walked, truth, "soup {k}, {a} -> {b}");
                hits += usize::from(truth);
            }
            assert!(hits >= 10, "soup {k}: {hits} segments met a triangle");
        }
    }

    /// A tree read back holds together or is refused: intact it is restored; a wide child
    /// pointing back at its parent, a binary child before its parent, a leaf past the
    /// slots or a triangle past the count are refused (each would loop or index out of
    /// bounds in a query).
    #[test]
    fn a_tree_read_back_that_does_not_hold_together_is_refused() {
        let soup: Vec<[DVec3; 3]> = (0..50)
            .map(|k| {
                let c = DVec3::new(k as f64, 0.0, 0.0);
                [c, c + DVec3::X * 0.5, c + DVec3::Y]
            })
            .collect();
        let ids: Vec<u32> = (0..50).collect();
        let corners = |t: u32| soup[t as usize];
        let tree = NearTree::new(&ids, corners, |t| {
            let [a, b, c] = soup[t as usize];
            (a.min(b).min(c).as_vec3(), a.max(b).max(c).as_vec3())
        });
        assert!(tree.clone().restore(50, corners, true));
        let mut looped = tree.clone();
        looped.nodes[0].child[0] = 0;
        assert!(!looped.restore(50, corners, true));
        let mut back = tree.clone();
        back.pairs[1].0[0].first = 0;
        assert!(!back.restore(50, corners, true));
        let mut past = tree.clone();
        past.triangles.pop();
        assert!(!past.restore(50, corners, true));
        assert!(!tree.clone().restore(49, corners, true));
    }

    /// A binary chain `levels` deep over 200 triangles: every internal node's first child
    /// goes on down, its second is a one-triangle leaf; every box holds everything.
    fn chain(levels: usize) -> NearTree {
        let soup: Vec<[DVec3; 3]> = (0..200)
            .map(|k| {
                [
                    DVec3::X * k as f64,
                    DVec3::new(k as f64, 1.0, 0.0),
                    DVec3::new(k as f64, 0.0, 1.0),
                ]
            })
            .collect();
        let ids: Vec<u32> = (0..200).collect();
        let mut tree = NearTree::new(&ids, |t| soup[t as usize], |_| (Vec3::splat(-1e3), Vec3::splat(1e3)));
        let node = |first: usize, count: u32| Node {
            lo: Vec3::splat(-1e3),
            first: first as u32,
            hi: Vec3::splat(1e3),
            count,
        };
        tree.pairs = (0..=levels)
            .map(|k| match k {
                0 => Pair([node(2, 0), node(0, 0)]),
                k if k == levels => Pair([node(k, 1), node(k + 100, 1)]),
                k => Pair([node(2 * k + 2, 0), node(k, 1)]),
            })
            .collect();
        tree
    }

    /// A tree read back deeper than the nearest-point descent's stack is refused; one level
    /// less is taken, and a descent that defers a child at every level (every box holds the
    /// point) runs through it.
    #[test]
    fn a_tree_read_back_too_deep_for_the_descent_is_refused() {
        let corners = |t: u32| {
            [
                DVec3::X * t as f64,
                DVec3::new(t as f64, 1.0, 0.0),
                DVec3::new(t as f64, 0.0, 1.0),
            ]
        };
        assert!(!chain(NEAREST_STACK + 1).restore(200, corners, true));
        let mut deepest = chain(NEAREST_STACK);
        assert!(deepest.restore(200, corners, true));
        assert_eq!(deepest.link(true), Some(NEAREST_STACK));
        let mut seen = 0;
        deepest.nearest(Vec3::ZERO, f32::INFINITY, |_, _| {
            seen += 1;
            None
        });
        assert_eq!(seen, NEAREST_STACK + 1);
    }
}
