//! The outer shell of a body whose parts pass into each other: heavy thighs meeting below
//! the crotch, a belly fold, an arm pressed to the side. Body meshes made by morphing a
//! template often cross themselves there; the surface then bounds the union of the parts
//! (the winding number is 2 where two parts overlap), and the triangles of one part that lie
//! inside another are **buried**: they are not skin, and their outward normals point into
//! the body. The nearest-point sign (pseudo-normals, Bærentzen and Aanæs 2005) is exact
//! only on a surface that does not cross itself; near a buried triangle it calls points
//! deep inside the pelvis "outside". The body index therefore answers nearest-point and ray
//! queries over the shell alone: every triangle that is not buried.
//!
//! Method. Every mesh edge is tested against the triangles that do not share a vertex
//! with it and whose bounding boxes meet its own triangle's (the pairs a BVH's self-test
//! gives: a dozen or so a triangle, instead of a ray cast through the tree per edge); an
//! edge that meets one marks that triangle and the edge's two triangles as **crossing**. Without crossings the surface bounds one volume and nothing is buried.
//! Otherwise the surface, cut along the crossing triangles, falls into connected pieces
//! that are each wholly buried or wholly outer (burial changes only where the surface
//! crosses itself). One winding number per piece, at a point just off the outer side of
//! its first triangle, says which: at least one, the outer side lies inside another part
//! and the piece is buried. Each crossing triangle is classified the same way on its own,
//! at its centroid. The winding number is counted along rays (signed crossings), which
//! needs no normals and so holds on a surface that crosses itself.

use std::collections::VecDeque;

use glam::DVec3;

use crate::geom::ray::ray_triangle;
use crate::mesh::TriMesh;
use crate::mesh::topology::NO_NEIGHBOUR;
use crate::par::par_map;

/// Which triangles of a body are buried, and how many cross another part.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Shell {
    /// Per triangle: it lies inside another part of the body.
    pub buried: Vec<bool>,
    /// Per triangle: the surface crosses itself there.
    pub crossing_at: Vec<bool>,
    /// Number of such triangles.
    pub crossing: usize,
}

/// Finds the buried triangles of `mesh` (closed, outward-oriented; `neighbours[t][k]` the
/// triangle across edge `k`, [`NO_NEIGHBOUR`] at a border). `overlapping` lists the pairs
/// of triangles whose bounding boxes meet (each pair once, in either order; a self-test of
/// a BVH over every triangle gives them): an edge can only pass through a triangle whose
/// box meets the box of the edge's own triangle. `winding(p)` is the winding number of
/// the whole surface about `p` (the index's, over every triangle); `height` (m) scales the
/// offsets.
pub fn find_shell(
    mesh: &TriMesh,
    neighbours: &[[u32; 3]],
    height: f64,
    overlapping: &[(u32, u32)],
    winding: impl Fn(DVec3) -> i32 + Sync,
) -> Shell {
    let n = mesh.triangles.len();
    let eps = 1e-9;
    let mut partners: Vec<Vec<u32>> = vec![Vec::new(); n];
    for &(a, b) in overlapping {
        if (a as usize) < n && (b as usize) < n {
            partners[a as usize].push(b);
            partners[b as usize].push(a);
        }
    }
    // Per triangle, for each of its edges it owns (from its low to its high vertex): the
    // triangles the edge passes through (strictly between its ends) that share no vertex
    // with it.
    let pierced: Vec<Vec<(usize, u32)>> = par_map(n, |t| {
        let tri = mesh.triangles[t];
        let mut out = Vec::new();
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if a > b {
                continue;
            }
            let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
            for &h in &partners[t] {
                let corners = mesh.triangles[h as usize];
                if !corners.contains(&a)
                    && !corners.contains(&b)
                    && ray_triangle(pa, pb - pa, mesh.corners(h as usize), eps, 1.0 - eps).is_some()
                {
                    out.push((k, h));
                }
            }
        }
        out
    });
    let mut crossing = vec![false; n];
    for (t, hits) in pierced.iter().enumerate() {
        for &(k, hit) in hits {
            crossing[hit as usize] = true;
            crossing[t] = true;
            if let Some(&other) = neighbours.get(t).map(|nb| &nb[k])
                && other != NO_NEIGHBOUR
            {
                crossing[other as usize] = true;
            }
        }
    }
    let count = crossing.iter().filter(|c| **c).count();
    if count == 0 {
        return Shell {
            buried: vec![false; n],
            crossing_at: crossing,
            crossing: 0,
        };
    }
    let off = 1e-7 * height.max(f64::MIN_POSITIVE);
    let outside_inside = |t: usize| {
        let c = mesh.triangles[t].map(|i| mesh.positions[i as usize]);
        let centroid = (c[0] + c[1] + c[2]) / 3.0;
        let normal = (c[1] - c[0]).cross(c[2] - c[0]).normalize_or_zero();
        winding(centroid + normal * off) >= 1
    };
    // Pieces of the surface between the crossings: one winding number each, at the
    // piece's first triangle; the crossing triangles one each.
    let mut piece_of = vec![usize::MAX; n];
    let mut firsts = Vec::new();
    for start in 0..n {
        if crossing[start] || piece_of[start] != usize::MAX {
            continue;
        }
        let id = firsts.len();
        firsts.push(start);
        piece_of[start] = id;
        let mut queue = VecDeque::from([start]);
        while let Some(t) = queue.pop_front() {
            for &o in neighbours.get(t).into_iter().flatten() {
                if o != NO_NEIGHBOUR && !crossing[o as usize] && piece_of[o as usize] == usize::MAX {
                    piece_of[o as usize] = id;
                    queue.push_back(o as usize);
                }
            }
        }
    }
    let crossing_list: Vec<usize> = (0..n).filter(|&t| crossing[t]).collect();
    let probes: Vec<usize> = firsts.iter().chain(&crossing_list).copied().collect();
    let inside = par_map(probes.len(), |k| outside_inside(probes[k]));
    let (piece_buried, crossing_buried) = inside.split_at(firsts.len());
    let mut buried: Vec<bool> = piece_of.iter().map(|&p| p != usize::MAX && piece_buried[p]).collect();
    for (&t, &b) in crossing_list.iter().zip(crossing_buried) {
        buried[t] = b;
    }
    Shell {
        buried,
        crossing_at: crossing,
        crossing: count,
    }
}
