//! The outer garment pushed out in front of the inner one, as the body collision pushes a
//! garment off the skin: every outer vertex behind the inner surface, or nearer in front
//! of it than the ease (the fabric's thickness), goes to its nearest inner point plus the
//! ease along that point's pseudo-normal; then, round by round, the ends of an outer edge
//! still through an inner face go out by the depth of its middle behind the inner surface
//! plus the ease, and the corners of an outer face an inner edge still passes through go
//! out along the inner normal there until the face stands the ease in front of the edge,
//! until the certificate is clear or the rounds run out.

use glam::DVec3;
use serde::Serialize;

use super::certificate::{LayerCounts, certify_layers, crossing_edges, gap};
use super::surface::{LayerError, LayerSurface};
use crate::geom::predicates::segment_crosses_triangle;
use crate::mesh::TriMesh;
use crate::mesh::topology::undirected_edges;

/// How the outer garment is pushed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PushOptions {
    /// The gap the outer keeps in front of the inner, m (the fabric's thickness). Default
    /// 0.002.
    pub ease: f64,
    /// Rounds of edge and face pushes after the vertex push. Default 8.
    pub rounds: usize,
}

impl Default for PushOptions {
    fn default() -> Self {
        Self { ease: 0.002, rounds: 8 }
    }
}

/// What a push did.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PushReport {
    /// The certificate before.
    pub before: LayerCounts,
    /// The certificate after.
    pub after: LayerCounts,
    /// Outer vertices moved.
    pub moved: usize,
    /// Edge and face rounds run.
    pub rounds: usize,
}

/// The direction a point of the outer garment is pushed in: the body's outward normal at the
/// skin nearest it (`None`: the inner surface's normal there).
pub type Outward<'a> = &'a dyn Fn(DVec3) -> Option<DVec3>;

/// Pushes `outer`'s positions out in front of `inner` (both oriented away from the body),
/// each move along the inner surface's normal at the nearest point.
///
/// # Failures
/// [`LayerError`] when the outer garment is not a manifold surface.
pub fn push_outside(
    inner: &LayerSurface,
    outer: &mut TriMesh,
    options: &PushOptions,
) -> Result<PushReport, LayerError> {
    push(inner, outer, options, &|_| None)
}

/// As [`push_outside`], each move along `outward` (the body's outward normal at the skin
/// nearest the point): the outer garment goes over the inner along the body normal, and
/// neighbouring vertices move alike where the inner surface is folded (at a crumpled
/// neckline its normals turn by more than 90 degrees from face to face, and moves along
/// them would send the outer's vertices apart and through it).
///
/// # Failures
/// [`LayerError`] when the outer garment is not a manifold surface.
pub fn push_outside_along(
    inner: &LayerSurface,
    outer: &mut TriMesh,
    options: &PushOptions,
    outward: Outward<'_>,
) -> Result<PushReport, LayerError> {
    push(inner, outer, options, outward)
}

/// The unit direction of a move at `p`: `outward`'s, else `normal`.
fn way(outward: Outward<'_>, p: DVec3, normal: DVec3) -> DVec3 {
    outward(p).map_or(normal, |d| d.normalize_or(normal))
}

/// The length of a move along `d` that takes a point `signed` in front of a surface with
/// normal `n` to `ease` in front of it (the cosine between them at least 0.3).
fn along(d: DVec3, n: DVec3, signed: f64, ease: f64) -> f64 {
    (ease - signed).max(0.0) / d.dot(n).max(0.3)
}

fn push(
    inner: &LayerSurface,
    outer: &mut TriMesh,
    options: &PushOptions,
    outward: Outward<'_>,
) -> Result<PushReport, LayerError> {
    let before = certify_layers(inner, &LayerSurface::new(outer, "outer")?);
    let mut moved = vec![false; outer.positions.len()];
    let ease = options.ease;
    put_in_front(inner, outer, &mut moved, (ease, outward));
    let edges = undirected_edges(outer);
    let mut rounds = 0;
    let mut after = certify_layers(inner, &LayerSurface::new(outer, "outer")?);
    while !after.clear() && rounds < options.rounds {
        rounds += 1;
        let mut shifts: Vec<(u32, DVec3)> = Vec::new();
        // An outer edge through an inner face: its middle is behind the inner surface;
        // both ends go out by that depth plus the ease.
        for [a, b] in crossing_edges(&outer.positions, &edges, inner) {
            let mid = (outer.positions[a as usize] + outer.positions[b as usize]) * 0.5;
            if let Some(near) = inner.nearest(mid).filter(|n| !n.on_opening) {
                let d = way(outward, mid, near.normal);
                let need = along(d, near.normal, (mid - near.point).dot(near.normal), ease);
                shifts.extend([a, b].map(|v| (v, d * need)));
            }
        }
        // An inner edge through an outer face: the face's corners go out along the inner
        // normal there until the face's plane stands the ease in front of the edge's end
        // that pokes through.
        for (t, normal, height) in pierced_faces(inner, outer) {
            let face = outer.scaled_normal(t).normalize_or_zero();
            let [a, b, c] = outer.corners(t);
            let d = way(outward, (a + b + c) / 3.0, normal);
            let s = (height + ease) / d.dot(face).max(0.7);
            shifts.extend(outer.triangles[t].map(|v| (v, d * s)));
        }
        // Each vertex moves by the largest shift asked of it (shifts are outward, so the
        // largest along its own direction covers the others nearly).
        shifts.sort_by(|x, y| {
            x.0.cmp(&y.0)
                .then(y.1.length_squared().total_cmp(&x.1.length_squared()))
        });
        shifts.dedup_by_key(|s| s.0);
        for (v, shift) in shifts {
            outer.positions[v as usize] += shift;
            moved[v as usize] = true;
        }
        // A shift along one inner normal can take a vertex behind another part of the
        // inner surface (in a fold): the vertex rule again.
        put_in_front(inner, outer, &mut moved, (ease, outward));
        after = certify_layers(inner, &LayerSurface::new(outer, "outer")?);
    }
    Ok(PushReport {
        before,
        after,
        moved: moved.iter().filter(|&&m| m).count(),
        rounds,
    })
}

/// Every outer vertex behind the inner surface, or nearer in front of it than `ease`, to its
/// nearest inner point plus the ease along that point's pseudo-normal (only ever outward).
/// A vertex whose nearest inner point is on an opening (a hem, a cuff) is beside the inner
/// garment, not behind it, and stays, unless it is nearer than the ease: on the opening
/// itself (two garments sharing a neckline or a hem), it goes out in front of it too.
fn put_in_front(inner: &LayerSurface, outer: &mut TriMesh, moved: &mut [bool], (ease, outward): (f64, Outward<'_>)) {
    let ease_in = ease * (1.0 - 1e-9);
    for (p, m) in outer.positions.iter_mut().zip(moved) {
        // Along a direction that is not the surface's normal, one move may end behind or
        // near another part of the surface (a fold): a few more.
        for _ in 0..4 {
            let Some(near) = inner.nearest(*p) else { break };
            let push = if near.on_opening {
                near.point.distance(*p) < ease_in && near.signed < ease_in
            } else {
                gap(inner, *p).is_some_and(|(behind, signed)| behind || signed < ease_in)
            };
            if !push {
                break;
            }
            let signed = (*p - near.point).dot(near.normal);
            let d = way(outward, *p, near.normal);
            // Behind the surface by the exact side test but in front by the pseudo-normal
            // (nearest to an edge of a fold): at least the ease.
            let step = along(d, near.normal, signed, ease);
            *p += d * if step > 0.0 { step } else { ease };
            *m = true;
        }
    }
}

/// The outer faces an inner edge passes through, each with the inner normal at the middle
/// of such an edge and how far its end in front of the face stands out of the face's plane.
fn pierced_faces(inner: &LayerSurface, outer: &TriMesh) -> Vec<(usize, DVec3, f64)> {
    let mut out = Vec::new();
    for (t, tri) in outer.triangles.iter().enumerate() {
        let c = tri.map(|i| outer.positions[i as usize]);
        let face = outer.scaled_normal(t).normalize_or_zero();
        let lo = c[0].min(c[1]).min(c[2]);
        let hi = c[0].max(c[1]).max(c[2]);
        let mut hit: Option<(DVec3, f64)> = None;
        inner.in_box(lo, hi, |_, corners| {
            for e in 0..3 {
                let (p, q) = (corners[e], corners[(e + 1) % 3]);
                if segment_crosses_triangle(p, q, c) {
                    let height = (p - c[0]).dot(face).max((q - c[0]).dot(face));
                    if hit.is_none_or(|h| height > h.1) {
                        hit = Some(((p + q) * 0.5, height));
                    }
                }
            }
        });
        if let Some((middle, height)) = hit
            && let Some(near) = inner.nearest(middle)
        {
            out.push((t, near.normal, height));
        }
    }
    out
}
