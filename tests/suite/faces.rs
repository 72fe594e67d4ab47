//! Faces the body pokes through: a bump under a large garment triangle whose corners and
//! edges are clear of it. The check must find it, the face rounds lift it off, and the
//! truth comes from the test: every body edge against the face by the test's own segment
//! test, and every body vertex's height over the lifted face's plane.

use drape::collision::faces::{pierced_faces, respond_faces};
use drape::collision::{BodyIndex, ResponseOptions};
use drape::mesh::TriMesh;
use glam::DVec3;

use super::common::{closed_grid, faces_pierced_by, segment_through_triangle};

/// A sphere of radius `r` about the origin, `rings` latitudes of `around` points, its
/// triangles counter-clockwise seen from outside (as a body's are once loaded: the rings
/// run counter-clockwise seen from above).
fn sphere(r: f64, rings: usize, around: usize) -> TriMesh {
    closed_grid(
        rings,
        around,
        |i, j| {
            let lat = std::f64::consts::PI * ((i + 1) as f64 / (rings + 1) as f64 - 0.5);
            let lon = super::common::angle(j, around);
            r * DVec3::new(lat.cos() * lon.cos(), lat.sin(), lat.cos() * lon.sin())
        },
        DVec3::new(0.0, -r, 0.0),
        DVec3::new(0.0, r, 0.0),
    )
}

/// A flat garment triangle at height `y` over the sphere's top, corners `reach` from the
/// axis (counter-clockwise seen from above: its normal points up, away from the sphere).
fn lid(y: f64, reach: f64) -> Vec<DVec3> {
    (0..3)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 3.0;
            DVec3::new(reach * a.cos(), y, -reach * a.sin())
        })
        .collect()
}

/// The bump pokes 4 mm through a triangle of 0.35 m sides whose corners and edges lie
/// far off the sphere: the check finds the face pierced (as the test's own brute force
/// does), the face rounds lift it, and afterwards no body edge passes through it and every
/// body vertex lies below its plane by at least the ease (less the response's tolerance).
#[test]
fn a_bump_under_a_large_triangle_is_found_lifted_and_certified() {
    let r = 0.05;
    let body = sphere(r, 24, 48);
    let index = BodyIndex::from_mesh(&body).expect("a closed sphere");
    let top = body.positions.iter().map(|p| p.y).fold(f64::MIN, f64::max);
    let mut positions = lid(top - 0.004, 0.2);
    let triangles = [[0u32, 1, 2]];
    // The corners and the edges are clear of the sphere (the edges pass 0.1 m from the axis).
    for p in &positions {
        assert!(p.length() > 2.0 * r);
    }
    assert_eq!(
        faces_pierced_by(&body, &positions, &triangles),
        vec![0],
        "the truth sees the bump"
    );
    let free: Vec<f64> = positions.iter().map(|p| p.length() - r).collect();
    assert_eq!(pierced_faces(&index, &positions, &triangles, &free, None), vec![0]);
    let ease = 0.003;
    let normals = vec![DVec3::Y; 3];
    let plain = super::common::PlainRoles::new(3);
    let roles = plain.with(&normals);
    let rounds = respond_faces(
        &index,
        &mut positions,
        (&triangles, &[[0, 1], [1, 2], [0, 2]]),
        vec![0],
        &[0, 0, 0],
        &roles,
        ease,
        &ResponseOptions::default(),
        None,
    );
    assert_eq!(rounds.first, vec![0]);
    assert!(!rounds.lifts.is_empty(), "nothing lifted");
    // Certified by the test's truths: no body edge through the face, every body vertex
    // under its plane by the ease.
    assert!(faces_pierced_by(&body, &positions, &triangles).is_empty());
    assert!(pierced_faces(&index, &positions, &triangles, &[0.0; 3], None).is_empty());
    let [a, b, c] = [0, 1, 2].map(|k| positions[k]);
    let n = (b - a).cross(c - a).normalize();
    assert!(n.y > 0.0, "the face turned over");
    let highest = body.positions.iter().map(|&p| (p - a).dot(n)).fold(f64::MIN, f64::max);
    assert!(
        highest <= -(1.0 - 0.05) * ease,
        "the bump stands {highest} m over the face"
    );
}

/// Faces the body does not reach, faces it passes through at a corner's ball (covered) and
/// faces beside it: the check agrees with the brute force on a sheet of small faces laid
/// over the sphere at heights from below its top to above it.
#[test]
fn the_check_agrees_with_the_brute_force_over_a_sheet() {
    let r = 0.05;
    let body = sphere(r, 16, 32);
    let index = BodyIndex::from_mesh(&body).expect("a closed sphere");
    for k in 0..12 {
        let y = r - 0.012 + 0.002 * k as f64;
        let n = 9;
        let step = 0.16 / n as f64;
        let mut positions = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                positions.push(DVec3::new(
                    -0.08 + step * i as f64,
                    y + 0.0003 * j as f64,
                    -0.08 + step * j as f64,
                ));
            }
        }
        let id = |i: usize, j: usize| (i * (n + 1) + j) as u32;
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..n {
                triangles.push([id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i + 1, j)]);
            }
        }
        let free: Vec<f64> = positions
            .iter()
            .map(|&p| index.signed_distance(p, 1.0).map_or(0.0, f64::abs))
            .collect();
        let found: Vec<usize> = pierced_faces(&index, &positions, &triangles, &free, None)
            .into_iter()
            .map(|f| f as usize)
            .collect();
        assert_eq!(
            found,
            faces_pierced_by(&body, &positions, &triangles),
            "sheet at y = {y}"
        );
    }
}

/// The test's own segment test: through the inside, past the triangle, ending on it.
#[test]
fn the_segment_test_of_the_tests() {
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    assert!(segment_through_triangle(
        DVec3::new(0.2, 0.2, 1.0),
        DVec3::new(0.2, 0.2, -1.0),
        t
    ));
    assert!(!segment_through_triangle(
        DVec3::new(0.8, 0.8, 1.0),
        DVec3::new(0.8, 0.8, -1.0),
        t
    ));
    assert!(!segment_through_triangle(
        DVec3::new(0.2, 0.2, 1.0),
        DVec3::new(0.2, 0.2, 0.5),
        t
    ));
}

/// Faces squeezed in the crotch of the two old bodies, where the thighs meet (a slot a few
/// millimetres wide) or a pubic ridge crosses a face of the crotch web: random sessions
/// whose `set ease` the face rounds could not clear when they only lifted faces off along
/// their normal, from the side the corners' ways out pointed (tests/fixtures/squeeze/,
/// found by `drape stress --bodies assets/bodies --sessions 100`). Now no step is refused
/// as "cannot be kept clear", and every garment a collision ends with is clear by the
/// test's truths: no vertex inside (winding number), no edge through a body triangle and
/// no body edge through a face (the test's own segment test, every body edge).
#[test]
fn faces_squeezed_in_the_crotch_are_cleared_by_the_face_rounds() {
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir("tests/fixtures/squeeze")
        .expect("tests/fixtures/squeeze")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "drape"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 4);
    for file in files {
        let text = std::fs::read_to_string(&file).expect("reads");
        let session =
            drape::session::parse_session(&text, &file.display().to_string(), file.parent().unwrap()).expect("parses");
        let body = drape::body::BodyMesh::load(&session.scene.body, session.scene.units.scale()).expect("the body");
        let mut every = super::common::EveryGarment::default();
        let report = drape::session::run_session(&session, &drape::session::RunOptions::default(), &mut [&mut every]);
        assert!(report.error.is_none(), "{}: {:?}", file.display(), report.error);
        for step in &report.steps {
            let refused = step.figures.get("refused").and_then(|r| r.as_str()).unwrap_or("");
            assert!(
                !refused.contains("kept clear"),
                "{} step {}: {refused}",
                file.display(),
                step.step
            );
        }
        assert!(every.0.len() >= 6, "{}: {} collisions", file.display(), every.0.len());
        for (k, (positions, edges, triangles)) in every.0.iter().enumerate() {
            let truth = drape::collision::ground_truth(&body.mesh, positions, edges);
            assert_eq!(truth.inside_count(), 0, "{} collision {k}", file.display());
            assert!(truth.crossing.iter().all(|c| !c), "{} collision {k}", file.display());
            let pierced = faces_pierced_by(&body.mesh, positions, triangles);
            assert!(
                pierced.is_empty(),
                "{} collision {k}: faces pierced {pierced:?}",
                file.display()
            );
        }
    }
}

/// The test's sphere faces outwards: every triangle's normal points away from the centre.
#[test]
fn the_test_sphere_faces_outwards() {
    let s = sphere(0.05, 16, 32);
    for t in &s.triangles {
        let [a, b, c] = t.map(|v| s.positions[v as usize]);
        assert!((b - a).cross(c - a).dot(a + b + c) > 0.0, "{t:?} faces inwards");
    }
}
