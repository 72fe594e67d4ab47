//! Ring resampling on the real body's convexified rings: equal spacing per arc, extremes kept.

use drape::garment::{ConvexRing, convex_ring, resample_closed, resample_open};
use drape::geom::Plane;
use glam::DVec3;

use super::common::real_body;

#[test]
fn body_rings_resample_to_equal_spacing_keeping_the_extremes() {
    let body = real_body();
    let per_arc = 8;
    for ring in &body.rings {
        let ConvexRing {
            points: convex,
            anchors,
            ..
        } = convex_ring(&ring.points, &Plane::horizontal(ring.y));
        let samples = resample_closed(&convex, &anchors, per_arc).unwrap();
        assert_eq!(samples.len(), anchors.len() * per_arc, "{}", ring.name);
        for (k, &a) in anchors.iter().enumerate() {
            assert_eq!(samples[k * per_arc], convex[a], "{}: extreme {k} moved", ring.name);
            // Chord spacing along the arc (to the next anchor) equal within 1%.
            let arc: Vec<DVec3> = (0..=per_arc)
                .map(|j| samples[(k * per_arc + j) % samples.len()])
                .collect();
            let gaps: Vec<f64> = arc.windows(2).map(|w| w[0].distance(w[1])).collect();
            let mean = gaps.iter().sum::<f64>() / gaps.len() as f64;
            for g in &gaps {
                assert!(
                    (g - mean).abs() <= 0.01 * mean,
                    "{} arc {k}: gap {g} vs mean {mean}",
                    ring.name
                );
            }
        }
        assert!(samples.iter().all(|p| (p.y - ring.y).abs() < 1e-12));
    }
}

#[test]
fn an_open_curve_keeps_its_ends_and_middle() {
    // An L: 3 m along x then 1 m along z; total 4, middle at (2, 0, 0).
    let curve = [DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 1.0)];
    let s = resample_open(&curve, 4).unwrap();
    assert_eq!(s.len(), 9);
    assert_eq!((s[0], s[8]), (curve[0], curve[2]));
    assert!(s[4].distance(DVec3::new(2.0, 0.0, 0.0)) < 1e-15);
    assert!(s[6].distance(DVec3::new(3.0, 0.0, 0.0)) < 1e-15);
}

#[test]
fn anchors_out_of_order_are_refused() {
    let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 0.0, 1.0), DVec3::Z];
    assert!(resample_closed(&square, &[0, 2, 1, 3], 4).is_err());
    assert!(resample_closed(&square, &[0, 1, 2, 3], 4).is_ok());
}
