//! Easing the real body's rings: every eased point's gap to the (convexified) body ring
//! equals the ease, and no point comes nearer the raw section than that.

use drape::garment::{ConvexRing, Ease, convex_ring, ease_ring, extremes, resample_closed};
use drape::geom::{Plane, polygon};
use glam::{DVec2, DVec3};

use super::common::real_body;

/// Distance from `p` to a closed polyline, computed here independently of the library.
fn gap(p: DVec2, ring: &[DVec2]) -> f64 {
    let n = ring.len();
    let mut best = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        let ab = b - a;
        let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        best = best.min((a + ab * t - p).length());
    }
    best
}

struct Prepared {
    name: String,
    plane: Plane,
    raw: Vec<DVec2>,
    convex: Vec<DVec3>,
    convex_flat: Vec<DVec2>,
    samples: Vec<DVec3>,
    per_arc: usize,
}

fn prepared_rings() -> Vec<Prepared> {
    let per_arc = 10;
    real_body()
        .rings
        .iter()
        .map(|ring| {
            let plane = Plane::horizontal(ring.y);
            let raw: Vec<DVec2> = ring.points.iter().map(|p| plane.project(*p)).collect();
            let ConvexRing {
                points: convex,
                anchors,
                ..
            } = convex_ring(&ring.points, &plane);
            let samples = resample_closed(&convex, &anchors, per_arc).unwrap();
            let convex_flat = convex.iter().map(|p| plane.project(*p)).collect();
            Prepared {
                name: ring.name.clone(),
                plane,
                raw,
                convex,
                convex_flat,
                samples,
                per_arc,
            }
        })
        .collect()
}

#[test]
fn uniform_ease_gives_every_point_the_same_gap() {
    for ease in [0.005, 0.02, 0.08] {
        for r in prepared_rings() {
            let eased = ease_ring(&r.samples, &r.convex, &r.plane, Ease::Uniform(ease)).unwrap();
            for (k, p) in eased.iter().enumerate() {
                let q = r.plane.project(*p);
                let g = gap(q, &r.convex_flat);
                assert!((g - ease).abs() < 1e-9, "{} point {k}: gap {g} for ease {ease}", r.name);
                assert!(
                    gap(q, &r.raw) >= ease - 1e-9,
                    "{} point {k} nearer the skin than the ease",
                    r.name
                );
                assert!(!polygon::contains(&r.raw, q));
                assert!((p.y - r.plane.offset).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn per_direction_ease_is_met_at_the_extremes() {
    let ease = Ease::PerDirection {
        front: 0.03,
        left: 0.01,
        back: 0.02,
        right: 0.015,
    };
    let rings: Vec<Prepared> = prepared_rings()
        .into_iter()
        .filter(|r| r.samples.len() == 4 * r.per_arc)
        .collect();
    assert!(rings.len() >= 8, "only {} rings have 4 distinct extremes", rings.len());
    for r in rings {
        let eased = ease_ring(&r.samples, &r.convex, &r.plane, ease).unwrap();
        // The samples start at the front extreme; the others follow in ring order.
        let flat: Vec<DVec2> = r.samples.iter().map(|p| r.plane.project(*p)).collect();
        let order = extremes(&flat);
        for (k, want) in [0.03, 0.01, 0.02, 0.015].into_iter().enumerate() {
            let g = gap(r.plane.project(eased[order[k]]), &r.convex_flat);
            assert!((g - want).abs() < 1e-9, "{} extreme {k}: gap {g}, want {want}", r.name);
        }
    }
}

#[test]
fn a_negative_ease_is_refused() {
    let r = &prepared_rings()[0];
    let e = ease_ring(&r.samples, &r.convex, &r.plane, Ease::Uniform(-0.01)).unwrap_err();
    assert_eq!(e.to_string(), "ease must be finite and not negative (got -0.01 m)");
}
