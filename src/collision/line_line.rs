//! The line-line test (\[collide\] 4.2, figure 9a), for legs and abdomen: in the horizontal
//! section nearest the vertex's height, the vertex's short segment along its normal,
//! `p - w2 n .. p + w1 n` (the normal's horizontal part), is intersected with the body's
//! ring polylines. From a point outside every loop the first crossing either way enters a
//! loop, from a point inside it leaves one; so the nearest crossing's side gives the
//! verdict, and its distance to the crossed edge the depth.
//!
//! The test is cheap (a few runs of 2D edges near the vertex or its line) and approximate: it reads the section at the
//! nearest slice height, not the vertex's own, and it misses points deeper than `w1`
//! along the normal. The error it really makes is measured against the exact test (see
//! the collision benchmark and `--verify`).

use glam::{DVec2, DVec3};

use super::point_face::Reach;
use crate::body::slices::{CHUNK, Loop2, Slice, flat};
use crate::geom::polygon;

/// What the line-line test found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineLine {
    /// Index of the slice read.
    pub slice: usize,
    /// Inside (the nearest crossing leaves a loop).
    pub inside: bool,
    /// Distance from the vertex to the crossed edge's line (in the section), m.
    pub depth: f64,
    /// The crossing point (at the slice's height), m (world frame).
    pub foot: DVec3,
    /// Outward unit normal of the crossed edge (horizontal, world frame).
    pub normal: DVec3,
    /// Distance in the section from the vertex to the nearest loop edge, m (a lower bound on
    /// how far it can move in this slice before the verdict can change).
    pub clearance: f64,
}

fn cross_segment(p: DVec2, d: DVec2, a: DVec2, b: DVec2) -> Option<f64> {
    let e = b - a;
    let den = d.perp_dot(e);
    if den == 0.0 {
        return None;
    }
    let w = a - p;
    let s = w.perp_dot(d) / den;
    (0.0..=1.0).contains(&s).then(|| w.perp_dot(e) / den)
}

/// Squared distance from `p` to the box `[lo, hi]` (zero inside).
fn box_distance2(p: DVec2, [lo, hi]: [DVec2; 2]) -> f64 {
    (lo - p).max(p - hi).max(DVec2::ZERO).length_squared()
}

/// Whether the part `t` in `[t0, t1]` of the line `p + t d` (`d` a unit vector) can meet
/// the box `[lo, hi]`: the part's own box overlaps it and the box's corners do not all lie
/// strictly on one side of the line. Callers widen `[t0, t1]` by far more than rounding,
/// so that no crossing inside the range is ever passed by.
fn line_meets_box(p: DVec2, d: DVec2, [t0, t1]: [f64; 2], [lo, hi]: [DVec2; 2]) -> bool {
    let (a, b) = (p + d * t0, p + d * t1);
    let (from, to) = (a.min(b), a.max(b));
    if from.x > hi.x || to.x < lo.x || from.y > hi.y || to.y < lo.y {
        return false;
    }
    let sides = [lo, hi, DVec2::new(lo.x, hi.y), DVec2::new(hi.x, lo.y)].map(|c| (c - p).perp_dot(d));
    !(sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0))
}

/// The edges of `l`'s run `c`: `(i, a, b)`.
fn run(l: &Loop2, c: usize) -> impl Iterator<Item = (usize, DVec2, DVec2)> + '_ {
    let points = l.points();
    let n = points.len();
    (c * CHUNK..((c + 1) * CHUNK).min(n)).map(move |i| (i, points[i], points[(i + 1) % n]))
}

thread_local! {
    /// The run holding the nearest edge of the last line-line test on this thread: (the
    /// slice's address, loop, run). Only a hint: see [`line_line`].
    static LAST_RUN: std::cell::Cell<(usize, usize, usize)> = const { std::cell::Cell::new((0, 0, 0)) };
}

/// The line-line test of `p` with (3D) normal `normal` in slice `slice` (index `k`).
/// A normal with no horizontal part is replaced by the direction from the ring's global
/// centre, then by `+z`.
///
/// Every edge of every loop counts, but a run of edges is read only where its box could
/// matter: for the clearance when the box lies no farther than the nearest edge so far
/// (first the run nearest the last vertex's, or else the run whose box is nearest), for the crossing when the vertex's line meets
/// the box. The runs are read in loop order, so the answer is the one a scan of every
/// edge gives, bit for bit.
pub fn line_line(slice: &Slice, k: usize, p: DVec3, normal: DVec3, reach: &Reach) -> LineLine {
    let q = flat(p);
    let mut d = flat(normal).normalize_or_zero();
    if d == DVec2::ZERO {
        d = slice
            .centres
            .map_or(DVec2::ZERO, |c| (q - c.global).normalize_or_zero());
    }
    if d == DVec2::ZERO {
        d = DVec2::Y;
    }
    // The clearance so far (squared), first from the run nearest the last vertex tested on
    // this slice by this thread (vertices come in a spatially coherent order), else from
    // the run whose box is nearest. It only prunes: the answer does not depend on it.
    let key = std::ptr::from_ref(slice) as usize;
    let (last_key, last_loop, last_run) = LAST_RUN.get();
    let seed = (last_key == key && last_loop < slice.loops.len() && last_run < slice.loops[last_loop].chunks().len())
        .then_some((last_loop, last_run))
        .or_else(|| {
            slice
                .loops
                .iter()
                .enumerate()
                .flat_map(|(j, l)| {
                    l.chunks()
                        .iter()
                        .enumerate()
                        .map(move |(c, b)| (box_distance2(q, *b), j, c))
                })
                .min_by(|x, y| x.0.total_cmp(&y.0))
                .map(|(_, j, c)| (j, c))
        });
    let mut near2 = f64::INFINITY;
    let mut nearest = seed;
    if let Some((j, c)) = seed {
        for (_, a, b) in run(&slice.loops[j], c) {
            near2 = near2.min(polygon::segment_distance2(q, a, b));
        }
    }
    // The crossings that count lie at `t` in `[-w2, w1]` along the line: boxes are tested
    // against that part of it, widened by a millionth of its length.
    let pad = 1e-6 * (reach.inside + reach.outside);
    let along = [-reach.outside - pad, reach.inside + pad];
    let mut best: Option<(f64, DVec2)> = None;
    for (j, l) in slice.loops.iter().enumerate() {
        if box_distance2(q, l.bounds()) > near2 && !line_meets_box(q, d, along, l.bounds()) {
            continue;
        }
        for (c, &bounds) in l.chunks().iter().enumerate() {
            // The seed run's edges are in `near2` already.
            let near = seed != Some((j, c)) && box_distance2(q, bounds) <= near2;
            let crossing = line_meets_box(q, d, along, bounds);
            if !near && !crossing {
                continue;
            }
            for (i, a, b) in run(l, c) {
                if near {
                    let e2 = polygon::segment_distance2(q, a, b);
                    if e2 < near2 {
                        near2 = e2;
                        nearest = Some((j, c));
                    }
                }
                if crossing
                    && let Some(t) = cross_segment(q, d, a, b)
                    && t >= -reach.outside
                    && t <= reach.inside
                    && best.is_none_or(|(bt, _)| t.abs() < bt.abs())
                {
                    best = Some((t, l.edge_normal(i)));
                }
            }
        }
    }
    if let Some((j, c)) = nearest {
        LAST_RUN.set((key, j, c));
    }
    let clearance = near2.sqrt();
    let at = |v: DVec2| DVec3::new(v.x, slice.y, v.y);
    match best {
        Some((t, n)) => {
            let depth = t.abs() * d.dot(n).abs();
            let inside = t * d.dot(n) > 0.0 && depth > reach.surface;
            LineLine {
                slice: k,
                inside,
                depth: if inside { depth } else { 0.0 },
                foot: at(q + d * t),
                normal: DVec3::new(n.x, 0.0, n.y),
                clearance: if inside { 0.0 } else { clearance },
            }
        }
        None => LineLine {
            slice: k,
            inside: false,
            depth: 0.0,
            foot: at(q),
            normal: DVec3::ZERO,
            // Deeper than the reach: missed, and never skipped later.
            clearance: if slice.loops.iter().any(|l| polygon::contains(l.points(), q)) {
                0.0
            } else {
                clearance
            },
        },
    }
}
