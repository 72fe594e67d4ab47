//! Landmarks on the real body: anatomical order, symmetry, and invariance under changes
//! of scale and girth (nothing is tuned to one mesh's absolute sizes).

use drape::body::{
    Body, BodyMesh, LandmarkKind, LandmarkOptions, LandmarkOverride, PartitionId, PartitionOptions, Side,
};
use glam::DVec3;

use super::common::real_body;

fn heights(body: &Body) -> Vec<f64> {
    LandmarkKind::ALL.iter().map(|k| body.landmarks.height(*k)).collect()
}

#[test]
fn landmarks_come_in_anatomical_order_and_plausible_proportions() {
    let body = real_body();
    let h = heights(body);
    // ALL is bottom to top: ankle, knee, crotch, hip, waist, bust, armpit, shoulder,
    // front neck, side neck, neck.
    for (w, k) in h.windows(2).zip(LandmarkKind::ALL.windows(2)) {
        assert!(
            w[0] < w[1],
            "{:?} ({}) should be below {:?} ({})",
            k[0],
            w[0],
            k[1],
            w[1]
        );
    }
    let stature = body.mesh.height();
    let ratio = |k: LandmarkKind| body.landmarks.height(k) / stature;
    // Published adult proportions (e.g. Drillis and Contini): crotch ~0.47, waist ~0.63,
    // shoulder ~0.82 of stature; knee ~0.28. Generous bands, not fitted values.
    assert!(
        (0.42..0.52).contains(&ratio(LandmarkKind::Crotch)),
        "{}",
        ratio(LandmarkKind::Crotch)
    );
    assert!(
        (0.58..0.68).contains(&ratio(LandmarkKind::Waist)),
        "{}",
        ratio(LandmarkKind::Waist)
    );
    assert!(
        (0.78..0.86).contains(&ratio(LandmarkKind::Shoulder)),
        "{}",
        ratio(LandmarkKind::Shoulder)
    );
    assert!(
        (0.22..0.32).contains(&ratio(LandmarkKind::Knee)),
        "{}",
        ratio(LandmarkKind::Knee)
    );
}

#[test]
fn paired_landmarks_mirror_each_other() {
    let body = real_body();
    let mid = body.landmarks.mid_x;
    for kind in LandmarkKind::ALL.into_iter().filter(|k| k.is_paired()) {
        let l = body.landmarks.get(kind, Side::Left).unwrap().position();
        let r = body.landmarks.get(kind, Side::Right).unwrap().position();
        assert!(l.x > mid && r.x < mid, "{kind:?}");
        assert!(
            ((l.x - mid) + (r.x - mid)).abs() < 2e-3 && (l.y - r.y).abs() < 2e-3,
            "{kind:?}: {l} {r}"
        );
    }
}

fn analyse_scaled(scale: DVec3, offset: DVec3) -> Body {
    let mut mesh = real_body().mesh.clone();
    for p in &mut mesh.mesh.positions {
        *p = *p * scale + offset;
    }
    mesh.reindex();
    Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).unwrap()
}

#[test]
fn a_taller_body_elsewhere_has_the_same_landmarks_scaled() {
    let (s, offset) = (1.17, DVec3::new(0.4, -0.2, 1.5));
    let scaled = analyse_scaled(DVec3::splat(s), offset);
    let base = real_body();
    for (a, b) in base.landmarks.items.iter().zip(&scaled.landmarks.items) {
        let expected = a.position() * s + offset;
        assert!(
            b.position().distance(expected) < 1e-6,
            "{}: {} vs {expected}",
            a.label(),
            b.position()
        );
    }
}

#[test]
fn a_stouter_body_keeps_its_landmark_heights() {
    // Girths 25% larger all round: every landmark height is found at the same level.
    let stout = analyse_scaled(DVec3::new(1.25, 1.0, 1.25), DVec3::ZERO);
    let base = real_body();
    let level = base.mesh.height() / LandmarkOptions::DEFAULT_LEVELS as f64;
    for kind in LandmarkKind::ALL {
        let (a, b) = (base.landmarks.height(kind), stout.landmarks.height(kind));
        assert!((a - b).abs() <= level, "{kind:?}: {a} vs {b}");
    }
}

#[test]
fn an_override_moves_the_landmark_its_ring_and_the_partitions() {
    let mesh = BodyMesh::load(&drape::body::BodySource::Builtin, 1.0).unwrap();
    let mut options = LandmarkOptions::default();
    options.overrides = vec![(LandmarkKind::Waist, LandmarkOverride::Height(1.0))];
    let body = Body::analyse(mesh, &options, &PartitionOptions::default()).unwrap();
    let waist = body.landmarks.get(LandmarkKind::Waist, Side::Centre).unwrap();
    assert!(waist.overridden && waist.point[1] == 1.0);
    let ring = body.rings.iter().find(|r| r.name == "waist").unwrap();
    assert!((ring.y - 1.0).abs() < 1e-12 && ring.points.iter().all(|p| (p.y - 1.0).abs() < 1e-12));
    let hip = body.landmarks.height(LandmarkKind::Hip);
    let c = body.partitions.iter().find(|p| p.id == PartitionId::C).unwrap();
    assert!((c.upper_y - 0.5 * (hip + 1.0)).abs() < 1e-12);
}

#[test]
fn partitions_tile_the_body_and_every_triangle_is_in_one() {
    let body = real_body();
    let (lo, hi) = body.mesh.mesh.bounds().unwrap();
    let parts = &body.partitions;
    assert_eq!(
        parts.iter().map(|p| p.id).collect::<Vec<_>>(),
        PartitionId::ALL.to_vec()
    );
    assert_eq!(parts[0].lower_y, lo.y);
    assert_eq!(parts[6].upper_y, hi.y);
    for w in parts.windows(2) {
        assert_eq!(w[0].upper_y, w[1].lower_y);
        assert!(w[0].lower_y < w[0].upper_y);
    }
    let mut covered = vec![false; body.mesh.mesh.triangles.len()];
    for p in parts {
        for &t in &p.triangles {
            covered[t as usize] = true;
        }
    }
    assert!(covered.iter().all(|c| *c));
    // Legs and abdomen use the line-line test, the others point-face ([collide] table 1).
    use drape::body::DetectionMethod::{LineLine, PointFace};
    let methods: Vec<_> = parts.iter().map(|p| p.method).collect();
    assert_eq!(
        methods,
        vec![
            LineLine, PointFace, PointFace, LineLine, PointFace, PointFace, PointFace
        ]
    );
}
