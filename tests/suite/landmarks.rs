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

/// A closed tube of radius `r` along the polyline `axis` (8 sides per ring, rings every
/// `step` along each segment, the ends capped), as OBJ text.
fn tube_obj(axis: &[DVec3], r: f64, step: f64) -> String {
    let mut centres = Vec::new();
    for w in axis.windows(2) {
        let n = ((w[1] - w[0]).length() / step).ceil().max(1.0) as usize;
        centres.extend((0..n).map(|k| w[0].lerp(w[1], k as f64 / n as f64)));
    }
    centres.push(axis[axis.len() - 1]);
    let sides = 16;
    let mut text = String::new();
    for (k, c) in centres.iter().enumerate() {
        // A frame across the local direction (horizontal x and the rest).
        let a = (k.saturating_sub(1), (k + 1).min(centres.len() - 1));
        let d = (centres[a.1] - centres[a.0]).normalize();
        let u = d.cross(DVec3::Z).normalize();
        let v = d.cross(u);
        for s in 0..sides {
            let t = std::f64::consts::TAU * s as f64 / sides as f64;
            let p = *c + (u * t.cos() + v * t.sin()) * r;
            text.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
        }
    }
    let ring = |k: usize, s: usize| k * sides + s % sides + 1;
    for k in 0..centres.len() - 1 {
        for s in 0..sides {
            text.push_str(&format!("f {} {} {}\n", ring(k, s), ring(k, s + 1), ring(k + 1, s + 1)));
            text.push_str(&format!("f {} {} {}\n", ring(k, s), ring(k + 1, s + 1), ring(k + 1, s)));
        }
    }
    let last = centres.len() - 1;
    let (top, bottom) = (centres.len() * sides + 1, centres.len() * sides + 2);
    text.push_str(&format!("v {} {} {}\n", centres[0].x, centres[0].y, centres[0].z));
    text.push_str(&format!(
        "v {} {} {}\n",
        centres[last].x, centres[last].y, centres[last].z
    ));
    for s in 0..sides {
        text.push_str(&format!("f {} {} {}\n", top, ring(0, s + 1), ring(0, s)));
        text.push_str(&format!("f {} {} {}\n", bottom, ring(last, s), ring(last, s + 1)));
    }
    text
}

#[test]
fn the_elbow_is_found_at_the_bend_of_a_synthetic_arm() {
    // An arm hanging 40 degrees from the vertical down to the elbow at y = 1.0, then 20
    // degrees further out to the wrist: its horizontal sections' centroids (the arm's
    // rule) lie on the axis, and the best two-segment fit puts the corner at the bend.
    let down = |deg: f64| DVec3::new(deg.to_radians().sin(), -deg.to_radians().cos(), 0.0);
    let shoulder = DVec3::new(0.2, 1.3, 0.0);
    let elbow = shoulder + down(40.0) * (0.3 / 40f64.to_radians().cos());
    let wrist = elbow + down(60.0) * 0.25;
    let text = tube_obj(&[shoulder, elbow, wrist], 0.04, 0.005);
    let arm = BodyMesh::from_obj_text(&text, "arm", 1.0).expect("a closed tube");
    let mut centres = Vec::new();
    let mut y = shoulder.y - 0.05;
    while y > wrist.y + 0.05 {
        let loops = drape::body::profile::outer_loops(&arm, y, 1.0);
        assert_eq!(loops.len(), 1, "one section at y = {y}");
        let c = loops[0].centroid;
        // On the axis: the oblique cut of a round tube is centred on it.
        let on_axis = if y >= elbow.y {
            shoulder.lerp(elbow, (shoulder.y - y) / (shoulder.y - elbow.y))
        } else {
            elbow.lerp(wrist, (elbow.y - y) / (elbow.y - wrist.y))
        };
        if (y - elbow.y).abs() > 0.06 {
            assert!(
                (DVec3::new(c.x, y, c.y) - on_axis).length() < 2e-3,
                "y {y}: {c} vs {on_axis}"
            );
        }
        centres.push(DVec3::new(c.x, y, c.y));
        y -= 0.005;
    }
    let k = drape::body::landmarks::bend(&centres);
    // Within 3 cm: sections that cut both segments near the bend pull their centroids in.
    assert!(
        (centres[k].y - elbow.y).abs() < 0.03,
        "the bend at y {} (true {})",
        centres[k].y,
        elbow.y
    );
    // A straight arm has no bend to find: the middle is taken.
    let straight: Vec<DVec3> = (0..41).map(|i| shoulder.lerp(wrist, i as f64 / 40.0)).collect();
    assert_eq!(drape::body::landmarks::bend(&straight), 20);
}

#[test]
fn every_shipped_body_has_elbows_between_its_shoulders_and_wrists() {
    for path in super::common::shipped_bodies() {
        let body = Body::load_default(Some(&path)).expect("a shipped body");
        let lm = &body.landmarks;
        for (k, side) in [Side::Left, Side::Right].into_iter().enumerate() {
            let name = path.display();
            let s = lm.get(LandmarkKind::Shoulder, side).expect("shoulder").position();
            let e = lm
                .get(LandmarkKind::Elbow, side)
                .unwrap_or_else(|| panic!("{name}: no elbow"))
                .position();
            let w = lm
                .get(LandmarkKind::Wrist, side)
                .unwrap_or_else(|| panic!("{name}: no wrist"))
                .position();
            assert!(
                w.y < e.y && e.y < s.y,
                "{name} {side:?}: heights {} {} {}",
                s.y,
                e.y,
                w.y
            );
            let axis = &lm.arm_axis[k];
            assert!(
                axis.elbow > 1 && axis.elbow + 1 < axis.points.len(),
                "{name}: elbow {}",
                axis.elbow
            );
            // The elbow's landmark is on the arm's skin beside its axis point.
            let along = axis.points[axis.elbow];
            assert!(
                (e.y - along.y).abs() < 1e-9 && e.distance(along) < 0.08,
                "{name}: {e} vs {along}"
            );
            // Published adult proportions (e.g. Drillis and Contini): upper arm ~0.19 and
            // forearm ~0.15 of stature, the elbow a bit past half way. Generous bands.
            let stature = body.mesh.height();
            let upper = s.distance(along) / stature;
            let whole = axis.length() / stature;
            assert!(
                (0.12..0.24).contains(&upper) && (0.24..0.40).contains(&whole),
                "{name}: {upper} {whole}"
            );
            // The wrist is narrower across the arm than the elbow.
            let across = |k: usize| drape::body::girth_across(&body.mesh, axis.points[k], axis.direction(k));
            let last = axis.points.len() - 1;
            assert!(across(last).unwrap() < across(axis.elbow).unwrap(), "{name}");
        }
    }
}

#[test]
fn an_elbow_override_moves_both_elbows_to_that_height_on_the_arms() {
    let mesh = BodyMesh::load(&drape::body::BodySource::Builtin, 1.0).unwrap();
    let mut options = LandmarkOptions::default();
    options.overrides = vec![(LandmarkKind::Elbow, LandmarkOverride::Height(1.05))];
    let body = Body::analyse(mesh, &options, &PartitionOptions::default()).unwrap();
    let lm = &body.landmarks;
    let torso = drape::body::profile::outer_loops(&body.mesh, 1.05, body.mesh.height())
        .into_iter()
        .find(|l| l.contains(glam::DVec2::new(lm.mid_x, lm.torso_at(1.05).unwrap().y)))
        .expect("the torso's section");
    for (k, side) in [Side::Left, Side::Right].into_iter().enumerate() {
        let e = lm.get(LandmarkKind::Elbow, side).unwrap();
        assert!(e.overridden && e.point[1] == 1.05, "{side:?}: {:?}", e.point);
        // On the arm: outside the torso's section, beside the arm's axis at that height.
        let x = e.point[0];
        assert!(
            if k == 0 { x > torso.max.x } else { x < torso.min.x },
            "{side:?}: x {x}"
        );
        let axis = lm.arm_axis[k]
            .points
            .iter()
            .min_by(|a, b| (a.y - 1.05).abs().total_cmp(&(b.y - 1.05).abs()))
            .unwrap();
        assert!(e.position().distance(*axis) < 0.08, "{side:?}: {:?} vs {axis}", e.point);
    }
}
