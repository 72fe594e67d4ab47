//! A flat bounding-volume tree for the body's nearest-point queries: binned-SAH splits,
//! the two children of a node side by side (one cache line holds both boxes), a few
//! triangles a leaf with their corners stored in leaf order (no lookup through the mesh),
//! and a depth-first descent, nearer child first, that drops a deferred node when it is
//! taken back off the stack if the best distance found meanwhile has passed it.
//!
//! The tree only decides which triangles are looked at: the caller measures each one and
//! returns the bound (squared, `f32`) that prunes the rest, so a query gives exactly the
//! answer of a scan over every triangle as long as the boxes hold their triangles (they
//! are the callers' boxes, widened against `f32` rounding) and the bound is never below the
//! best distance.

use glam::{DVec3, Vec3, Vec3A};

/// Most triangles in a leaf.
const LEAF: usize = 2;
/// Bins of a split.
const BINS: usize = 12;

/// A node: its box, and either its two children (`count == 0`: at `first` and `first + 1`)
/// or its triangles (`first..first + count` in leaf order).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[repr(C)]
struct Node {
    lo: [f32; 3],
    first: u32,
    hi: [f32; 3],
    count: u32,
}

/// Two sibling nodes in one cache line.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[repr(C, align(64))]
struct Pair([Node; 2]);

impl Node {
    /// Squared distance from `q` to the box (zero inside).
    #[inline(always)]
    fn distance_squared(&self, q: Vec3A) -> f32 {
        let lo = Vec3A::from_array(self.lo);
        let hi = Vec3A::from_array(self.hi);
        (lo - q).max(q - hi).max(Vec3A::ZERO).length_squared()
    }
}

/// The tree over a set of triangles.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NearTree {
    /// Nodes by pairs of siblings: node `i` is `pairs[i / 2].0[i % 2]`; the root is node 0
    /// (node 1 is unused), so every pair of children starts at an even node.
    pairs: Vec<Pair>,
    /// Triangle of each leaf slot.
    triangles: Vec<u32>,
    /// Corners of each leaf slot's triangle, m (not stored: [`Self::restore`] makes them again).
    #[serde(skip)]
    corners: Vec<[DVec3; 3]>,
}

/// One triangle to build from: its id, corners and (widened) box.
struct Item {
    triangle: u32,
    lo: Vec3,
    hi: Vec3,
    centre: Vec3,
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
        tree.pairs.push(Pair::default());
        tree.split(0, &mut items, 0);
        tree.corners = tree.triangles.iter().map(|&t| corners(t)).collect();
        tree
    }

    /// Fills node `at` with `items` (whose first leaf slot is `base`).
    fn split(&mut self, at: usize, items: &mut [Item], base: usize) {
        let (lo, hi) = items
            .iter()
            .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), i| {
                (lo.min(i.lo), hi.max(i.hi))
            });
        let node = self.node_mut(at);
        node.lo = lo.to_array();
        node.hi = hi.to_array();
        if items.len() <= LEAF {
            let node = self.node_mut(at);
            node.first = base as u32;
            node.count = items.len() as u32;
            self.triangles.extend(items.iter().map(|i| i.triangle));
            return;
        }
        let mid = sah_split(items);
        let first = 2 * self.pairs.len();
        self.pairs.push(Pair::default());
        let node = self.node_mut(at);
        node.first = first as u32;
        node.count = 0;
        let (left, right) = items.split_at_mut(mid);
        self.split(first, left, base);
        self.split(first + 1, right, base + mid);
    }

    /// Makes the corners of a tree read back from storage again (`corners(t)`: triangle
    /// `t`'s corners, as given to [`Self::new`]).
    pub fn restore(&mut self, corners: impl Fn(u32) -> [DVec3; 3]) {
        self.corners = self.triangles.iter().map(|&t| corners(t)).collect();
    }

    /// The triangles of leaf `node`, with their corners.
    fn leaf(&self, node: Node) -> impl Iterator<Item = (u32, &[DVec3; 3])> {
        let slots = node.first as usize..(node.first + node.count) as usize;
        self.triangles[slots.clone()].iter().copied().zip(&self.corners[slots])
    }

    /// Whether the tree holds no triangle.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Node `i`.
    #[inline(always)]
    fn node(&self, i: usize) -> &Node {
        &self.pairs[i >> 1].0[i & 1]
    }

    fn node_mut(&mut self, i: usize) -> &mut Node {
        &mut self.pairs[i >> 1].0[i & 1]
    }

    /// Visits the triangles whose boxes lie nearer `q` than the bound: `bound` (squared,
    /// `f32`) to start with, then the least that `leaf(triangle, corners)` returned so far
    /// (`None`: the bound stands). Nearer children first.
    #[inline]
    pub fn nearest(&self, q: Vec3, mut bound: f32, mut leaf: impl FnMut(u32, &[DVec3; 3]) -> Option<f32>) {
        let q = Vec3A::from(q);
        let Some(root) = self.pairs.first().map(|p| &p.0[0]) else {
            return;
        };
        if root.distance_squared(q) >= bound {
            return;
        }
        let mut stack = [(0u32, 0f32); 64];
        let mut depth = 0usize;
        let mut at = 0usize;
        loop {
            let node = *self.node(at);
            if node.count > 0 {
                for (t, corners) in self.leaf(node) {
                    if let Some(b) = leaf(t, corners) {
                        bound = bound.min(b);
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
                if dn < bound {
                    if df < bound && depth < stack.len() {
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
                if d < bound {
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
        if self.pairs.is_empty() {
            return false;
        }
        let o = Vec3A::from(a.as_vec3());
        // A zero component made the least positive one: no 0 * infinity below, and the
        // box test along that axis is unchanged (the segment stays inside or outside it).
        let d = Vec3A::from(
            d.as_vec3()
                .to_array()
                .map(|x| if x == 0.0 { f32::MIN_POSITIVE } else { x }),
        );
        let inv = Vec3A::ONE / d;
        let (t0, t1) = (range[0] as f32, range[1] as f32);
        let meets = |n: &Node| {
            let s = (Vec3A::from_array(n.lo) - o) * inv;
            let e = (Vec3A::from_array(n.hi) - o) * inv;
            s.min(e).max_element().max(t0) <= s.max(e).min_element().min(t1)
        };
        let mut stack = [0u32; 64];
        let mut depth = 0usize;
        if !meets(self.node(0)) {
            return false;
        }
        let mut at = 0usize;
        loop {
            let node = *self.node(at);
            if node.count > 0 {
                if self.leaf(node).any(|(t, corners)| test(t, corners)) {
                    return true;
                }
            } else {
                let c = node.first as usize;
                let [a, b] = &self.pairs[c >> 1].0;
                let (ma, mb) = (meets(a), meets(b));
                if ma || mb {
                    if ma && mb {
                        if depth == stack.len() {
                            // Deeper than any tree built here; test the rest plainly.
                            return self.any_below(c + 1, &mut test) || self.any_below(c, &mut test);
                        }
                        stack[depth] = (c + 1) as u32;
                        depth += 1;
                    }
                    at = if ma { c } else { c + 1 };
                    continue;
                }
            }
            if depth == 0 {
                return false;
            }
            depth -= 1;
            at = stack[depth] as usize;
        }
    }

    /// Whether `test` holds for any triangle below node `at` (every one, no box test).
    fn any_below(&self, at: usize, test: &mut impl FnMut(u32, &[DVec3; 3]) -> bool) -> bool {
        let node = *self.node(at);
        if node.count > 0 {
            return self.leaf(node).any(|(t, corners)| test(t, corners));
        }
        let c = node.first as usize;
        self.any_below(c, test) || self.any_below(c + 1, test)
    }
}

/// Sorts `items` into two non-empty runs by the cheapest binned surface-area split along
/// the longest axis of their centres (the median where the centres coincide); the split.
fn sah_split(items: &mut [Item]) -> usize {
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
    if extent[axis] <= 0.0 {
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
