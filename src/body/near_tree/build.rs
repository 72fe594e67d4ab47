//! Building the tree: binned-SAH splits, the binary layout and the four-wide one, and a
//! tree read back checked and linked.

use super::*;

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
    pub(super) fn link(&mut self, parents: bool) -> Option<usize> {
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
