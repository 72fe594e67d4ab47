//! The tree's queries against scans of every triangle, and trees read back that do not
//! hold together.

use glam::{DVec3, Vec3};

use super::{NEAREST_STACK, NearTree, Node, Pair};

/// Whether segment `ab` meets triangle `t` (Möller-Trumbore, parameter in `[0, 1]`).
fn crosses(a: DVec3, b: DVec3, [p, q, r]: [DVec3; 3]) -> bool {
    let (d, e1, e2) = (b - a, q - p, r - p);
    let h = d.cross(e2);
    let det = e1.dot(h);
    if det.abs() < 1e-300 {
        return false;
    }
    let s = a - p;
    let u = s.dot(h) / det;
    let w = s.cross(e1);
    let v = d.dot(w) / det;
    let t = e2.dot(w) / det;
    (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && (0.0..=1.0).contains(&t)
}

/// Numbers in `[0, 1)`.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Distance from `p` to segment `ab`.
fn to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// Distance from `p` to triangle `abc` (its plane where `p` projects inside it by the
/// signs of the edges' cross products, else the nearest edge), written here apart from
/// the library's closest point.
fn to_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let n = (b - a).cross(c - a);
    if n.length_squared() > 0.0 {
        let q = p - n * ((p - a).dot(n) / n.length_squared());
        if [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| (v - u).cross(q - u).dot(n) >= 0.0)
        {
            return p.distance(q);
        }
    }
    to_segment(p, a, b).min(to_segment(p, b, c)).min(to_segment(p, c, a))
}

/// Triangle soups the body never gives: a cluster of near-coincident triangles, a run
/// shrinking geometrically towards a point (which drives surface-area splits deep), and
/// triangles scattered at random. For each, the tree's nearest distance equals a scan
/// of every triangle, at points near and far, searched from the root or from any
/// triangle's leaf; a gather within a radius visits every triangle nearer than it; and
/// its walk along a segment finds a
/// crossing exactly when a scan does, with the caller's boxes widened as the body index
/// widens its own.
#[test]
fn nearest_points_and_segment_walks_through_the_tree_equal_a_scan_of_every_triangle_on_awkward_soups() {
    let mut rng = Lcg(3);
    let mut jitter = |s: f64| DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * s;
    let mut soups: Vec<Vec<[DVec3; 3]>> = Vec::new();
    soups.push(
        (0..600)
            .map(|_| {
                [
                    jitter(1e-4),
                    jitter(1e-4) + DVec3::X * 1e-3,
                    jitter(1e-4) + DVec3::Y * 1e-3,
                ]
            })
            .collect(),
    );
    soups.push(
        (0..300)
            .map(|k| {
                let s = 0.8f64.powi(k);
                [DVec3::splat(s), DVec3::new(s, 0.0, 0.0) * 1.1, DVec3::new(0.0, s, s)]
            })
            .collect(),
    );
    soups.push(
        (0..2000)
            .map(|_| {
                let c = jitter(2.0);
                [c, c + jitter(0.05), c + jitter(0.05)]
            })
            .collect(),
    );
    for (k, soup) in soups.iter().enumerate() {
        let ids: Vec<u32> = (0..soup.len() as u32).collect();
        let slack = 1e-6;
        let tree = NearTree::new(
            &ids,
            |t| soup[t as usize],
            |t| {
                let [a, b, c] = soup[t as usize];
                let (lo, hi) = (
                    a.min(b).min(c) - DVec3::splat(slack),
                    a.max(b).max(c) + DVec3::splat(slack),
                );
                (lo.as_vec3(), hi.as_vec3())
            },
        );
        for _ in 0..300 {
            let p = jitter(if k == 2 { 5.0 } else { 0.01 });
            let truth = soup.iter().map(|&t| to_triangle(p, t)).fold(f64::INFINITY, f64::min);
            let mut best = f64::INFINITY;
            tree.nearest(p.as_vec3(), f32::INFINITY, |_, corners| {
                let d = to_triangle(p, *corners);
                best = best.min(d);
                Some(((d + 1e-5) * (d + 1e-5)) as f32)
            });
            assert_eq!(best, truth, "soup {k}, {p}");
            // Started from any node (a leaf, an inner node or none of the tree's, which
            // start from the root): the same.
            let start = (jitter(1.0).x + 0.5) * (2 * tree.pairs.len() + 5) as f64;
            let mut best = f64::INFINITY;
            tree.nearest_from(p.as_vec3(), f32::INFINITY, Some(start as usize), |_, corners| {
                let d = to_triangle(p, *corners);
                best = best.min(d);
                Some(((d + 1e-5) * (d + 1e-5)) as f32)
            });
            assert_eq!(best, truth, "soup {k}, {p}, from node {start}");
            // Gathering within a radius: every triangle nearer than it is visited, once.
            let radius = (truth + 1e-4) * (1.0 + 3.0 * jitter(1.0).x.abs());
            let mut visited = Vec::new();
            tree.within(p.as_vec3(), (radius * radius) as f32, |t, _| visited.push(t));
            visited.sort_unstable();
            let count = visited.len();
            visited.dedup();
            assert_eq!(visited.len(), count, "soup {k}, {p}: a triangle visited twice");
            for (t, &tri) in soup.iter().enumerate() {
                let d = to_triangle(p, tri);
                let seen = visited.binary_search(&(t as u32)).is_ok();
                assert!(
                    seen || d >= radius,
                    "soup {k}, {p}: triangle {t} at {d} < {radius} missed"
                );
            }
        }
        // Segments: the walk may look at more triangles than it must, never at fewer.
        let mut hits = 0;
        for _ in 0..300 {
            let a = jitter(if k == 2 { 5.0 } else { 0.01 });
            // Through the middle of the small soups; anywhere in the scattered one.
            let b = if k == 2 {
                // Through a triangle's centre, a little off it.
                let [p, q, r] = soup[(a.x.abs() * 1e4) as usize % soup.len()];
                2.0 * (p + q + r) / 3.0 - a + jitter(0.02)
            } else {
                2.0 * DVec3::new(5e-4, 5e-4, 0.0) - a + jitter(1e-3)
            };
            let truth = soup.iter().any(|&t| crosses(a, b, t));
            let walked = tree.any_on_segment(a, b, 1e-5, |_, c| crosses(a, b, *c));
            assert_eq!(walked, truth, "soup {k}, {a} -> {b}");
            hits += usize::from(truth);
        }
        assert!(hits >= 10, "soup {k}: {hits} segments met a triangle");
    }
}

/// A tree read back holds together or is refused: intact it is restored; a wide child
/// pointing back at its parent, a binary child before its parent, a leaf past the
/// slots or a triangle past the count are refused (each would loop or index out of
/// bounds in a query).
#[test]
fn a_tree_read_back_that_does_not_hold_together_is_refused() {
    let soup: Vec<[DVec3; 3]> = (0..50)
        .map(|k| {
            let c = DVec3::new(k as f64, 0.0, 0.0);
            [c, c + DVec3::X * 0.5, c + DVec3::Y]
        })
        .collect();
    let ids: Vec<u32> = (0..50).collect();
    let corners = |t: u32| soup[t as usize];
    let tree = NearTree::new(&ids, corners, |t| {
        let [a, b, c] = soup[t as usize];
        (a.min(b).min(c).as_vec3(), a.max(b).max(c).as_vec3())
    });
    assert!(tree.clone().restore(50, corners, true));
    let mut looped = tree.clone();
    looped.nodes[0].child[0] = 0;
    assert!(!looped.restore(50, corners, true));
    let mut back = tree.clone();
    back.pairs[1].0[0].first = 0;
    assert!(!back.restore(50, corners, true));
    let mut past = tree.clone();
    past.triangles.pop();
    assert!(!past.restore(50, corners, true));
    assert!(!tree.clone().restore(49, corners, true));
}

/// A binary chain `levels` deep over 200 triangles: every internal node's first child
/// goes on down, its second is a one-triangle leaf; every box holds everything.
fn chain(levels: usize) -> NearTree {
    let soup: Vec<[DVec3; 3]> = (0..200)
        .map(|k| {
            [
                DVec3::X * k as f64,
                DVec3::new(k as f64, 1.0, 0.0),
                DVec3::new(k as f64, 0.0, 1.0),
            ]
        })
        .collect();
    let ids: Vec<u32> = (0..200).collect();
    let mut tree = NearTree::new(&ids, |t| soup[t as usize], |_| (Vec3::splat(-1e3), Vec3::splat(1e3)));
    let node = |first: usize, count: u32| Node {
        lo: Vec3::splat(-1e3),
        first: first as u32,
        hi: Vec3::splat(1e3),
        count,
    };
    tree.pairs = (0..=levels)
        .map(|k| match k {
            0 => Pair([node(2, 0), node(0, 0)]),
            k if k == levels => Pair([node(k, 1), node(k + 100, 1)]),
            k => Pair([node(2 * k + 2, 0), node(k, 1)]),
        })
        .collect();
    tree
}

/// A tree read back deeper than the nearest-point descent's stack is refused; one level
/// less is taken, and a descent that defers a child at every level (every box holds the
/// point) runs through it.
#[test]
fn a_tree_read_back_too_deep_for_the_descent_is_refused() {
    let corners = |t: u32| {
        [
            DVec3::X * t as f64,
            DVec3::new(t as f64, 1.0, 0.0),
            DVec3::new(t as f64, 0.0, 1.0),
        ]
    };
    assert!(!chain(NEAREST_STACK + 1).restore(200, corners, true));
    let mut deepest = chain(NEAREST_STACK);
    assert!(deepest.restore(200, corners, true));
    assert_eq!(deepest.link(true), Some(NEAREST_STACK));
    let mut seen = 0;
    deepest.nearest(Vec3::ZERO, f32::INFINITY, |_, _| {
        seen += 1;
        None
    });
    assert_eq!(seen, NEAREST_STACK + 1);
}
