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
//! its distance to the body is the ease (a few secant steps on the exact distance).
//!
//! Two checks keep a rule from doing harm, and are recorded as `fallback` when they act:
//! a direction more than 75 degrees off the vertex's shortest way out of the body (a
//! horizontal ring ray under the crotch, where the skin faces down) is replaced by that
//! way out, and so is a push that would travel more than three times the depth plus the
//! ease (the ray would cross the body to its far side).
//!
//! Edges can still cross the body with both ends outside (\[collide\] figure 14). Edge
//! rounds move the ends of such edges out by the depth the edge reaches inside, by the
//! same rules, until none crosses or the rounds run out.

use glam::{DVec2, DVec3};

use super::detect::Hit;
use super::par::par_map;
use crate::body::ResponseRule;
use crate::body::index::BodyIndex;
use crate::body::slices::flat;

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
    /// Rounds of edge response: the ends of edges that still cross the body after the
    /// vertex response are moved out by their own rules, by the depth the edge reaches
    /// inside plus a quarter of the ease (at least to the ease). Default value: 3.
    pub edge_rounds: usize,
}

impl Default for ResponseOptions {
    fn default() -> Self {
        Self {
            ease_fraction: 0.5,
            min_ease: 0.002,
            view: DVec3::Z,
            edge_rounds: 3,
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
    /// The rule's direction was more than 75 degrees off the shortest way out, or its push
    /// too long: out along the shortest way instead.
    Fallback,
}

impl AppliedRule {
    /// All rules, in order.
    pub const ALL: [Self; 7] = [
        Self::VertexNormal,
        Self::ViewDirection,
        Self::BodyNormal,
        Self::GlobalCentre,
        Self::LocalCentre,
        Self::Guard,
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
    /// Its distance to the body afterwards minus the ease it was sent to, m.
    pub ease_error: f64,
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

/// Moves `p` along unit `d` out of the body and on to `ease` off it. Returns the new
/// point and its distance to the body minus the ease; `None` if no ray leaves the body.
fn push_out(index: &BodyIndex, p: DVec3, d: DVec3, ease: f64) -> Option<(DVec3, f64)> {
    let far = 2.0 * index.height;
    let reach = 0.2 * index.height;
    let mut q = p;
    for round in 0..8 {
        // From outside (an edge's end), straight to the secant steps.
        let outside = round == 0 && index.signed_distance(p, reach).is_none_or(|s| s >= 0.0);
        let mut s = if outside {
            // From outside the direction must lead away from the body.
            let near = index.nearest(p, reach)?;
            let away = if near.distance > 0.0 {
                (p - near.foot) / near.distance
            } else {
                near.normal
            };
            if d.dot(away) < 0.2 {
                return None;
            }
            p
        } else {
            let (t, _) = index.cast_ray(q, d, 0.0, far)?;
            q + d * (t + ease)
        };
        let mut inside = false;
        for _ in 0..8 {
            let Some(near) = index.nearest(s, reach) else {
                return Some((s, 0.0));
            };
            let signed = near.signed(s);
            if signed < 0.0 {
                inside = true;
                break;
            }
            let err = ease - signed;
            if err <= 1e-3 * ease {
                return Some((s, signed - ease));
            }
            let slope = if signed > 0.0 {
                d.dot(s - near.foot) / signed
            } else {
                1.0
            };
            s += d * (err / slope.max(0.2));
        }
        if !inside {
            let signed = index.signed_distance(s, reach).unwrap_or(reach);
            return Some((s, signed - ease));
        }
        // The point entered another part of the body (an arm, the other leg): go on.
        q = s;
    }
    None
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

/// Edge rounds: the ends of edges of `positions` that still meet the body are moved out
/// by their rules to a quarter of the ease beyond where they stand (at least the ease).
/// Returns the responses of all rounds and the number of crossing edges each round
/// found; `positions` is updated.
pub fn respond_edges(
    index: &BodyIndex,
    positions: &mut [DVec3],
    edges: &[[u32; 2]],
    partition: &[usize],
    roles: &VertexRoles<'_>,
    ease: f64,
    options: &ResponseOptions,
) -> (Vec<Response>, Vec<usize>) {
    let reach = 0.2 * index.height;
    let mut all = Vec::new();
    let mut found = Vec::new();
    // Edges to check: all at first, then those with an end moved in the round before (the
    // others kept their ends, and none of them crossed).
    let mut check: Vec<usize> = (0..edges.len()).collect();
    for round in 1..=options.edge_rounds {
        // How deep each crossing edge goes: the middle of its part inside the body.
        let mut need: std::collections::BTreeMap<u32, f64> = std::collections::BTreeMap::new();
        let depths = {
            let positions = &*positions;
            let check = &check;
            par_map(check.len(), |k| {
                let [a, b] = edges[check[k]];
                let (pa, pb) = (positions[a as usize], positions[b as usize]);
                let (t_in, _) = index.cast_ray(pa, pb - pa, 0.0, 1.0)?;
                let t_out = index.cast_ray(pb, pa - pb, 0.0, 1.0).map_or(t_in, |(t, _)| 1.0 - t);
                let mid = pa.lerp(pb, 0.5 * (t_in + t_out.max(t_in)));
                Some(index.signed_distance(mid, reach).map_or(0.0, |s| (-s).max(0.0)))
            })
        };
        let mut count = 0;
        for (&e, depth) in check.iter().zip(depths) {
            let [a, b] = edges[e];
            let Some(depth) = depth else {
                continue;
            };
            count += 1;
            for v in [a, b] {
                let e = need.entry(v).or_insert(0.0);
                *e = e.max(depth);
            }
        }
        found.push(count);
        if need.is_empty() {
            break;
        }
        let hits: Vec<Hit> = need
            .keys()
            .filter_map(|&v| {
                let p = positions[v as usize];
                let near = index.nearest(p, reach)?;
                Some(Hit {
                    vertex: v,
                    partition: partition.get(v as usize).copied().unwrap_or(0),
                    method: crate::body::DetectionMethod::PointFace,
                    depth: -near.signed(p),
                    foot: near.foot,
                    normal: near.normal,
                    triangle: Some(near.triangle),
                })
            })
            .collect();
        // Each end goes out by the edge's depth and a quarter of the ease beyond where it
        // stands, at least to the ease.
        let target = |h: &Hit| ease.max(-h.depth + need.get(&h.vertex).copied().unwrap_or(0.0) + 0.25 * ease);
        let moved = respond_round(index, positions, &hits, roles, &target, round, options);
        let ends: std::collections::BTreeSet<u32> = moved.iter().map(|r| r.vertex).collect();
        check = (0..edges.len())
            .filter(|&e| ends.contains(&edges[e][0]) || ends.contains(&edges[e][1]))
            .collect();
        all.extend(moved);
    }
    (all, found)
}

fn respond_round(
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
            Some(near) if near.distance > 0.0 => {
                let s = near.signed(p);
                ((p - near.foot) * s.signum() / near.distance, (-s).max(0.0))
            }
            Some(near) => (near.normal, 0.0),
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
        if let Some(pn) = iso {
            let along = d - pn * d.dot(pn);
            d = if along.length() > 1e-3 * d.length().max(1e-300) {
                along
            } else {
                n - pn * n.dot(pn)
            };
        }
        d = d.normalize_or_zero();
        let proposed = d;
        // Self-collision guard where the body has ring centres.
        if let Some(c) = index.slices.at(p.y).and_then(|s| s.centres) {
            let local = c.local_of(flat(p));
            let g = flat(p) - local;
            if d != DVec3::ZERO && g.length() > 0.0 && horizontal(d).dot(DVec3::new(g.x, 0.0, g.y)) <= 0.0 {
                d = DVec3::new(g.x, 0.0, g.y).normalize();
                rule = AppliedRule::Guard;
                centre = Some(local);
            }
        }
        // A direction more than 75 degrees off the way out would drag the vertex through
        // the body (a horizontal ring ray under the crotch): take the way out instead.
        if d.dot(way_out) < MIN_COSINE {
            d = keep_plane(way_out).normalize_or_zero();
            rule = AppliedRule::Fallback;
            centre = None;
        }
        let limit = 3.0 * (depth + ease);
        let pushed = push_out(index, p, d, ease).filter(|(q, _)| q.distance(p) <= limit);
        let (to, ease_error, rule) = match pushed {
            Some((q, e)) => (q, e, rule),
            None => {
                let foot = near.map_or(hit.foot, |n| n.foot);
                let q = foot + way_out * ease;
                let e = index.signed_distance(q, reach).unwrap_or(0.0) - ease;
                (q, e, AppliedRule::Fallback)
            }
        };
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
            edge_round,
        }
    });
    for r in &responses {
        out[r.vertex as usize] = r.to;
    }
    responses
}
