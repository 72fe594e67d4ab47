//! Faces the body pokes through: a garment triangle whose three corners and three edges are
//! clear of the body can still be pierced inside, where a convex bit of body (a bust apex, a
//! kneecap) rises above the triangle's flat chord by about `c^2 / (8 R)` for a chord `c`
//! over a radius `R`. The check finds them exactly; the face rounds lift them off.
//!
//! **The check.** A face is pierced when an edge of the body passes through it
//! ([`BodyIndex::pierces`]: the body edge's ends strictly on either side of the face's plane,
//! the crossing point in the closed face, by exact predicates over the body triangles whose
//! boxes meet the face's). With the corners' distances to the body known, a face whose
//! corners' free balls cover it has no body point on it and needs no test: every point of a
//! triangle lies within `L / sqrt(3)` of one of its corners (`L` its longest edge; the bound
//! is met by the equilateral triangle's centre), so a face whose least corner distance passes
//! that, by a margin for the distances' rounding, is clear.
//!
//! **The face rounds.** The face's outer side is the side the body leaves through it: the
//! body's way out where its surface crosses the face (the crossing body triangles' normals,
//! summed by area) where that points clearly to one side (a bump pokes out through the
//! face's outside; a thigh pressed against the face from outside pokes through it inwards,
//! and the face must go the other way), else the side its corners' ways out of the body
//! point to. The body above a pierced face, on its outer side, is a cap whose deepest
//! point is a body vertex: the body surface is flat between its vertices, so the height
//! above the face's plane
//! is greatest at a corner of the cap, and the cap's corners off the plane are body
//! vertices. The cap is grown from the outer ends of the body edges through the face along
//! the body's edges, over the vertices above the face (over its plane, their foot in the
//! face; so that a part of the body over the plane that does not pass through the face, an
//! arm beside the torso, is not taken); its deepest vertex is the target. A cap higher than
//! the face's longest edge is no bump but a part of the body the face lies across (a
//! ridge between the thighs): that face is not lifted off its plane but slid along it
//! (below). With `b` that point's barycentric coordinates on the face (clamped into it) and
//! `h` its height, the face is lifted there by `lift = h + ease`: its corners move along the face's outer normal by the least-squares
//! split `u_i = lift b_i / sum_j b_j^2` (so that `sum_i b_i u_i = lift`), over the corners
//! that may move (pinned ones stay: M0's vertices in M1), at most twice the lift. A
//! corner shared by several pierced faces takes the longest of its moves, and a move that
//! would leave it inside the body or nearer it than the ease is not made (as the edge
//! rounds do, [`super::edges`]). Only the faces at moved corners are checked again, for a
//! few rounds; where three rounds in a row leave more faces pierced than the best round
//! before them (lifts that push faces into other parts of the body), the rounds stop and
//! the positions of that best round are taken back.
//!
//! **The slide.** Where the body's way out at the crossings lies mostly in the face's plane
//! (a ridge under the crotch crossing a face of the crotch web), the face is moved whole
//! along it, as far as takes every crossing point out of the face across its edges (the
//! longest of their ways out of the triangle, along the move's part in its plane), plus the
//! ease; the shorter of the lift and the slide is made. A face pierced from one side in one
//! round and from the other in the next is squeezed in a slot between two parts of the body
//! (the thighs pressed together): lifting it off either wall pushes it into the other, so
//! it is slid along the two walls' ways out summed, out of the slot where it opens.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use super::edges::{KnownClearance, lift, respond_edges};
use super::poke::{Poke, longest_edge, poke};
use super::response::{AppliedRule, Response, ResponseOptions, VertexRoles};
use super::reuse::Reuse;
use crate::body::index::BodyIndex;
use crate::geom::closest::triangles_distance;
use crate::par::par_map;

/// `1 / sqrt(3)`: every point of a triangle lies within this many times its longest edge
/// of one of its corners.
const COVER: f64 = 0.577_350_269_189_625_8;

/// A lower bound of the distance from the body to any point of face `tri` whose corners
/// stand at least `free` from it: the least of them less `L / sqrt(3)` (see the module's
/// text); positive only where the corners' free balls cover the face.
fn least_distance(tri: [DVec3; 3], free: [f64; 3]) -> f64 {
    free.into_iter().fold(f64::INFINITY, f64::min) - COVER * longest_edge(tri)
}

/// How far each corner's distance to the body may be off by rounding: a millionth of the
/// body's height, as for the edges' balls ([`super::edges::KnownClearance`]).
fn margin(index: &BodyIndex) -> f64 {
    1e-6 * index.height
}

/// Whether face `tri` is pierced by the body, exactly; `free` are its corners' distances to
/// the body where known (zero where not).
fn pierced(index: &BodyIndex, tri: [DVec3; 3], free: [f64; 3]) -> bool {
    least_distance(tri, free) <= margin(index) && index.pierces(tri)
}

/// The faces of `triangles` (at `positions`) the body pokes through, ascending; `free[v]` is
/// how far vertex `v` stood at least from the body (zero where not known). With `reuse`, a
/// face tested by an earlier pass since which none of its corners moved keeps that pass's
/// verdict, and every face gets this check's (call [`Reuse::begin_pass`] first).
pub fn pierced_faces(
    index: &BodyIndex,
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    free: &[f64],
    mut reuse: Option<&mut Reuse>,
) -> Vec<u32> {
    let known: Vec<Option<bool>> = match &mut reuse {
        Some(r) => {
            r.begin_faces(triangles);
            (0..triangles.len()).map(|f| r.face(f, triangles[f])).collect()
        }
        None => vec![None; triangles.len()],
    };
    let corners = |f: usize| triangles[f].map(|v| positions[v as usize]);
    let balls = |f: usize| triangles[f].map(|v| free.get(v as usize).copied().unwrap_or(0.0));
    let hits = par_map(triangles.len(), |f| {
        known[f].unwrap_or_else(|| pierced(index, corners(f), balls(f)))
    });
    if let Some(r) = reuse {
        for (f, &hit) in hits.iter().enumerate() {
            r.set_face(f, hit);
        }
    }
    (0..triangles.len() as u32).filter(|&f| hits[f as usize]).collect()
}

/// The least distance from face `tri` to the body when it is less than `cap` (m), else
/// `cap`: over the body triangles within `cap` of the face's box, each measured exactly
/// ([`triangles_distance`]; 0 for a face the body pierces).
pub fn face_distance(index: &BodyIndex, tri: [DVec3; 3], cap: f64) -> f64 {
    let reach = DVec3::splat(cap);
    let (lo, hi) = (tri[0].min(tri[1]).min(tri[2]), tri[0].max(tri[1]).max(tri[2]));
    let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize_or_zero();
    let mut best = cap;
    index.visit_box(lo - reach, hi + reach, |_, c| {
        // Two quick bounds first: the gap between the boxes, and the body triangle's
        // distance from the face's plane when it lies on one side of it.
        let gap = (lo - c[0].max(c[1]).max(c[2]))
            .max(c[0].min(c[1]).min(c[2]) - hi)
            .max(DVec3::ZERO)
            .length();
        let heights = c.map(|p| (p - tri[0]).dot(normal));
        let (below, above) = (
            heights.iter().fold(f64::INFINITY, |a, &h| a.min(h)),
            heights.iter().fold(f64::NEG_INFINITY, |a, &h| a.max(h)),
        );
        let off_plane = if below > 0.0 {
            below
        } else if above < 0.0 {
            -above
        } else {
            0.0
        };
        if gap.max(off_plane) < best {
            best = best.min(triangles_distance(tri, *c));
        }
    });
    best
}

/// The faces of `triangles` (at `positions`) nearer the body than `cap` (m), with their least
/// distance to it, ascending by face: every point of a face counted, not only its corners.
/// `free[v]` is how far vertex `v` stands at least from the body, and bounds a face from
/// below by the least of its corners less `L / sqrt(3)` (see the module's text): only the
/// faces that bound lets below `cap` are measured. The `pierced` faces are at 0. With
/// `reuse`, a face measured with the same cap by an earlier pass since which none of its
/// corners moved keeps that distance, and every face measured is remembered.
pub fn faces_nearer(
    index: &BodyIndex,
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    (free, pierced): (&[f64], &[u32]),
    cap: f64,
    mut reuse: Option<&mut Reuse>,
) -> Vec<(u32, f64)> {
    let corners = |f: usize| triangles[f].map(|v| positions[v as usize]);
    let balls = |f: usize| triangles[f].map(|v| free.get(v as usize).copied().unwrap_or(0.0));
    let candidates: Vec<u32> = (0..triangles.len())
        .filter(|&f| least_distance(corners(f), balls(f)) < cap)
        .map(|f| f as u32)
        .collect();
    let known: Vec<Option<f64>> = candidates
        .iter()
        .map(|&f| {
            let r = reuse.as_ref()?;
            r.face_distance(f as usize, triangles[f as usize], cap)
        })
        .collect();
    let found = par_map(candidates.len(), |k| {
        let f = candidates[k];
        if pierced.binary_search(&f).is_ok() {
            0.0
        } else {
            known[k].unwrap_or_else(|| face_distance(index, corners(f as usize), cap))
        }
    });
    if let Some(r) = &mut reuse {
        for (&f, &d) in candidates.iter().zip(&found) {
            r.set_face_distance(triangles.len(), f as usize, cap, d);
        }
    }
    candidates.into_iter().zip(found).filter(|&(_, d)| d < cap).collect()
}

/// What the face rounds did: the moves made, as responses, the number of pierced faces each
/// round found, and the faces the first round found pierced.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FaceRounds {
    /// The moves, as responses: the face lifts (rule [`AppliedRule::FaceLift`]), then the
    /// edge rounds' lifts at the corners they moved.
    pub lifts: Vec<Response>,
    /// Pierced faces at the start of each round (those the round tested that are, and those
    /// found before whose corners have not moved since).
    pub found: Vec<usize>,
    /// The faces the first round found pierced, ascending (the others it tested are clear).
    pub first: Vec<u32>,
}

/// Face rounds on `positions` (updated): the faces of `check` the body pokes through are
/// lifted off it, then the faces at the corners moved are checked again, for at most
/// [`ResponseOptions::edge_rounds`] rounds; then the edges of `edges` at the lifted corners
/// go through edge rounds of their own ([`respond_edges`]). With `known`, a face whose
/// corners still stand where their distances were measured, and whose corners' free balls
/// cover it, is not tested (it is clear).
#[allow(clippy::too_many_arguments)]
pub fn respond_faces(
    index: &BodyIndex,
    positions: &mut [DVec3],
    (triangles, edges): (&[[u32; 3]], &[[u32; 2]]),
    mut check: Vec<u32>,
    partition: &[usize],
    roles: &VertexRoles<'_>,
    ease: f64,
    options: &ResponseOptions,
    known: Option<KnownClearance<'_>>,
) -> FaceRounds {
    let mut out = FaceRounds::default();
    // The faces pierced now (those tested last), and the best state so far: the fewest
    // pierced, the positions then and how many lifts had been made. Rounds that do not
    // better it three times over stop, and the best state is taken back.
    let mut standing: BTreeSet<u32> = BTreeSet::new();
    let mut best: Option<(usize, Vec<DVec3>, usize)> = None;
    let mut worse = 0;
    // The side the body last pierced each face from (its way out there).
    let mut sides: BTreeMap<u32, DVec3> = BTreeMap::new();
    for round in 1..=options.edge_rounds {
        let now = &*positions;
        let corners = |f: u32| triangles[f as usize].map(|v| now[v as usize]);
        let free = |f: u32| {
            let tri = triangles[f as usize];
            let free = known.map(|k| [0, 1, 2].map(|c| k.free_at(tri[c], now[tri[c] as usize])));
            free.map_or([0.0; 3], |f| f.map(|d| d.unwrap_or(0.0)))
        };
        // Whether each face is pierced, and for those that are, where to lift them (boxed:
        // few faces are pierced, and a list of unboxed answers for every face tested would
        // take a dozen times the memory, in new pages each round).
        let tested: Vec<Option<Box<Option<Poke>>>> = par_map(check.len(), |k| {
            let tri = corners(check[k]);
            pierced(index, tri, free(check[k]))
                .then(|| Box::new(poke(index, tri, sides.get(&check[k]).copied().unwrap_or_default())))
        });
        let hit: Vec<u32> = check
            .iter()
            .zip(&tested)
            .filter(|(_, t)| t.is_some())
            .map(|(&f, _)| f)
            .collect();
        for f in &check {
            standing.remove(f);
        }
        standing.extend(&hit);
        out.found.push(standing.len());
        if round == 1 {
            out.first = hit;
        }
        if best.as_ref().is_none_or(|b| standing.len() < b.0) {
            best = Some((standing.len(), positions.to_vec(), out.lifts.len()));
            worse = 0;
        } else {
            worse += 1;
            if worse >= 3 {
                break;
            }
        }
        let pierced: Vec<(u32, Poke)> = check
            .iter()
            .zip(tested)
            .filter_map(|(&f, p)| Some((f, (*p?)?)))
            .collect();
        sides.extend(pierced.iter().map(|(f, p)| (*f, p.way_out)));
        if pierced.is_empty() {
            break;
        }
        let mut moves: BTreeMap<u32, DVec3> = BTreeMap::new();
        for (f, poke) in &pierced {
            let tri = triangles[*f as usize];
            let lift = poke.height + ease;
            let free: Vec<usize> = (0..3).filter(|&k| !roles.is_pinned(tri[k])).collect();
            let weight: f64 = free.iter().map(|&k| poke.at[k] * poke.at[k]).sum();
            for &k in &free {
                let share = if weight > 0.0 {
                    (lift * poke.at[k] / weight).min(2.0 * lift)
                } else {
                    lift
                };
                let m = poke.out * share;
                let slot = moves.entry(tri[k]).or_insert(DVec3::ZERO);
                if m.length_squared() > slot.length_squared() {
                    *slot = m;
                }
            }
        }
        let moves: Vec<(u32, DVec3)> = moves.into_iter().filter(|(_, m)| *m != DVec3::ZERO).collect();
        let moved: Vec<Response> = par_map(moves.len(), |k| {
            let (v, m) = moves[k];
            lift(index, now, v, m, roles, partition, ease, (round, AppliedRule::FaceLift))
        })
        .into_iter()
        .flatten()
        .collect();
        if moved.is_empty() {
            break;
        }
        let mut at_moved = vec![false; positions.len()];
        for r in &moved {
            positions[r.vertex as usize] = r.to;
            at_moved[r.vertex as usize] = true;
        }
        check = (0..triangles.len() as u32)
            .filter(|&f| triangles[f as usize].iter().any(|&v| at_moved[v as usize]))
            .collect();
        out.lifts.extend(moved);
    }
    if let Some((count, at, made)) = best
        && standing.len() > count
    {
        positions.copy_from_slice(&at);
        out.lifts.truncate(made);
    }
    if !out.lifts.is_empty() {
        let mut lifted = vec![false; positions.len()];
        for r in &out.lifts {
            lifted[r.vertex as usize] = true;
        }
        let touched: Vec<[u32; 2]> = edges
            .iter()
            .copied()
            .filter(|e| e.iter().any(|&v| lifted[v as usize]))
            .collect();
        let (more, _, _) = respond_edges(index, positions, &touched, partition, roles, ease, options, None, None);
        out.lifts.extend(more);
    }
    out
}
