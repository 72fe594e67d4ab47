//! Coons patches: exact reproduction of bilinear patches and planes, exact boundaries.

use drape::geom::CoonsPatch;
use glam::DVec3;

const TOLERANCE: f64 = 1e-12;

fn lerp(a: DVec3, b: DVec3) -> impl Fn(f64) -> DVec3 {
    move |t| a + (b - a) * t
}

fn params() -> impl Iterator<Item = (f64, f64)> {
    (0..=16).flat_map(|i| (0..=16).map(move |j| (i as f64 / 16.0, j as f64 / 16.0)))
}

#[test]
fn straight_boundaries_give_the_bilinear_patch() {
    // A twisted (non-planar) quadrilateral.
    let [p00, p10, p01, p11] = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.2, 0.1, 0.3),
        DVec3::new(-0.1, 0.9, -0.4),
        DVec3::new(1.0, 1.3, 0.8),
    ];
    let patch = CoonsPatch::try_new(
        Box::new(lerp(p00, p10)) as Box<dyn Fn(f64) -> DVec3>,
        Box::new(lerp(p01, p11)),
        Box::new(lerp(p00, p01)),
        Box::new(lerp(p10, p11)),
        1e-12,
    )
    .unwrap();
    for (u, v) in params() {
        let bilinear = p00 * ((1.0 - u) * (1.0 - v)) + p10 * (u * (1.0 - v)) + p01 * ((1.0 - u) * v) + p11 * (u * v);
        assert!(patch.sample(u, v).distance(bilinear) <= TOLERANCE, "({u}, {v})");
    }
}

#[test]
fn curved_boundaries_in_a_plane_stay_in_the_plane_and_are_interpolated() {
    // Boundaries are curves drawn in the plane through `o` spanned by `e1`, `e2`.
    let o = DVec3::new(0.3, 1.1, -0.2);
    let e1 = DVec3::new(1.0, 0.2, 0.1).normalize();
    let e2 = e1.cross(DVec3::new(0.1, 0.3, 1.0)).normalize();
    let normal = e1.cross(e2).normalize();
    let at = move |a: f64, b: f64| o + e1 * a + e2 * b;
    let bottom = move |t: f64| at(t, 0.15 * (std::f64::consts::PI * t).sin());
    let top = move |t: f64| at(t + 0.1 * t * (1.0 - t), 1.0 + 0.2 * t * t);
    let left = move |t: f64| at(-0.12 * (std::f64::consts::PI * t).sin(), t);
    let right = move |t: f64| at(1.0 + 0.3 * t * t * (1.0 - t), 0.2 * t * t + t * (1.0 - t) * 0.05 + t);
    let curves: [Box<dyn Fn(f64) -> DVec3>; 4] = [Box::new(bottom), Box::new(top), Box::new(left), Box::new(right)];
    let [b, t, l, r] = curves;
    let patch = CoonsPatch::try_new(b, t, l, r, 1e-12).unwrap();
    for (u, v) in params() {
        assert!(
            (patch.sample(u, v) - o).dot(normal).abs() <= TOLERANCE,
            "off the plane at ({u}, {v})"
        );
    }
    for s in (0..=32).map(|i| i as f64 / 32.0) {
        assert!(patch.sample(s, 0.0).distance(bottom(s)) <= TOLERANCE);
        assert!(patch.sample(s, 1.0).distance(top(s)) <= TOLERANCE);
        assert!(patch.sample(0.0, s).distance(left(s)) <= TOLERANCE);
        assert!(patch.sample(1.0, s).distance(right(s)) <= TOLERANCE);
    }
}

#[test]
fn boundaries_that_do_not_meet_are_refused_naming_the_corner() {
    let f = |a: DVec3, b: DVec3| Box::new(lerp(a, b)) as Box<dyn Fn(f64) -> DVec3>;
    let (p00, p10, p01, p11) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE);
    let gap = DVec3::new(0.0, 0.0, 1e-3);
    let Err(e) = CoonsPatch::try_new(f(p00, p10), f(p01, p11), f(p00, p01), f(p10 + gap, p11), 1e-6) else {
        panic!("accepted a gap");
    };
    assert_eq!(e.corner, "P10");
    assert!((e.distance - 1e-3).abs() < 1e-15);
}

/// Barycentric samples over the triangle, corners and sides included.
fn barycentric(n: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for r in 0..=n {
        for i in 0..=n - r {
            let (b1, b2) = (i as f64 / n as f64, r as f64 / n as f64);
            out.push([1.0 - b1 - b2, b1, b2]);
        }
    }
    out
}

#[test]
fn a_three_sided_patch_reproduces_a_flat_triangle() {
    // To 1e-9: the sides' derivatives are taken by differences of their samples.
    use drape::geom::TrianglePatch;
    let v = [
        DVec3::new(0.1, 0.2, 0.3),
        DVec3::new(1.3, 0.4, -0.2),
        DVec3::new(0.5, 1.7, 0.9),
    ];
    let patch = TrianglePatch::try_new([lerp(v[0], v[1]), lerp(v[1], v[2]), lerp(v[2], v[0])], 1e-12).unwrap();
    for b in barycentric(12) {
        let want = v[0] * b[0] + v[1] * b[1] + v[2] * b[2];
        assert!(
            patch.sample(b).distance(want) < 1e-9,
            "{b:?}: {}",
            patch.sample(b).distance(want)
        );
    }
}

#[test]
fn a_three_sided_patch_on_great_circle_arcs_stays_near_the_sphere() {
    use drape::geom::TrianglePatch;
    // The octant of the unit sphere bounded by three quarter circles: the sides are met
    // exactly, the inside stays within 5% of the radius (measured 4.4%: the blend knows the
    // sides and their tangents at the corners, not the sphere; linear side-vertex lines,
    // chords, sank it by 26%), and the patch's triangles all face outwards with no
    // degenerate one.
    let arc = |a: DVec3, b: DVec3| {
        move |t: f64| a * (std::f64::consts::FRAC_PI_2 * t).cos() + b * (std::f64::consts::FRAC_PI_2 * t).sin()
    };
    let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
    let patch = TrianglePatch::try_new([arc(x, y), arc(y, z), arc(z, x)], 1e-12).unwrap();
    for k in 0..=20 {
        let t = k as f64 / 20.0;
        assert!(
            patch.sample([1.0 - t, t, 0.0]).distance(arc(x, y)(t)) < 1e-12,
            "side 0 at {t}"
        );
        assert!(
            patch.sample([0.0, 1.0 - t, t]).distance(arc(y, z)(t)) < 1e-12,
            "side 1 at {t}"
        );
        assert!(
            patch.sample([t, 0.0, 1.0 - t]).distance(arc(z, x)(t)) < 1e-12,
            "side 2 at {t}"
        );
    }
    let worst = barycentric(24)
        .into_iter()
        .map(|b| (patch.sample(b).length() - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst < 0.05, "largest radial error {worst}");
    let n = 16;
    let points = patch.grid(n);
    let triangles = drape::geom::triangle_grid(n);
    assert_eq!(triangles.len(), n * n);
    for t in &triangles {
        let [a, b, c] = t.map(|i| points[i as usize]);
        let normal = (b - a).cross(c - a);
        assert!(normal.length() > 1e-6, "a degenerate triangle {t:?}");
        assert!(normal.dot(a + b + c) > 0.0, "a triangle facing in {t:?}");
    }
    // No T-junction: every directed edge has its twin, but the 3n of the boundary.
    let mut edges = std::collections::BTreeSet::new();
    for t in &triangles {
        for k in 0..3 {
            assert!(edges.insert((t[k], t[(k + 1) % 3])), "an edge used twice the same way");
        }
    }
    let open = edges.iter().filter(|(a, b)| !edges.contains(&(*b, *a))).count();
    assert_eq!(open, 3 * n);
}
