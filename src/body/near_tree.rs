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

use glam::{DVec3, Vec3};

/// Most triangles in a leaf.
const LEAF: usize = 2;
/// Bins of a split.
const BINS: usize = 12;

/// A node: its box, and either its two children (`count == 0`: at `first` and `first + 1`)
/// or its triangles (`first..first + count` in leaf order).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[repr(C, align(32))]
struct Node {
    lo: [f32; 3],
    first: u32,
    hi: [f32; 3],
    count: u32,
}

impl Node {
    /// Squared distance from `q` to the box (zero inside).
    #[inline(always)]
    fn distance_squared(&self, q: Vec3) -> f32 {
        let lo = Vec3::from_array(self.lo);
        let hi = Vec3::from_array(self.hi);
        (lo - q).max(q - hi).max(Vec3::ZERO).length_squared()
    }
}

/// The tree over a set of triangles.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NearTree {
    nodes: Vec<Node>,
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
        tree.nodes.push(Node::default());
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
        self.nodes[at].lo = lo.to_array();
        self.nodes[at].hi = hi.to_array();
        if items.len() <= LEAF {
            self.nodes[at].first = base as u32;
            self.nodes[at].count = items.len() as u32;
            self.triangles.extend(items.iter().map(|i| i.triangle));
            return;
        }
        let mid = sah_split(items);
        let first = self.nodes.len();
        self.nodes.push(Node::default());
        self.nodes.push(Node::default());
        self.nodes[at].first = first as u32;
        self.nodes[at].count = 0;
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
        self.nodes.is_empty()
    }

    /// Visits the triangles whose boxes lie nearer `q` than the bound: `bound` (squared,
    /// `f32`) to start with, then the least that `leaf(triangle, corners)` returned so far
    /// (`None`: the bound stands). Nearer children first.
    #[inline]
    pub fn nearest(&self, q: Vec3, mut bound: f32, mut leaf: impl FnMut(u32, &[DVec3; 3]) -> Option<f32>) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        if root.distance_squared(q) >= bound {
            return;
        }
        let mut stack = [(0u32, 0f32); 64];
        let mut depth = 0usize;
        let mut at = 0usize;
        loop {
            let node = self.nodes[at];
            if node.count > 0 {
                for (t, corners) in self.leaf(node) {
                    if let Some(b) = leaf(t, corners) {
                        bound = bound.min(b);
                    }
                }
            } else {
                let c = node.first as usize;
                let (da, db) = (self.nodes[c].distance_squared(q), self.nodes[c + 1].distance_squared(q));
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
    pub fn any_on_segment(&self, a: DVec3, b: DVec3, pad: f64, mut test: impl FnMut(u32, &[DVec3; 3]) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let o = a.as_vec3();
        let d = (b - a).as_vec3();
        let inv = Vec3::ONE / d;
        let (t0, t1) = (-pad as f32, 1.0 + pad as f32);
        let meets = |n: &Node| {
            let (mut lo, mut hi) = (t0, t1);
            for k in 0..3 {
                if d[k] == 0.0 {
                    if o[k] < n.lo[k] || o[k] > n.hi[k] {
                        return false;
                    }
                    continue;
                }
                let (s, e) = ((n.lo[k] - o[k]) * inv[k], (n.hi[k] - o[k]) * inv[k]);
                lo = lo.max(s.min(e));
                hi = hi.min(s.max(e));
            }
            lo <= hi
        };
        let mut stack = [0u32; 64];
        let mut depth = 0usize;
        if !meets(&self.nodes[0]) {
            return false;
        }
        let mut at = 0usize;
        loop {
            let node = self.nodes[at];
            if node.count > 0 {
                if self.leaf(node).any(|(t, corners)| test(t, corners)) {
                    return true;
                }
            } else {
                let c = node.first as usize;
                let (ma, mb) = (meets(&self.nodes[c]), meets(&self.nodes[c + 1]));
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
        let node = self.nodes[at];
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
