//! Hull hierarchies: a tree whose nodes carry a [`Kdop`] and whose leaves are items (the
//! sub-surfaces of a NURBS surface after `L` levels of quartering, or body triangles), and
//! the simultaneous descent of two trees that discards a pair of nodes as soon as their
//! hulls are farther apart than the caller's bound.

use glam::DVec3;

use super::hull::Kdop;
use super::split::quarter;
use super::surface::{Direction, NurbsSurface};

/// A node: its hull, and either children (`first..first + count` in the node list) or an
/// item.
#[derive(Clone, Debug)]
pub struct HullNode {
    /// Hull of everything below.
    pub hull: Kdop,
    /// First child.
    pub first: u32,
    /// Number of children (0 for a leaf).
    pub count: u32,
    /// The leaf's item (meaningless for an inner node).
    pub item: u32,
    /// Depth (0 at the root).
    pub depth: u8,
}

/// A hierarchy of hulls; node 0 is the root.
#[derive(Clone, Debug, Default)]
pub struct HullTree {
    /// Nodes, children stored together.
    pub nodes: Vec<HullNode>,
}

impl HullTree {
    /// The nodes at `depth` (leaves above it included when the tree is shallower there).
    pub fn at_depth(&self, depth: u8) -> impl Iterator<Item = &HullNode> {
        self.nodes
            .iter()
            .filter(move |n| n.depth == depth || (n.count == 0 && n.depth < depth))
    }

    /// A binary tree over items with the given hulls, split at the median of the items'
    /// hull centres along the axis where the centres spread most; one item per leaf.
    pub fn over_items(hulls: &[Kdop]) -> Self {
        let mut tree = Self { nodes: Vec::new() };
        if hulls.is_empty() {
            return tree;
        }
        let mut items: Vec<u32> = (0..hulls.len() as u32).collect();
        tree.nodes.push(leaf_node(Kdop::EMPTY, 0, 0));
        tree.fill(0, &mut items, hulls, 0);
        tree
    }

    fn fill(&mut self, slot: usize, items: &mut [u32], hulls: &[Kdop], depth: u8) {
        let hull = items.iter().fold(Kdop::EMPTY, |h, &i| h.merge(&hulls[i as usize]));
        if items.len() == 1 {
            self.nodes[slot] = leaf_node(hull, items[0], depth);
            return;
        }
        let centre = |i: u32| {
            let h = &hulls[i as usize];
            DVec3::new(h.min[0] + h.max[0], h.min[1] + h.max[1], h.min[2] + h.max[2])
        };
        let (lo, hi) = items
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &i| {
                (lo.min(centre(i)), hi.max(centre(i)))
            });
        let axis = (hi - lo).max_position();
        // Ties broken by item index, so the tree does not depend on the sort's stability.
        items.sort_unstable_by(|&a, &b| centre(a)[axis].total_cmp(&centre(b)[axis]).then(a.cmp(&b)));
        let first = self.nodes.len();
        self.nodes.push(leaf_node(Kdop::EMPTY, 0, depth + 1));
        self.nodes.push(leaf_node(Kdop::EMPTY, 0, depth + 1));
        self.nodes[slot] = HullNode {
            hull,
            first: first as u32,
            count: 2,
            item: 0,
            depth,
        };
        let (left, right) = items.split_at_mut(items.len() / 2);
        self.fill(first, left, hulls, depth + 1);
        self.fill(first + 1, right, hulls, depth + 1);
    }
}

fn leaf_node(hull: Kdop, item: u32, depth: u8) -> HullNode {
    HullNode {
        hull,
        first: 0,
        count: 0,
        item,
        depth,
    }
}

/// What a descent of two trees is told and tells.
pub trait PairVisitor {
    /// Pairs whose hulls are farther apart than this are discarded.
    fn bound(&self) -> f64;
    /// A pair of leaves within the bound, with their hulls' gap.
    fn leaves(&mut self, a: u32, b: u32, gap: f64);
    /// Whether the answer is final (the descent stops).
    fn done(&self) -> bool {
        false
    }
}

/// Descends `a` and `b` together from their roots: a pair of nodes whose hulls' gap exceeds
/// the visitor's bound is discarded with everything below it; otherwise the larger node (by
/// hull extent; an inner node before a leaf) is opened, and its children's pairs are
/// visited nearest first. Returns the number of hull pairs tested.
pub fn descend(a: &HullTree, b: &HullTree, visitor: &mut impl PairVisitor) -> u64 {
    if a.nodes.is_empty() || b.nodes.is_empty() {
        return 0;
    }
    let mut tests = 1u64;
    let root_gap = a.nodes[0].hull.gap(&b.nodes[0].hull);
    if root_gap > visitor.bound() {
        return tests;
    }
    let mut stack = vec![(0u32, 0u32, root_gap)];
    let mut children = Vec::with_capacity(4);
    while let Some((i, j, gap)) = stack.pop() {
        if visitor.done() {
            break;
        }
        if gap > visitor.bound() {
            continue;
        }
        let (na, nb) = (&a.nodes[i as usize], &b.nodes[j as usize]);
        if na.count == 0 && nb.count == 0 {
            visitor.leaves(na.item, nb.item, gap);
            continue;
        }
        let open_a = nb.count == 0 || (na.count > 0 && na.hull.extent() >= nb.hull.extent());
        children.clear();
        if open_a {
            for c in na.first..na.first + na.count {
                children.push((c, j, a.nodes[c as usize].hull.gap(&nb.hull)));
            }
        } else {
            for c in nb.first..nb.first + nb.count {
                children.push((i, c, na.hull.gap(&b.nodes[c as usize].hull)));
            }
        }
        tests += children.len() as u64;
        // Farthest pushed first, so the nearest is opened next.
        children.sort_by(|x, y| y.2.total_cmp(&x.2));
        let bound = visitor.bound();
        stack.extend(children.iter().copied().filter(|c| c.2 <= bound));
    }
    tests
}

/// One leaf of a subdivided surface: the sub-surface (exactly the original on `range`) and
/// its control points.
#[derive(Clone, Debug)]
pub struct Patch {
    /// The sub-surface.
    pub surface: NurbsSurface,
    /// Its control points (Euclidean), row-major.
    pub points: Vec<DVec3>,
    /// Its parameter box in u and in v.
    pub range: [(f64, f64); 2],
}

/// A NURBS surface subdivided `level` times by quartering (4^level leaves), with the hull of
/// every sub-surface's control points at every level.
#[derive(Clone, Debug)]
pub struct PatchTree {
    /// The hulls; leaf items index `patches`.
    pub tree: HullTree,
    /// The leaves.
    pub patches: Vec<Patch>,
    /// Levels of subdivision.
    pub level: u8,
}

impl PatchTree {
    /// Subdivides `surface` to `level` (a sub-surface that can no longer be split stays a
    /// leaf early).
    pub fn build(surface: &NurbsSurface, level: u8) -> Self {
        let mut out = Self {
            tree: HullTree {
                nodes: vec![leaf_node(Kdop::EMPTY, 0, 0)],
            },
            patches: Vec::new(),
            level,
        };
        out.fill(0, surface.clone(), 0);
        out
    }

    fn fill(&mut self, slot: usize, surface: NurbsSurface, depth: u8) {
        let points: Vec<DVec3> = surface.control_points().collect();
        let hull = Kdop::from_points(points.iter().copied());
        let parts = if depth < self.level { quarter(&surface) } else { None };
        let Some(parts) = parts else {
            let range = [surface.range(Direction::U), surface.range(Direction::V)];
            self.tree.nodes[slot] = leaf_node(hull, self.patches.len() as u32, depth);
            self.patches.push(Patch { surface, points, range });
            return;
        };
        let first = self.tree.nodes.len();
        for _ in 0..4 {
            self.tree.nodes.push(leaf_node(Kdop::EMPTY, 0, depth + 1));
        }
        self.tree.nodes[slot] = HullNode {
            hull,
            first: first as u32,
            count: 4,
            item: 0,
            depth,
        };
        for (k, part) in parts.into_iter().enumerate() {
            self.fill(first + k, part, depth + 1);
        }
    }
}
