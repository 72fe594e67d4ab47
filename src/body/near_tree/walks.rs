//! The walks along segments and rays and over boxes, four lanes wide.

use super::*;

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
    pub(super) fn walk(&self, mut lanes: impl FnMut(&Wide) -> u32, mut leaf: impl FnMut(u32) -> bool) -> bool {
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
