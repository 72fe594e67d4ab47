//! Collision response (\[collide\] 5.2): every penetrating vertex is moved out along a
//! constrained direction until it stands the ease off the body.
//!
//! The direction, by the vertex's partition rule and its place in the garment:
//! 1. no constraint (chest, neck): the vertex normal;
//! 2. given directions: the view direction for boundary vertices at the shoulder (they
//!    must stay on their contour as drawn), the body normal at the hit for the abdomen
//!    (avoids folds), the ray from a ring centre for legs, crotch and hip (global or local
//!    centres by the rule in [`crate::body::slices`]);
//! 3. iso-height: a vertex on a garment ring keeps its place in the ring's plane (the
//!    component along the plane's normal is removed: zero vertical part for a horizontal
//!    ring);
//! 4. self-collision guard (\[collide\] 5.1): where the body has ring centres (legs to
//!    abdomen), the direction must lie within 90 degrees of the direction from the
//!    vertex's local centre through its mapped body point (on the ray from that centre
//!    through the vertex); if not, it becomes that direction.
//!
//! The vertex then travels along the direction to where it leaves the body, and on until
//! its distance to the body is the ease, within [`EASE_TOLERANCE`] of it either way (secant
//! steps on the exact distance, bracketed). Where another part of the body lies within two
//! eases along the direction (the other thigh just below the crotch, an arm against the
//! torso) there is no room for the ease: the vertex stands where it is farthest from both
//! along the ray, and the shortest way out is tried as well, the better one kept. The gap a
//! vertex was sent to is recorded with it ([`Response::gap`]).
//!
//! Two checks keep a rule from doing harm, and are recorded as `fallback` when they act:
//! a direction more than 75 degrees off the vertex's shortest way out of the body (a
//! horizontal ring ray under the crotch, where the skin faces down) is replaced by that
//! way out, and so is a push that would travel more than three times the depth plus the
//! ease (the ray would cross the body to its far side).
//!
//! Edges can still cross the body with both ends outside (\[collide\] figure 14): the edge
//! rounds of [`super::edges`] lift them.

use glam::{DVec2, DVec3};

pub use super::push::EASE_TOLERANCE;
use super::push::{push_out, settle};
use super::types::Hit;
use crate::body::ResponseRule;
use crate::body::index::BodyIndex;
use crate::body::slices::flat;
use crate::par::par_map;

/// Response settings.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ResponseOptions {
    /// The ease a moved vertex stands off the body, as a fraction of the garment's ease.
    /// Default value: 0.5 (the Coons blend between eased rings stands about that far off).
    pub ease_fraction: f64,
    /// Least ease, as a fraction of the body's height (a garment with zero ease still gets
    /// its vertices off the skin). Default value: 0.002.
    pub min_ease: f64,
    /// View direction for shoulder boundary vertices, a unit vector in the world frame.
    /// Default value: `+z` (front view).
    pub view: DVec3,
    /// Most rounds of edge response (see [`super::edges`]): the ends of edges that still
    /// cross the body after the vertex response are lifted out along the way out at the
    /// edge's deepest point; each round checks only the edges at ends moved before, and the
    /// rounds stop when none crosses. Default value: 20.
    pub edge_rounds: usize,
}

impl Default for ResponseOptions {
    fn default() -> Self {
        Self {
            ease_fraction: 0.5,
            min_ease: 0.002,
            view: DVec3::Z,
            edge_rounds: 20,
        }
    }
}

/// Which direction rule moved a vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AppliedRule {
    /// The garment vertex normal.
    VertexNormal,
    /// The view direction (shoulder boundary).
    ViewDirection,
    /// The body normal at the hit (abdomen).
    BodyNormal,
    /// The ray from the ring's global centre.
    GlobalCentre,
    /// The ray from a half ring's local centre.
    LocalCentre,
    /// The self-collision guard replaced the direction.
    Guard,
    /// An end of an edge still crossing the body, lifted along the way out at the edge's
    /// deepest point (edge rounds).
    EdgeLift,
    /// A corner of a face the body pokes through (its corners and edges clear of it),
    /// lifted along the face's outward normal (face rounds, see [`super::faces`]).
    FaceLift,
    /// The rule's direction was more than 75 degrees off the shortest way out, or its push
    /// too long: out along the shortest way instead.
    Fallback,
}

impl AppliedRule {
    /// All rules, in order.
    pub const ALL: [Self; 9] = [
        Self::VertexNormal,
        Self::ViewDirection,
        Self::BodyNormal,
        Self::GlobalCentre,
        Self::LocalCentre,
        Self::Guard,
        Self::EdgeLift,
        Self::FaceLift,
        Self::Fallback,
    ];

    /// Name for logs and metrics.
    pub fn name(self) -> &'static str {
        match self {
            Self::VertexNormal => "vertex_normal",
            Self::ViewDirection => "view_direction",
            Self::BodyNormal => "body_normal",
            Self::GlobalCentre => "global_centre",
            Self::LocalCentre => "local_centre",
            Self::Guard => "guard",
            Self::EdgeLift => "edge_lift",
            Self::FaceLift => "face_lift",
            Self::Fallback => "fallback",
        }
    }
}

/// Where each garment vertex sits in the garment, as the rules need it.
#[derive(Clone, Copy, Debug)]
pub struct VertexRoles<'a> {
    /// Vertex normals.
    pub normals: &'a [DVec3],
    /// On a mesh boundary (an opening).
    pub boundary: &'a [bool],
    /// The plane normal of the garment ring it lies on, if any.
    pub ring_normal: &'a [Option<DVec3>],
    /// Vertices the edge rounds must not move (M0's vertices in M1); empty: none.
    pub pinned: &'a [bool],
}

impl VertexRoles<'_> {
    /// Whether the edge rounds must leave vertex `v` where it is.
    pub fn is_pinned(&self, v: u32) -> bool {
        self.pinned.get(v as usize).copied().unwrap_or(false)
    }
}

/// One moved vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Response {
    /// Garment vertex.
    pub vertex: u32,
    /// Partition index.
    pub partition: usize,
    /// Position before, m (world frame).
    pub from: DVec3,
    /// Position after, m (world frame).
    pub to: DVec3,
    /// Unit direction it moved along.
    pub direction: DVec3,
    /// The rule that gave the direction.
    pub rule: AppliedRule,
    /// The unit direction before the guard (equal to `direction` unless guarded).
    pub proposed: DVec3,
    /// The iso-height constraint removed the component along this ring normal (`None` if
    /// the vertex is on no ring, or a fallback had to leave the ring's plane).
    pub iso: Option<DVec3>,
    /// The centre the rule or the guard read, `(x, z)`.
    pub centre: Option<DVec2>,
    /// Its distance to the body afterwards minus `gap`, m.
    pub ease_error: f64,
    /// The gap it was sent to, m: the ease, or half the free space where another part of
    /// the body lies within two eases along its direction.
    pub gap: f64,
    /// Moved as the end of an edge crossing the body (edge round, from 1), not as a
    /// penetrating vertex (0).
    pub edge_round: usize,
}

/// Least cosine between a response direction and the shortest way out (75 degrees).
pub const MIN_COSINE: f64 = 0.2588;

fn horizontal(v: DVec3) -> DVec3 {
    DVec3::new(v.x, 0.0, v.z)
}

/// The direction for a hit, before the guard: `(direction, rule, centre)`.
fn rule_direction(
    index: &BodyIndex,
    hit: &Hit,
    p: DVec3,
    roles: &VertexRoles<'_>,
    options: &ResponseOptions,
) -> (DVec3, AppliedRule, Option<DVec2>) {
    let v = hit.vertex as usize;
    let n = roles.normals.get(v).copied().unwrap_or(DVec3::ZERO);
    let rule = index
        .partitions
        .get(hit.partition)
        .map_or(ResponseRule::VertexNormal, |p| p.response);
    match rule {
        ResponseRule::VertexNormal => (n, AppliedRule::VertexNormal, None),
        ResponseRule::ViewDirection if roles.boundary.get(v).copied().unwrap_or(false) => {
            let sign = if n.dot(options.view) < 0.0 { -1.0 } else { 1.0 };
            (options.view * sign, AppliedRule::ViewDirection, None)
        }
        ResponseRule::ViewDirection => (n, AppliedRule::VertexNormal, None),
        ResponseRule::BodyNormal => (hit.normal, AppliedRule::BodyNormal, None),
        ResponseRule::RingCentre => {
            let centres = index.slices.at(p.y).and_then(|s| s.centres);
            match centres {
                Some(c) => {
                    let (centre, global) = c.for_point(flat(p));
                    let d = flat(p) - centre;
                    let rule = if global {
                        AppliedRule::GlobalCentre
                    } else {
                        AppliedRule::LocalCentre
                    };
                    (DVec3::new(d.x, 0.0, d.y), rule, Some(centre))
                }
                None => (n, AppliedRule::VertexNormal, None),
            }
        }
    }
}

/// The gap (m) responses stand off at for a garment of ease `garment_ease` (m): half the
/// ease ([`ResponseOptions::ease_fraction`]), at least [`ResponseOptions::min_ease`] of the
/// body's height.
pub fn response_ease(index: &BodyIndex, garment_ease: f64, options: &ResponseOptions) -> f64 {
    (options.ease_fraction * garment_ease).max(options.min_ease * index.height)
}

/// Responds to every hit; returns the moved positions and what happened, by vertex.
pub fn respond(
    index: &BodyIndex,
    positions: &[DVec3],
    hits: &[Hit],
    roles: &VertexRoles<'_>,
    ease: f64,
    options: &ResponseOptions,
) -> (Vec<DVec3>, Vec<Response>) {
    let mut out = positions.to_vec();
    let responses = respond_round(index, &mut out, hits, roles, &|_| ease, 0, options);
    (out, responses)
}

/// A response direction `d` kept in the plane of the vertex's ring (normal `iso`): its part
/// in the plane, or the vertex normal `n`'s where `d` is almost across the plane.
fn in_ring_plane(d: DVec3, n: DVec3, iso: Option<DVec3>) -> DVec3 {
    let Some(pn) = iso else {
        return d;
    };
    let along = d - pn * d.dot(pn);
    if along.length() > 1e-3 * d.length().max(1e-300) {
        along
    } else {
        n - pn * n.dot(pn)
    }
}

/// The self-collision guard where the body has ring centres at `p`'s height: a direction
/// `d` that points (horizontally) towards the local centre is turned away from it. Returns
/// the new direction and the centre, or `None` where `d` stands.
fn guard(index: &BodyIndex, p: DVec3, d: DVec3) -> Option<(DVec3, DVec2)> {
    let c = index.slices.at(p.y).and_then(|s| s.centres)?;
    let local = c.local_of(flat(p));
    let g = flat(p) - local;
    (d != DVec3::ZERO && g.length() > 0.0 && horizontal(d).dot(DVec3::new(g.x, 0.0, g.y)) <= 0.0)
        .then(|| (DVec3::new(g.x, 0.0, g.y).normalize(), local))
}

/// One round of the vertex response: each hit moved along its rule's direction (or the
/// shortest way out) to its target gap `target(hit)`, every vertex reading the positions
/// before the round; `out` takes the moves.
pub(super) fn respond_round(
    index: &BodyIndex,
    out: &mut [DVec3],
    hits: &[Hit],
    roles: &VertexRoles<'_>,
    target: &(dyn Fn(&Hit) -> f64 + Sync),
    edge_round: usize,
    options: &ResponseOptions,
) -> Vec<Response> {
    let positions = out.to_vec();
    let reach = 0.2 * index.height;
    // Each vertex reads the positions before the round and moves alone: in parallel.
    let responses: Vec<Response> = par_map(hits.len(), |k| {
        let hit = &hits[k];
        let ease = target(hit);
        let v = hit.vertex as usize;
        let p = positions[v];
        let n = roles.normals.get(v).copied().unwrap_or(DVec3::ZERO);
        let iso = roles.ring_normal.get(v).copied().flatten();
        // The shortest way out of (or away from) the body, exact.
        let near = index.nearest(p, reach);
        let (way_out, depth) = match near {
            Some(near) => (near.way_out(p, index.resolved()), (-near.signed(p)).max(0.0)),
            None => (hit.normal, hit.depth.max(0.0)),
        };
        let keep_plane = |d: DVec3| match iso {
            Some(pn) => {
                let along = d - pn * d.dot(pn);
                if along.length() > 0.5 * d.length() { along } else { d }
            }
            None => d,
        };
        let (mut d, mut rule, mut centre) = rule_direction(index, hit, p, roles, options);
        d = in_ring_plane(d, n, iso).normalize_or_zero();
        let proposed = d;
        // Self-collision guard where the body has ring centres.
        if let Some((guarded, local)) = guard(index, p, d) {
            d = guarded;
            rule = AppliedRule::Guard;
            centre = Some(local);
        }
        // A direction more than 75 degrees off the way out would drag the vertex through
        // the body (a horizontal ring ray under the crotch): take the way out instead.
        if d.dot(way_out) < MIN_COSINE {
            d = keep_plane(way_out).normalize_or_zero();
            rule = AppliedRule::Fallback;
            centre = None;
        }
        // A push farther than this has gone on through another part of the body (out of one
        // thigh and through the other, where they touch): no way out is taken that far,
        // the rule's nor the shortest.
        let limit = 3.0 * (depth + ease);
        let pushed = push_out(index, p, d, ease).filter(|q| q.to.distance(p) <= limit);
        // Squeezed along the rule's direction (another part of the body in the way): the
        // shortest way out, if it stands further off.
        let pushed = match pushed {
            Some(q) if q.target < (1.0 - EASE_TOLERANCE) * ease && rule != AppliedRule::Fallback => {
                let foot = near.map_or(hit.foot, |n| n.foot);
                match push_out(index, foot + way_out * ease, way_out, ease) {
                    Some(w) if w.target > q.target && w.to.distance(p) <= limit => {
                        rule = AppliedRule::Fallback;
                        Some(w)
                    }
                    _ => Some(q),
                }
            }
            other => other,
        };
        let (pushed, rule) = match pushed {
            Some(q) => (q, rule),
            None => {
                // The shortest way out: from the nearest surface point out along it; where
                // that too leads on through the body, stepping out from the nearest surface
                // ([`settle`]).
                let foot = near.map_or(hit.foot, |n| n.foot);
                let start = foot + way_out * ease;
                let q = push_out(index, start, way_out, ease)
                    .filter(|q| q.to.distance(p) <= limit)
                    .unwrap_or_else(|| settle(index, start, ease));
                (q, AppliedRule::Fallback)
            }
        };
        let (to, ease_error) = (pushed.to, pushed.error);
        let direction = if rule == AppliedRule::Fallback {
            (to - p).normalize_or_zero()
        } else {
            d
        };
        // A fallback may have had to leave the ring's plane.
        let iso = iso.filter(|n| direction.dot(*n).abs() <= 1e-9);
        Response {
            vertex: hit.vertex,
            partition: hit.partition,
            from: p,
            to,
            direction,
            rule,
            proposed,
            iso,
            centre,
            ease_error,
            gap: pushed.target,
            edge_round,
        }
    });
    for r in &responses {
        out[r.vertex as usize] = r.to;
    }
    responses
}
