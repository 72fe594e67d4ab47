//! Edge rounds (\[collide\] figure 14: both ends outside, the edge inside): after the vertex
//! response, the ends of every edge that still meets the body are lifted out of it.
//!
//! An edge crossing the body has a part inside; at the middle of that part (parameter `t`
//! along the edge) it is deepest, `depth` behind the surface, whose way out there is `n`.
//! Lifting that point by `lift = depth + ease / 4` takes the ends out by the least-squares
//! split of the lift, `u_a = lift (1 - t) / w` and `u_b = lift t / w` with
//! `w = (1 - t)^2 + t^2` (so that `(1 - t) u_a + t u_b = lift`). Each end moves along `n`
//! where that leads away from the body at the end too (within 75 degrees of the end's own
//! shortest way out), else along its own way out. An end with too little room to rise by its
//! share (another part of the body ahead: it may go no further than the middle of the free
//! space) rises as far as it may and slides the rest along the skin, towards the other end
//! of its edge: out of the squeeze, shortening the edge where it bends round the body (at
//! most half the edge, and half the way to the body ahead). The other end keeps its own
//! share: handing it the pinned end's share as well sends it off the body by many times
//! the lift on a short edge, each round, without clearing the edge. An end shared by several
//! crossing edges takes the longest of its moves. A vertex on a garment ring keeps its height
//! where that leaves most of the move. A move that would leave the end inside the body, or
//! nearer it than the ease (or than it stood, when it stood nearer), is not made. A pinned
//! end ([`VertexRoles::pinned`]: M0's vertices when M1 is collided) does not move; the other
//! end takes the whole lift. Only the edges at moved ends are checked again, for a few
//! rounds.

use std::collections::BTreeMap;

use glam::DVec3;

use super::response::{AppliedRule, EASE_TOLERANCE, MIN_COSINE, Response, ResponseOptions, VertexRoles, respond_round};
use super::reuse::{Reuse, Reused};
use super::types::Hit;
use crate::body::index::BodyIndex;
use crate::par::par_map;

/// Distances measured before the edge rounds: vertex `v`, standing at `at[v]`, was at least
/// `free[v]` (m) from the body surface (zero where not known). An edge both of whose ends
/// still stand there, and whose ends' free balls overlap along it (`free[a] + free[b]` more
/// than its length, by a margin for the ray test's rounding), has no point on the surface:
/// the first edge round does not test it.
#[derive(Clone, Copy, Debug)]
pub struct KnownClearance<'a> {
    /// Where each vertex stood when measured, m.
    pub at: &'a [DVec3],
    /// How far from the surface it stood at least, m.
    pub free: &'a [f64],
}

impl KnownClearance<'_> {
    /// How far vertex `v`, now at `p`, stands at least from the body, if measured there.
    pub fn free_at(&self, v: u32, p: DVec3) -> Option<f64> {
        let v = v as usize;
        (self.at.get(v) == Some(&p)).then(|| self.free.get(v).copied().unwrap_or(0.0))
    }

    /// Whether edge `[a, b]`, now at `ends`, is known to be clear of the surface by more
    /// than `margin` (m).
    fn covers(&self, [a, b]: [u32; 2], ends: [DVec3; 2], margin: f64) -> bool {
        match (self.free_at(a, ends[0]), self.free_at(b, ends[1])) {
            (Some(fa), Some(fb)) => fa + fb > ends[0].distance(ends[1]) + margin,
            _ => false,
        }
    }
}

/// A crossing edge: its ends, where along it it is deepest, the way out there and how deep.
struct Crossing {
    ends: [u32; 2],
    t: f64,
    out: DVec3,
    depth: f64,
}

/// The deepest point inside the body of an edge that passes through the body surface (as
/// [`BodyIndex::segment_hits`] decides): where it goes in and out is found by casting rays
/// along it both ways (the middle of the edge where a ray slips through a crack between
/// triangles that the exact test does not let it through).
fn crossing(index: &BodyIndex, ends: [u32; 2], pa: DVec3, pb: DVec3) -> Option<Crossing> {
    let reach = 0.2 * index.height;
    let t_in = index.cast_ray(pa, pb - pa, 0.0, 1.0).map(|(t, _)| t);
    let t_out = index.cast_ray(pb, pa - pb, 0.0, 1.0).map(|(t, _)| 1.0 - t);
    let (t_in, t_out) = match (t_in, t_out) {
        (Some(a), b) => (a, b.unwrap_or(a)),
        (None, Some(b)) => (b, b),
        (None, None) => (0.5, 0.5),
    };
    let t = 0.5 * (t_in + t_out.max(t_in));
    let mid = pa.lerp(pb, t);
    let near = index.nearest(mid, reach)?;
    let signed = near.signed(mid);
    let out = if signed < 0.0 {
        near.way_out(mid, index.resolved())
    } else {
        near.normal
    };
    Some(Crossing {
        ends,
        t: t.clamp(0.0, 1.0),
        out,
        depth: (-signed).max(0.0),
    })
}

/// Where an end can go: its direction out, how far before the middle of the free space, and
/// its own shortest way out of the body.
#[derive(Clone, Copy)]
struct Way {
    dir: DVec3,
    room: f64,
    own: DVec3,
}

/// The way out for the end at `p` when its edge is lifted along `n`.
fn way(index: &BodyIndex, p: DVec3, n: DVec3, ease: f64) -> Option<Way> {
    let reach = 0.2 * index.height;
    let near = index.nearest(p, reach)?;
    if near.signed(p) < 0.0 {
        // An end inside (a miss of the approximate line-line test) is pushed out as a hit.
        return None;
    }
    let own = near.way_out(p, index.resolved());
    let dir = if n.dot(own) >= MIN_COSINE { n } else { own };
    let behind = near.distance;
    let room = match index.cast_ray(p, dir, 1e-6 * index.height, 4.0 * ease) {
        Some((ahead, _)) => (0.5 * (behind + ahead) - behind).max(0.0),
        None => f64::INFINITY,
    };
    Some(Way { dir, room, own })
}

/// Where an end without room to rise (squeezed between two parts of the body) slides
/// instead: along the surface, towards the other end of its crossing edge, out of the
/// squeeze. At most `want`, half the edge, and half the way to the body ahead.
fn slide(index: &BodyIndex, p: DVec3, way: &Way, towards: DVec3, want: f64, ease: f64) -> DVec3 {
    let to = towards - p;
    let along = to - way.own * to.dot(way.own);
    let Some(dir) = along.try_normalize() else {
        return DVec3::ZERO;
    };
    let most = want.min(0.5 * to.length());
    let most = match index.cast_ray(p, dir, 1e-6 * index.height, most + 2.0 * ease) {
        Some((ahead, _)) => most.min(0.5 * ahead),
        None => most,
    };
    dir * most
}

/// Edge rounds on `positions` (updated): returns the lifts made, as responses, the number
/// of crossing edges each round found, and the edges the first round found (their ends).
/// With `reuse`, the first round skips the edges it knows were clear of the body at the
/// same ends (and remembers this round's verdicts); with `known`, those the measured
/// distances of their ends show clear: the same lifts.
#[allow(clippy::too_many_arguments)]
pub fn respond_edges(
    index: &BodyIndex,
    positions: &mut [DVec3],
    edges: &[[u32; 2]],
    partition: &[usize],
    roles: &VertexRoles<'_>,
    ease: f64,
    options: &ResponseOptions,
    mut reuse: Option<(&mut Reuse, &mut Reused)>,
    known: Option<KnownClearance<'_>>,
) -> (Vec<Response>, Vec<usize>, Vec<[u32; 2]>) {
    let reach = 0.2 * index.height;
    let mut all = Vec::new();
    let mut first = Vec::new();
    let mut found = Vec::new();
    let ends_at = |positions: &[DVec3], e: usize| edges[e].map(|v| positions[v as usize]);
    // Edges to check: all at first (but those known clear at the same ends), then those
    // with an end moved in the round before (the others kept their ends, and none of them
    // crossed).
    let mut check: Vec<usize> = match &mut reuse {
        Some((r, _)) => {
            r.begin_pass(positions, edges);
            (0..edges.len()).filter(|&e| !r.clear_in_round(e, edges[e])).collect()
        }
        None => (0..edges.len()).collect(),
    };
    if let Some(k) = known {
        // A ray test rounds at about 1e-16 of the body's size; a millionth of the body
        // (about 2 um) keeps every edge the rounded test could call crossing. An edge its
        // ends' distances show clear is remembered as clear, as the test would find it: the
        // round gives or keeps a verdict for every edge (see `Reuse::begin_pass`).
        let margin = 1e-6 * index.height;
        check.retain(|&e| {
            let covered = k.covers(edges[e], ends_at(positions, e), margin);
            if covered && let Some((r, _)) = &mut reuse {
                r.set_round(e, true);
            }
            !covered
        });
    }
    if let Some((_, counts)) = &mut reuse {
        counts.round_edges = edges.len() - check.len();
    }
    for round in 1..=options.edge_rounds {
        let positions_now = &*positions;
        // Whether each edge passes through the surface, decided by the quality check's
        // exact test (so that the check takes a first round's verdict at the same ends),
        // and for those that do, how to lift them (boxed: few edges cross).
        type Lift = Box<(Crossing, [Option<Way>; 2])>;
        let tested: Vec<(bool, Option<Lift>)> = par_map(check.len(), |k| {
            let ends = edges[check[k]];
            let [pa, pb] = ends.map(|v| positions_now[v as usize]);
            if !index.segment_hits(pa, pb) {
                return (false, None);
            }
            let lift = crossing(index, ends, pa, pb).map(|c| {
                let ways = [0, 1].map(|k| {
                    (!roles.is_pinned(ends[k]))
                        .then(|| way(index, [pa, pb][k], c.out, ease))
                        .flatten()
                });
                Box::new((c, ways))
            });
            (true, lift)
        });
        if round == 1
            && let Some((r, _)) = &mut reuse
        {
            for (&e, (hit, _)) in check.iter().zip(&tested) {
                r.set_round(e, !hit);
            }
        }
        let crossings: Vec<(Crossing, [Option<Way>; 2])> =
            tested.into_iter().filter_map(|(_, c)| c.map(|c| *c)).collect();
        found.push(crossings.len());
        if round == 1 {
            first = crossings.iter().map(|(c, _)| c.ends).collect();
        }
        if crossings.is_empty() {
            break;
        }
        let mut moves: BTreeMap<u32, DVec3> = BTreeMap::new();
        for (c, ways) in &crossings {
            let lift = c.depth + 0.25 * ease;
            let w = (1.0 - c.t).powi(2) + c.t * c.t;
            let mut share = [lift * (1.0 - c.t) / w, lift * c.t / w];
            // A pinned end leaves the whole lift to the other: `t u_b = lift` (or
            // `(1 - t) u_a`), at most four times the lift.
            let weight = [1.0 - c.t, c.t];
            for k in 0..2 {
                if roles.is_pinned(c.ends[k]) {
                    share[k] = 0.0;
                    share[1 - k] = lift / weight[1 - k].max(0.25);
                }
            }
            let ends = c.ends.map(|v| positions_now[v as usize]);
            for k in 0..2 {
                let Some(way) = ways[k] else {
                    continue;
                };
                // The end rises by its share as far as it has room; what is left it slides.
                let rise = share[k].min(way.room);
                let mut m = way.dir * rise;
                if share[k] > rise {
                    m += slide(index, ends[k], &way, ends[1 - k], share[k] - rise, ease);
                }
                let slot = moves.entry(c.ends[k]).or_insert(DVec3::ZERO);
                if m.length_squared() > slot.length_squared() {
                    *slot = m;
                }
            }
        }
        let moves: Vec<(u32, DVec3)> = moves.into_iter().filter(|(_, m)| *m != DVec3::ZERO).collect();
        // Ends inside the body: pushed out by their partition's rule, as penetrating vertices.
        let mut inside: Vec<u32> = crossings.iter().flat_map(|(c, _)| c.ends).collect();
        inside.retain(|&v| !roles.is_pinned(v));
        inside.sort_unstable();
        inside.dedup();
        let hits: Vec<Hit> = inside
            .into_iter()
            .filter_map(|v| {
                let p = positions_now[v as usize];
                let near = index.nearest(p, reach)?;
                let signed = near.signed(p);
                (signed < 0.0).then(|| Hit {
                    vertex: v,
                    partition: partition.get(v as usize).copied().unwrap_or(0),
                    method: crate::body::DetectionMethod::PointFace,
                    depth: -signed,
                    foot: near.foot,
                    normal: near.normal,
                    triangle: Some(near.triangle),
                })
            })
            .collect();
        let mut pushed_out = positions_now.to_vec();
        let responses = respond_round(index, &mut pushed_out, &hits, roles, &|_| ease, round, options);
        let moved: Vec<Response> = par_map(moves.len(), |k| {
            let (v, m) = moves[k];
            lift(
                index,
                positions_now,
                v,
                m,
                roles,
                partition,
                ease,
                (round, AppliedRule::EdgeLift),
            )
        })
        .into_iter()
        .flatten()
        .collect();
        let moved: Vec<Response> = responses.into_iter().chain(moved).collect();
        for r in &moved {
            positions[r.vertex as usize] = r.to;
        }
        let mut ends = vec![false; positions.len()];
        for r in &moved {
            ends[r.vertex as usize] = true;
        }
        check = (0..edges.len())
            .filter(|&e| edges[e].iter().any(|&v| ends[v as usize]))
            .collect();
        let none_moved = moved.is_empty();
        all.extend(moved);
        if none_moved {
            break;
        }
    }
    (all, found, first)
}

/// Vertex `v` (at `positions[v]`) lifted by `m` as `rule` in round `round`: a vertex on a
/// garment ring keeps its height where that leaves most of the move; `None` when the move
/// would leave it inside the body, or nearer it than the ease (or than it stood, when it
/// stood nearer).
#[allow(clippy::too_many_arguments)]
pub(super) fn lift(
    index: &BodyIndex,
    positions: &[DVec3],
    v: u32,
    m: DVec3,
    roles: &VertexRoles<'_>,
    partition: &[usize],
    ease: f64,
    (round, rule): (usize, AppliedRule),
) -> Option<Response> {
    let reach = 0.2 * index.height;
    let p = positions[v as usize];
    let iso = roles.ring_normal.get(v as usize).copied().flatten();
    let along = iso.map_or(m, |n| m - n * m.dot(n));
    let (m, iso) = if along.length() > 0.5 * m.length() {
        (along, iso)
    } else {
        (m, None)
    };
    let to = p + m;
    let stands = index.signed_distance(to, reach).unwrap_or(reach);
    // Never into the body, nor nearer it than the ease (or than it stood, if nearer).
    let before = index.signed_distance(p, reach).unwrap_or(reach);
    let least = before.min((1.0 - EASE_TOLERANCE) * ease).max(0.0);
    (stands >= least).then(|| Response {
        vertex: v,
        partition: partition.get(v as usize).copied().unwrap_or(0),
        from: p,
        to,
        direction: m.normalize_or_zero(),
        rule,
        proposed: m.normalize_or_zero(),
        iso,
        centre: None,
        // Lifts aim at clearing an edge or a face, not at a gap: where the end stands.
        ease_error: 0.0,
        gap: stands,
        edge_round: round,
    })
}
