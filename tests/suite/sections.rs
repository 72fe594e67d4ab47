//! Plane sections: exact girths of analytic shapes, and the real body's loops.

use drape::body::LandmarkKind;
use drape::body::profile::outer_loops;
use drape::geom::{Plane, section_mesh};
use drape::mesh::validate_and_repair;
use glam::DVec3;

use super::common::{angle, closed_grid, ellipse_perimeter, ellipse_point, real_body, soup_girth};

#[test]
fn cylinder_girth_is_exact() {
    let (r, n) = (0.13, 2048);
    let mut mesh = closed_grid(
        9,
        n,
        |i, j| ellipse_point(r, r, 0.1 * i as f64, angle(j, n)),
        DVec3::ZERO,
        DVec3::new(0.0, 0.8, 0.0),
    );
    let (_, adjacency) = validate_and_repair(&mut mesh, "cylinder", &[]).expect("valid");
    for y in [0.05, 0.333, 0.71] {
        let loops = section_mesh(&mesh, &adjacency, &Plane::horizontal(y));
        assert_eq!(loops.len(), 1);
        assert!(loops[0].closed);
        // The section of the prism is the regular n-gon, exactly.
        let polygon = 2.0 * n as f64 * r * (std::f64::consts::PI / n as f64).sin();
        assert!(
            (loops[0].length() - polygon).abs() < 1e-12,
            "{} vs {polygon}",
            loops[0].length()
        );
        // And that is the circle within 1e-6 m.
        assert!((loops[0].length() - std::f64::consts::TAU * r).abs() < 1e-6);
    }
}

#[test]
fn ellipsoid_girth_at_a_ring_is_the_ellipse() {
    let (a, b, c) = (0.2, 0.5, 0.1); // semi-axes x, y, z
    let (rings, n) = (99, 4096);
    let lat = |i: usize| std::f64::consts::PI * (i + 1) as f64 / (rings + 1) as f64;
    let mut mesh = closed_grid(
        rings,
        n,
        |i, j| {
            let (s, co) = lat(i).sin_cos();
            ellipse_point(a * s, c * s, -b * co, angle(j, n))
        },
        DVec3::new(0.0, -b, 0.0),
        DVec3::new(0.0, b, 0.0),
    );
    let (_, adjacency) = validate_and_repair(&mut mesh, "ellipsoid", &[]).expect("valid");
    for i in [20, 49, 77] {
        let y = -b * lat(i).cos();
        let loops = section_mesh(&mesh, &adjacency, &Plane::horizontal(y));
        assert_eq!(loops.len(), 1, "ring {i}");
        let s = lat(i).sin();
        let exact = ellipse_perimeter(a * s, c * s);
        assert!(
            (loops[0].length() - exact).abs() < 1e-6,
            "ring {i}: {} vs {exact}",
            loops[0].length()
        );
    }
}

#[test]
fn real_body_has_one_torso_loop_at_the_waist_and_two_legs_at_the_knee() {
    let body = real_body();
    let height = body.mesh.height();
    let waist_y = body.landmarks.height(LandmarkKind::Waist);
    let waist_loops = outer_loops(&body.mesh, waist_y, height);
    let torso: Vec<_> = waist_loops
        .iter()
        .filter(|l| l.contains(body.landmarks.torso_at(waist_y).unwrap()))
        .collect();
    assert_eq!(torso.len(), 1);
    let g = torso[0].tape_girth;
    assert!((0.6..=0.9).contains(&g), "waist girth {g}");
    let waist_ring = body.rings.iter().find(|r| r.name == "waist").unwrap();
    assert!((waist_ring.tape_girth - g).abs() < 1e-9);
    // Whatever else the knee plane cuts (hands hang lower on some bodies), two loops hold
    // the two leg axes, one on each side of the body's middle.
    let knee_y = body.landmarks.height(LandmarkKind::Knee);
    let knee_loops = outer_loops(&body.mesh, knee_y, height);
    let (l, r) = body.landmarks.legs_at(knee_y).unwrap();
    let left = knee_loops.iter().position(|lp| lp.contains(l)).expect("left leg");
    let right = knee_loops.iter().position(|lp| lp.contains(r)).expect("right leg");
    assert_ne!(left, right);
    assert!(knee_loops[left].centroid.x > body.landmarks.mid_x && knee_loops[right].centroid.x < body.landmarks.mid_x);
    for i in [left, right] {
        assert!(
            (0.25..=0.5).contains(&knee_loops[i].tape_girth),
            "knee girth {}",
            knee_loops[i].tape_girth
        );
    }
}

#[test]
fn body_sections_agree_with_an_independent_segment_soup() {
    // Independent check of the adjacency walk: sum the lengths of every triangle's own
    // crossing segment, with no chaining at all.
    let body = real_body();
    let mesh = &body.mesh.mesh;
    for y in [0.3, 0.95, 1.25] {
        let walked: f64 = section_mesh(mesh, &body.mesh.adjacency, &Plane::horizontal(y))
            .iter()
            .map(|l| l.length())
            .sum();
        let soup = soup_girth(mesh, y);
        assert!((walked - soup).abs() < 1e-9, "y={y}: walk {walked} soup {soup}");
    }
}

#[test]
fn banded_sections_equal_the_full_scan_on_every_shipped_body() {
    // The body's horizontal sections look only at the triangles of one height band; the
    // plain section scans every triangle. Both must give the same loops bit for bit at
    // any height, through vertices (the ties) and off the body, and the band's loops must
    // measure what an unchained segment soup over all triangles measures.
    use drape::body::{BodyMesh, BodySource};
    for path in super::common::shipped_bodies() {
        let body = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("loads");
        let (lo, hi) = body.mesh.bounds().expect("bounds");
        let mut heights: Vec<f64> = (0..=240).map(|k| lo.y + (hi.y - lo.y) * (k as f64 / 240.0)).collect();
        heights.extend(body.mesh.positions.iter().step_by(97).map(|p| p.y));
        heights.extend([lo.y - 0.1, hi.y + 0.1, f64::NAN]);
        let mut cut = 0;
        for &y in &heights {
            let plane = Plane::horizontal(y);
            let banded = body.section(&plane);
            let full = section_mesh(&body.mesh, &body.adjacency, &plane);
            assert_eq!(banded, full, "{}: y = {y}", path.display());
            if y.is_finite() {
                let walked: f64 = banded.iter().map(|l| l.length()).sum();
                let soup = soup_girth(&body.mesh, y);
                assert!(
                    (walked - soup).abs() < 1e-9,
                    "{}: y = {y}: {walked} vs {soup}",
                    path.display()
                );
            }
            cut += usize::from(!banded.is_empty());
        }
        assert!(cut > 240, "{}: only {cut} heights cut the body", path.display());
        // A tilted plane is not banded: it is cut by the full scan.
        let tilted = Plane::from_point_normal(0.5 * (lo + hi), DVec3::new(0.0, 1.0, 0.3));
        assert_eq!(
            body.section(&tilted),
            section_mesh(&body.mesh, &body.adjacency, &tilted)
        );
        // A body moved after loading (without reindex) is still cut right, the slow way;
        // after reindex, by its new bands.
        let mut moved = body.clone();
        for p in &mut moved.mesh.positions {
            *p = *p * 1.1 + DVec3::new(0.0, 0.25, 0.0);
        }
        let plane = Plane::horizontal(0.5 * (lo.y + hi.y) * 1.1 + 0.25);
        let full = section_mesh(&moved.mesh, &moved.adjacency, &plane);
        assert!(!full.is_empty());
        assert_eq!(moved.section(&plane), full);
        moved.reindex();
        assert_eq!(moved.section(&plane), full);
    }
}
