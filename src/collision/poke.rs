//! One pierced face taken off the body (the face rounds of [`super::faces`] call it): the
//! deepest point of the body above the face ([`poke`]), with the face's outer side taken
//! from the body's way out where its surface crosses the face, and the slide that moves a
//! face lying across a ridge along its plane instead.

use std::collections::BTreeSet;

use glam::DVec3;

use crate::body::index::{BodyIndex, edges_through};

/// Most body vertices a cap is grown to (a cap is a bump a few millimetres high: a few
/// vertices; the bound only stops a pathological case).
const MOST_CAP: usize = 4096;

/// The longest edge of `tri`, m.
pub(super) fn longest_edge(tri: [DVec3; 3]) -> f64 {
    (0..3).map(|k| tri[k].distance(tri[(k + 1) % 3])).fold(0.0, f64::max)
}

/// The deepest point of the body above a pierced face: the face's outer normal, the point's
/// barycentric coordinates on the face and its height above the face's plane, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Poke {
    /// Unit normal of the face, on the side away from the body.
    pub out: DVec3,
    /// Barycentric coordinates of the deepest point's foot on the face.
    pub at: [f64; 3],
    /// Its height above the face's plane, m.
    pub height: f64,
    /// The body's way out where it crosses the face (unit; zero where unknown): a face
    /// pierced from one side in one round and from the other in the next is squeezed
    /// between two parts of the body, and is slid along their ways out summed.
    pub way_out: DVec3,
}

/// Barycentric coordinates of `p`'s foot on the plane of `tri` (normal `n`, unnormalised).
fn barycentric(tri: [DVec3; 3], n: DVec3, p: DVec3) -> [f64; 3] {
    let area = n.length_squared();
    let w = |a: DVec3, b: DVec3| (b - a).cross(p - a).dot(n) / area;
    [w(tri[1], tri[2]), w(tri[2], tri[0]), w(tri[0], tri[1])]
}

/// The deepest point of the body above face `tri`, if the body pokes through it (`None`
/// for a face it does not, or a degenerate one).
pub fn poke(index: &BodyIndex, tri: [DVec3; 3], before: DVec3) -> Option<Poke> {
    let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    let unit = n.try_normalize()?;
    // Where the body's surface crosses the face (the body edges' crossing points), the
    // body's outward normal there (its triangles' normals, summed by area) and the edges.
    let (lo, hi) = (tri[0].min(tri[1]).min(tri[2]), tri[0].max(tri[1]).max(tri[2]));
    let mut crossings: Vec<DVec3> = Vec::new();
    let mut through: Vec<[u32; 2]> = Vec::new();
    let mut way_out = DVec3::ZERO;
    index.visit_box(lo, hi, |t, c| {
        let ids = index.triangles[t as usize];
        for k in edges_through(c, tri) {
            let (a, b) = (c[k], c[(k + 1) % 3]);
            let (ha, hb) = ((a - tri[0]).dot(unit), (b - tri[0]).dot(unit));
            crossings.push(a + (b - a) * (ha / (ha - hb)));
            through.push([ids[k], ids[(k + 1) % 3]]);
            way_out += index.face_normals[t as usize] * (c[1] - c[0]).cross(c[2] - c[0]).length();
        }
    });
    // The outer side: the side the body pokes out to, where its way out at the crossings
    // says so clearly (a bump pokes through the face towards the face's outside; a thigh
    // pressed against the face from its outside pokes through it inwards, and the face
    // goes to the side the body leaves thin); else where the corners' ways out point.
    let across = way_out.normalize_or_zero().dot(unit);
    let way: f64 = if across.abs() >= 0.25 {
        across
    } else {
        let reach = 0.2 * index.height;
        tri.iter()
            .filter_map(|&p| index.nearest(p, reach))
            .map(|near| near.normal.dot(unit))
            .sum()
    };
    let out = if way < 0.0 { -unit } else { unit };
    let height = |v: u32| (index.positions[v as usize] - tri[0]).dot(out);
    // The cap's first corners: the outer ends of the body edges through the face.
    let mut stack: Vec<u32> = through.iter().flatten().copied().filter(|&v| height(v) > 0.0).collect();
    // The rest of the cap: the body vertices over the face (above its plane, their foot in
    // it) joined to those by body edges over it (a part of the body over the plane but not
    // through the face, an arm beside the torso, is not reached).
    let over = |v: u32| {
        let p = index.positions[v as usize];
        height(v) > 0.0 && barycentric(tri, n, p).iter().all(|&b| b >= 0.0)
    };
    let mut cap: BTreeSet<u32> = BTreeSet::new();
    while let Some(v) = stack.pop() {
        if cap.len() >= MOST_CAP || !cap.insert(v) {
            continue;
        }
        let p = index.positions[v as usize];
        index.visit_box(p, p, |t, _| {
            let ids = index.triangles[t as usize];
            if ids.contains(&v) {
                stack.extend(ids.into_iter().filter(|&w| !cap.contains(&w) && over(w)));
            }
        });
    }
    let deepest = cap
        .into_iter()
        .max_by(|&a, &b| height(a).total_cmp(&height(b)).then(b.cmp(&a)))?;
    let (p, height) = (index.positions[deepest as usize], height(deepest));
    // A cap higher than the face is wide is no bump: the face lies across a part of the
    // body (a ridge between the thighs, say), and lifting it off its plane would fling it.
    // It is slid off the body instead, along the body's way out where it crosses the face.
    // Squeezed between two parts of the body (pierced from the other side before): slid
    // along both ways out summed, out of the slot between them.
    let own = way_out.normalize_or_zero();
    let squeezed = before.dot(own) < 0.0;
    let slid =
        slide(tri, unit, &crossings, if squeezed { before + own } else { own }).map(|p| Poke { way_out: own, ..p });
    if squeezed && slid.is_some() {
        return slid;
    }
    if height > longest_edge(tri) {
        return slid;
    }
    // Its foot on the face (clamped into it where the cap leans past an edge).
    let at = barycentric(tri, n, p).map(|b| b.max(0.0));
    let sum: f64 = at.iter().sum();
    let at = if sum > 0.0 { at.map(|b| b / sum) } else { [1.0 / 3.0; 3] };
    let lifted = Poke {
        out,
        at,
        height,
        way_out: own,
    };
    // Of the lift and the slide, the shorter move (a face across the crotch's ridge
    // slides down off it rather than into the thigh beside it).
    Some(match slid {
        Some(s) if s.height < height => s,
        _ => lifted,
    })
}

/// The slide of face `tri` (unit normal `unit`) off a part of the body that lies across it:
/// the face moved whole along the body's way out `way_out` where its surface crosses the
/// face (at `crossings`), as far as takes every crossing out of the face across its edges
/// (the longest of their ways out of it along the move's part in the face's plane). `None`
/// where the body's way out is mostly across the face (a slide would not take the body out
/// of it) or unknown.
fn slide(tri: [DVec3; 3], unit: DVec3, crossings: &[DVec3], way_out: DVec3) -> Option<Poke> {
    let out = way_out.try_normalize()?;
    let along = out - unit * out.dot(unit);
    let reach = along.length();
    if reach < 0.5 {
        return None;
    }
    // The face's edges seen from a crossing moving against `along`, in the face's plane.
    let back = -along / reach;
    let exit = |x: DVec3| {
        (0..3)
            .filter_map(|k| {
                let (p, q) = (tri[k], tri[(k + 1) % 3]);
                // x + s back = p + r (q - p): solved in the plane, by the cross products
                // against the face's normal.
                let e = q - p;
                let den = back.cross(e).dot(unit);
                if den.abs() <= f64::EPSILON * e.length() {
                    return None;
                }
                let s = (p - x).cross(e).dot(unit) / den;
                let r = (p - x).cross(back).dot(unit) / den;
                (s >= 0.0 && (-1e-9..=1.0 + 1e-9).contains(&r)).then_some(s)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let far = crossings
        .iter()
        .map(|&x| exit(x))
        .filter(|s| s.is_finite())
        .fold(0.0, f64::max);
    (far > 0.0).then(|| Poke {
        out,
        at: [1.0 / 3.0; 3],
        height: (far / reach).min(longest_edge(tri)),
        way_out: out,
    })
}
