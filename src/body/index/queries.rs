//! The body index's queries: nearest points (whole body, a partition, among candidates),
//! signed distance and the side of a point, the winding number, rays, boxes, segments and
//! the exact test of a garment face against the body's edges.

use super::*;

impl BodyIndex {
    /// The corners of triangle `t`.
    pub fn corners(&self, t: u32) -> [DVec3; 3] {
        self.triangles[t as usize].map(|i| self.positions[i as usize])
    }

    /// The partition a height falls in (the nearest one outside them all).
    pub fn partition_at(&self, y: f64) -> Option<usize> {
        let inside = self.partitions.iter().position(|p| y >= p.lower_y && y < p.upper_y);
        inside.or_else(|| {
            (0..self.partitions.len()).min_by(|&a, &b| {
                let d = |i: usize| {
                    let p = &self.partitions[i];
                    (p.lower_y - y).max(y - p.upper_y)
                };
                d(a).total_cmp(&d(b))
            })
        })
    }

    /// Distance from `p` to triangle `t`, with its foot, feature and pseudo-normal.
    pub fn nearest_on(&self, p: DVec3, t: u32) -> Nearest {
        self.exact_side(p, self.candidate(p, t))
    }

    /// [`Self::nearest_on`] without the exact side (`behind` is `None`): for the candidates
    /// of a search, the winner gets its side afterwards.
    fn candidate(&self, p: DVec3, t: u32) -> Nearest {
        let (foot, feature) = closest_on_triangle(p, self.corners(t));
        self.at_feature(t, foot, feature, p.distance(foot))
    }

    /// The candidate of triangle `t` whose nearest point `foot` (at `distance`) lies on
    /// `feature`, with that feature's pseudo-normal.
    pub(in crate::body) fn at_feature(&self, t: u32, foot: DVec3, feature: Feature, distance: f64) -> Nearest {
        let normal = match feature {
            Feature::Face => self.face_normals[t as usize],
            Feature::Edge(k) => self.edge_normals[t as usize][k as usize],
            Feature::Vertex(k) => self.vertex_normals[self.triangles[t as usize][k as usize] as usize],
        };
        Nearest {
            triangle: t,
            foot,
            feature,
            distance,
            normal,
            behind: None,
        }
    }

    /// `n` with the exact side of `p` where its foot lies inside a face.
    fn exact_side(&self, p: DVec3, mut n: Nearest) -> Nearest {
        if n.feature == Feature::Face {
            let [a, b, c] = self.corners(n.triangle);
            n.behind = Some(side(a, b, c, p) == Ordering::Less);
        }
        n
    }

    /// The nearest point among `candidates` (ties: the lowest triangle index).
    pub fn nearest_among(&self, p: DVec3, candidates: impl Iterator<Item = u32>) -> Option<Nearest> {
        let mut best: Option<Nearest> = None;
        for t in candidates {
            let n = self.candidate(p, t);
            if best.is_none_or(|b| n.distance < b.distance || (n.distance == b.distance && t < b.triangle)) {
                best = Some(n);
            }
        }
        best.map(|n| self.settle(p, n))
    }

    /// The shell's triangles (every triangle not buried), ascending.
    pub fn shell_triangles(&self) -> impl Iterator<Item = u32> + '_ {
        self.leaves.iter().copied()
    }

    /// `n` with a normal that gives `p` its true side where the pseudo-normals cannot be
    /// trusted (next to a self-crossing): the side counted along rays.
    pub(in crate::body) fn settle(&self, p: DVec3, n: Nearest) -> Nearest {
        let mut n = self.exact_side(p, n);
        if n.distance > self.resolved() && self.tangled.get(n.triangle as usize).copied().unwrap_or(false) {
            let away = (p - n.foot) / n.distance;
            n.normal = if self.winding(p) >= 1 { -away } else { away };
            n.behind = None;
        }
        n
    }

    /// The winding number of the whole surface (buried triangles too) about `p`, counted as
    /// the signed crossings of a ray (leaving the body +1, entering -1); the median of
    /// three rays in fixed directions, so that one ray grazing an edge cannot decide.
    pub fn winding(&self, p: DVec3) -> i32 {
        let tree = self.all.as_ref().unwrap_or(&self.near);
        let reach = 4.0 * self.height + p.length();
        let mut counts = WINDING_RAYS.map(|dir| {
            let pad = self.slack / dir.length();
            let mut count = 0;
            // Every triangle along the ray, counted by the side it is crossed from.
            tree.any_on_ray(p, dir, [-pad, reach + pad], |t, corners| {
                count += match ray_triangle(p, dir, *corners, 0.0, reach) {
                    Some(_) if dir.dot(self.face_normals[t as usize]) > 0.0 => 1,
                    Some(_) => -1,
                    None => 0,
                };
                false
            });
            count
        });
        counts.sort_unstable();
        counts[1]
    }

    /// The nearest point within `reach` of `p` among the triangles of `tree` (those `member`
    /// accepts).
    ///
    /// One depth-first pass, nearer child first ([`NearTree::nearest`]), pruned in `f32` by
    /// the best distance so far plus the boxes' slack, so that no triangle as near as the winner
    /// is ever pruned; the winner is picked in `f64` (ties: the lowest triangle index). The
    /// search starts from `hint` (a triangle found for a point nearby): its distance is the
    /// first bound, which only prunes, so the answer is the same with any hint or none. (A
    /// walk over the body's adjacency from the hint before descending was measured and
    /// dropped: the nearer-first descent visits as few leaves without it, 5.6 a query on
    /// the demo's garment, and the walk's own triangle tests cost more than they save.)
    ///
    /// With `upward`, a search on the same tree as this thread's last upward one starts at
    /// the leaf where that one's winner lay and goes up ([`NearTree::nearest_from`]; the
    /// hint is then not needed): faster when the last query was next to this one (vertex
    /// after vertex, as detection asks), slower when it was far (as between the edge
    /// rounds' crossings, which is why the whole-body search keeps the descent from the
    /// root). The answer is the same either way.
    fn nearest_in(
        &self,
        tree: &NearTree,
        member: impl Fn(u32) -> bool,
        p: DVec3,
        reach: f64,
        hint: Option<u32>,
        upward: bool,
    ) -> Option<Nearest> {
        let tree_key = std::ptr::from_ref(tree) as usize;
        let from = upward
            .then(|| LAST_LEAF.get())
            .filter(|&(key, _)| key == tree_key)
            .map(|(_, leaf)| leaf);
        let hint = hint.filter(|&t| from.is_none() && (t as usize) < self.triangles.len() && member(t));
        let start = hint.map(|t| self.candidate(p, t)).filter(|n| n.distance <= reach);
        let mut best = start;
        let limit = start.map_or(reach, |n| n.distance) + self.slack;
        let slack = self.slack;
        // A candidate whose squared distance lies beyond this is farther than the best so
        // far (or the reach) even once its square root is rounded: it can neither win nor
        // tie, and its bound would not lower the least so far. No square root for it.
        let mut past = beyond(start.map_or(reach, |n| n.distance));
        // Costs are squared distances (no square root per box).
        let fell = tree.nearest_from(p.as_vec3(), (limit * limit) as f32, from, |t, corners| {
            let (foot, feature) = closest_on_triangle(p, *corners);
            let distance2 = p.distance_squared(foot);
            if distance2 > past {
                return None;
            }
            let distance = distance2.sqrt();
            let better = best.is_none_or(|b| distance < b.distance || (distance == b.distance && t < b.triangle));
            if distance <= reach && better {
                // The pseudo-normal is looked up for the candidates that win only.
                best = Some(self.at_feature(t, foot, feature, distance));
                past = beyond(distance);
            }
            let cost = distance + slack;
            Some((cost * cost) as f32)
        });
        if upward && let Some(leaf) = fell {
            LAST_LEAF.set((tree_key, leaf));
        }
        let best = best?;
        LAST_FOUND.set((self.key(), best.triangle));
        Some(self.settle(p, best))
    }

    /// This index's key for [`LAST_FOUND`].
    fn key(&self) -> usize {
        std::ptr::from_ref(self) as usize
    }

    /// The last triangle this thread found on this index, as a hint.
    fn last_found(&self) -> Option<u32> {
        let (key, t) = LAST_FOUND.get();
        (key == self.key()).then_some(t)
    }

    fn on_shell(&self, t: u32) -> bool {
        !self.shell.buried.get(t as usize).copied().unwrap_or(false)
    }

    /// The least distance from the skin at which a point's way out is the way from its foot
    /// (m): [`RESOLVED`] of the body's height.
    pub fn resolved(&self) -> f64 {
        RESOLVED * self.height
    }

    /// The nearest body point within `reach`, over the whole body. Warm-started from the
    /// last triangle this thread found (queries come in a spatially coherent order: along a
    /// curve, over a patch, vertex after vertex); the answer does not depend on it.
    pub fn nearest(&self, p: DVec3, reach: f64) -> Option<Nearest> {
        self.nearest_from(p, reach, self.last_found())
    }

    /// [`Self::nearest`] for queries that come one next to the other (the samples of a
    /// patch, row after row): searched up from the leaf of the thread's last such search
    /// (see [`Self::nearest_in`]). The same answer.
    pub fn nearest_next(&self, p: DVec3, reach: f64) -> Option<Nearest> {
        self.nearest_in(&self.near, |t| self.on_shell(t), p, reach, self.last_found(), true)
    }

    /// [`Self::nearest`] warm-started from triangle `hint` (the one found for this point at
    /// its last position, say).
    pub fn nearest_from(&self, p: DVec3, reach: f64, hint: Option<u32>) -> Option<Nearest> {
        self.nearest_in(&self.near, |t| self.on_shell(t), p, reach, hint, false)
    }

    /// The nearest point of partition `k`'s triangles within `reach`: searched up from the
    /// leaf where the last search of this partition's tree on this thread found its winner
    /// (detection's point-face test asks vertex after vertex, so that leaf lies next to the
    /// answer), or else warm-started as [`Self::nearest`].
    pub fn nearest_in_partition(&self, k: usize, p: DVec3, reach: f64) -> Option<Nearest> {
        let part = &self.partitions[k];
        self.nearest_in(
            &part.tree,
            |t| part.triangles.binary_search(&t).is_ok(),
            p,
            reach,
            self.last_found(),
            true,
        )
    }

    /// Signed distance of `p` to the body (m, negative inside), exact; `None` when no
    /// triangle lies within `reach` (m).
    pub fn signed_distance(&self, p: DVec3, reach: f64) -> Option<f64> {
        self.nearest(p, reach).map(|n| n.signed(p))
    }

    /// The first body triangle the ray `origin + t dir` meets with `t` in `(t_min, t_max]`:
    /// `(t, triangle)`: the least `t` (the lowest triangle among equals), each triangle
    /// intersected in `f64` ([`NearTree::first_on_ray`]).
    pub fn cast_ray(&self, origin: DVec3, dir: DVec3, t_min: f64, t_max: f64) -> Option<(f64, u32)> {
        let pad = self.slack / dir.length().max(f64::MIN_POSITIVE);
        let range = [t_min - pad, t_max + pad];
        // Most rays meet nothing: a plain walk says so in about half the time of the search
        // for the first hit (0.09 against 0.17 us a garment edge, one core), which then runs
        // only for the rays that meet the body.
        let meets = |_: u32, c: &[DVec3; 3]| ray_triangle(origin, dir, *c, t_min, t_max).is_some();
        if !self.near.any_on_ray(origin, dir, range, meets) {
            return None;
        }
        self.near.first_on_ray(origin, dir, range, pad, |_, c| {
            ray_triangle(origin, dir, *c, t_min, t_max)
        })
    }

    /// Whether an edge of the body passes through the triangle `tri` (its ends strictly on
    /// either side of the triangle's plane, the crossing point in the closed triangle),
    /// decided by exact predicates over the shell triangles whose boxes meet the
    /// triangle's: the body poking through a garment face whose corners and edges are
    /// clear of it.
    pub fn pierces(&self, tri: [DVec3; 3]) -> bool {
        let lo = tri[0].min(tri[1]).min(tri[2]);
        let hi = tri[0].max(tri[1]).max(tri[2]);
        let pad = DVec3::splat(self.slack);
        self.near
            .any_in_box(lo - pad, hi + pad, |_, c| edges_through(c, tri).next().is_some())
    }

    /// Visits every shell triangle whose box meets the box `lo..hi` (and the others of
    /// its leaf), as `visit(triangle, corners)`.
    pub fn visit_box(&self, lo: DVec3, hi: DVec3, mut visit: impl FnMut(u32, &[DVec3; 3])) {
        let pad = DVec3::splat(self.slack);
        self.near.any_in_box(lo - pad, hi + pad, |t, c| {
            visit(t, c);
            false
        });
    }

    /// Whether the segment `a..b` passes through the body surface (its ends strictly on
    /// either side of a triangle it meets), decided by exact predicates: a segment through
    /// an edge or a corner shared by triangles is never let through the crack between
    /// them, as rounded ray-triangle tests can (see [`crate::geom::predicates`]).
    pub fn segment_hits(&self, a: DVec3, b: DVec3) -> bool {
        let pad = self.slack / (b - a).length().max(f64::MIN_POSITIVE);
        self.near
            .any_on_segment(a, b, pad, |_, c| segment_crosses_triangle(a, b, *c))
    }
}

/// The edges of the triangle with corners `c` that pass through the triangle `tri`
/// ([`segment_crosses_triangle`]: the same verdicts, each corner's side of `tri`'s plane
/// decided once), as the local index `k` of each (corner `k` to `k + 1`).
pub fn edges_through(c: &[DVec3; 3], tri: [DVec3; 3]) -> impl Iterator<Item = usize> + '_ {
    let sides = c.map(|p| side(tri[0], tri[1], tri[2], p));
    (0..3).filter(move |&k| {
        let l = (k + 1) % 3;
        strictly_apart(sides[k], sides[l]) && line_through_triangle(c[k], c[l], tri)
    })
}
