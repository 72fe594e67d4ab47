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
