//! The winding-number tree of the ground truth against the plain sum over every triangle.

use drape::body::{BodyMesh, BodySource};
use drape::geom::inside::winding_number;
use drape::geom::winding_tree::WindingTree;
use glam::DVec3;

/// Points about a body: each 7th vertex moved along its normal by -5 cm to +5 cm (through the
/// skin, where the verdict is hardest), and points spread through its box.
fn probes(mesh: &drape::mesh::TriMesh) -> Vec<DVec3> {
    let normals = mesh.vertex_normals();
    let offsets = [-0.05, -0.01, -0.001, -1e-4, 1e-4, 0.001, 0.01, 0.05];
    let mut out = Vec::new();
    for (k, (p, n)) in mesh.positions.iter().zip(&normals).enumerate().step_by(7) {
        out.push(*p + offsets[k % offsets.len()] * *n);
    }
    let (lo, hi) = mesh.bounds().expect("a body has points");
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..400 {
        out.push(lo + (hi - lo) * DVec3::new(next(), next(), next()));
    }
    out
}

/// On every shipped body, at points through the skin and through the body's box: the tree's
/// winding number lies within its stated bound of the sum over every triangle, and its
/// verdict (inside above one half) is the sum's.
#[test]
fn the_winding_tree_is_within_its_bound_of_the_full_sum_and_gives_its_verdict_on_every_body() {
    for path in super::common::shipped_bodies() {
        let body = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("the body loads");
        let mesh = &body.mesh;
        let tree = WindingTree::new(mesh);
        let points = probes(mesh);
        let results = drape::par::par_map(points.len(), |k| {
            let p = points[k];
            let full = winding_number(mesh, p);
            let (w, bound) = tree.winding_with_bound(p);
            (full, w, bound, tree.is_inside(p))
        });
        let mut inside = 0;
        let mut decided = 0;
        for (p, (full, w, bound, verdict)) in points.iter().zip(&results) {
            assert!(
                (w - full).abs() <= bound + 1e-9,
                "{}: at {p} the tree gives {w}, the full sum {full}, beyond the bound {bound}",
                path.display()
            );
            assert_eq!(
                *verdict,
                *full > 0.5,
                "{}: the verdict at {p} (winding {full})",
                path.display()
            );
            inside += usize::from(*verdict);
            decided += usize::from((w - 0.5).abs() > bound + 1e-9);
        }
        println!(
            "{}: {} points, {inside} inside, {decided} decided by the tree alone",
            path.display(),
            points.len()
        );
        assert!(
            inside > points.len() / 10 && inside < points.len() * 9 / 10,
            "{inside} inside"
        );
    }
}
