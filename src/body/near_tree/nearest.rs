//! The nearest-point descent (binary, nearer side first) and the gather of every
//! triangle within a bound (four lanes wide).

use super::*;

impl NearTree {
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
        // One stack for every descent of the query (not cleared between them: a descent
        // reads only what it pushed).
        let mut stack = [(0u32, 0f32); NEAREST_STACK];
        let start =
            start.filter(|&n| n != 1 && n < 2 * self.pairs.len() && self.node(n).count > 0 && !self.up.is_empty());
        let Some(mut below) = start else {
            self.descend(q, 0, (&mut bound, &mut fell), &mut stack, &mut leaf);
            return fell;
        };
        self.descend(q, below, (&mut bound, &mut fell), &mut stack, &mut leaf);
        while below > 1 {
            let other = below ^ 1;
            if self.node(other).distance_squared(q) < bound {
                self.descend(q, other, (&mut bound, &mut fell), &mut stack, &mut leaf);
            }
            below = self.up[below >> 1] as usize;
        }
        fell
    }

    /// The depth-first descent of [`Self::nearest`] through the subtree at binary node `at`,
    /// its deferred nodes on `stack`.
    #[inline(always)]
    fn descend(
        &self,
        q: Vec3A,
        mut at: usize,
        (bound, fell): (&mut f32, &mut Option<usize>),
        stack: &mut [(u32, f32); NEAREST_STACK],
        leaf: &mut impl FnMut(u32, &[DVec3; 3]) -> Option<f32>,
    ) {
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
}
