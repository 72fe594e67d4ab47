//! Nasty geometry: garment points exactly on a body vertex, edge or face, and within 1e-12 m
//! of the skin; coincident and nearly coincident control points; section planes through a
//! body vertex and nearly tangent to the body; zero-length and zero-area elements; a body
//! with a hole under the arm; and the two cases where plain floating point gets an
//! orientation wrong and drape's exact predicates get it right. (The body scaled 1e-3 and
//! 1e3 with matching units is `units.rs`; a zero-area body triangle is in `collision.rs`.)
//!
//! Every verdict is checked against a truth from outside the code under test: the
//! construction itself, the generalized winding number summed over every triangle, a
//! segment soup, or orientation determinants evaluated exactly in integers here.

use std::path::Path;

use drape::body::{Body, BodyMesh, BodySource, LandmarkKind, LandmarkOptions, PartitionOptions, Side};
use drape::collision::{
    BodyIndex, CollisionOptions, DetectState, GarmentMesh, Reach, Search, SliceOptions, collide, ground_truth,
    point_face, quality,
};
use drape::geom::Plane;
use drape::geom::closest::{Feature, closest_on_triangle};
use drape::geom::inside::winding_number;
use drape::geom::ray::ray_triangle;
use drape::geom::section::section_mesh;
use drape::mesh::TriMesh;
use drape::session::{
    GarmentPart, GarmentStage, RunOptions, SinkError, StageInfo, StageSink, parse_session, run_session,
};
use glam::DVec3;

use super::common::{LastGarment, Lcg, real_body, shipped_bodies, soup_girth};

/// Every shipped body, loaded and analysed (landmarks, partitions), with its index.
fn shipped() -> Vec<(String, Body, BodyIndex)> {
    shipped_bodies()
        .into_iter()
        .map(|path| {
            let mesh = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("loads");
            let body =
                Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("analyses");
            let index = BodyIndex::new(&body, &SliceOptions::default());
            (path.display().to_string(), body, index)
        })
        .collect()
}

/// Triangles of `mesh` picked evenly (`n` of them), skipping slivers, so that each body's
/// whole height is sampled.
fn picked(mesh: &TriMesh, n: usize) -> Vec<usize> {
    let step = (mesh.triangles.len() / n).max(1);
    (0..mesh.triangles.len())
        .step_by(step)
        .filter(|&t| {
            let [a, b, c] = mesh.corners(t);
            let e = (b - a).length().min((c - b).length()).min((a - c).length());
            (b - a).cross(c - a).length() > 0.2 * e * e
        })
        .take(n)
        .collect()
}

/// Garment points exactly on a body vertex, on the middle of a body edge and at a face's
/// centroid (on the surface up to the rounding of that mean) are on the skin: not inside
/// by the point-face test, not penetrating by the quality check, at a distance of at most
/// a few ulps; on every shipped body.
#[test]
fn garment_vertices_exactly_on_a_body_vertex_edge_or_face_are_on_the_skin() {
    for (name, body, index) in shipped() {
        let mesh = &body.mesh.mesh;
        let reach = Reach {
            inside: 0.1 * index.height,
            outside: 0.1 * index.height,
            surface: 1e-12 * index.height,
        };
        let mut points = Vec::new();
        for t in picked(mesh, 40) {
            let [a, b, c] = mesh.corners(t);
            points.extend([a, 0.5 * (a + b), (a + b + c) / 3.0]);
        }
        for &p in &points {
            for search in [
                Search::Brute,
                Search::PartitionBvh(index.partition_at(p.y).expect("partition")),
            ] {
                let r = point_face(&index, search, p, &reach);
                let n = r.nearest.expect("on the surface");
                assert!(n.distance <= 1e-15, "{name}: {p} is {} m off", n.distance);
                assert!(!r.inside, "{name}: {p} on the skin called inside ({search:?})");
            }
        }
        let q = quality(&index, &points, &points, &[], &[]);
        assert_eq!(q.penetrating_vertices, 0, "{name}");
        assert!(q.clearance.iter().all(|c| c.abs() <= 1e-15), "{name}");
    }
}

/// Points 2.5e-13 to 1e-12 m either side of a face (along its normal from the centroid):
/// the sign of drape's signed distance is the side the winding number gives (0.5 plus or
/// minus about the offset over the triangle's size, far above the sum's rounding), and its
/// size the offset; the quality check calls them all on the skin (its tolerance is 1e-12
/// of the height). On every shipped body.
#[test]
fn points_within_1e_12_m_of_the_skin_get_the_side_the_winding_number_gives() {
    for (name, body, index) in shipped() {
        let mesh = &body.mesh.mesh;
        let mut points = Vec::new();
        let mut truth = Vec::new();
        for t in picked(mesh, 12) {
            let [a, b, c] = mesh.corners(t);
            let n = (b - a).cross(c - a).normalize();
            let centroid = (a + b + c) / 3.0;
            for offset in [-1e-12, -5e-13, -2.5e-13, 2.5e-13, 5e-13, 1e-12] {
                let p = centroid + n * offset;
                let w = winding_number(mesh, p);
                assert!(
                    (w - 0.5).abs() > 1e-12,
                    "{name}: winding {w} too near one half to decide"
                );
                points.push(p);
                truth.push((w > 0.5, offset));
            }
        }
        for (p, (inside, offset)) in points.iter().zip(&truth) {
            let s = index.signed_distance(*p, 0.1).expect("near");
            assert_eq!(s < 0.0, *inside, "{name}: {p} offset {offset}: signed {s}");
            assert!((s.abs() - offset.abs()).abs() < 2e-15, "{name}: |{s}| against {offset}");
        }
        let q = quality(&index, &points, &points, &[], &[]);
        assert_eq!(q.penetrating_vertices, 0, "{name}: within the surface tolerance");
    }
}

/// Exact orientation of `d` against the plane `a b c`, in integers: the sign of
/// det[b - a, c - a, d - a] (positive: on the side the normal (b - a) x (c - a) points
/// to). `a b c` must lie on the grid of spacing `1 / plane_scale`, `d` on that of
/// `1 / point_scale` (a multiple of it); every product is checked for overflow.
fn exact_side(a: DVec3, b: DVec3, c: DVec3, d: DVec3, plane_scale: f64, point_scale: f64) -> i32 {
    let int = |p: DVec3, scale: f64| {
        let q = p * scale;
        assert!(
            q.round() == q && q.abs().max_element() < 2f64.powi(62),
            "{p} is not on the grid"
        );
        [q.x as i128, q.y as i128, q.z as i128]
    };
    let diff = |x: [i128; 3], y: [i128; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let (ia, ib, ic) = (int(a, plane_scale), int(b, plane_scale), int(c, plane_scale));
    let (u, v) = (diff(ib, ia), diff(ic, ia));
    let w = diff(int(d, point_scale), int(a, point_scale));
    let mul = |x: i128, y: i128| x.checked_mul(y).expect("no overflow");
    let cross = [
        mul(u[1], v[2]) - mul(u[2], v[1]),
        mul(u[2], v[0]) - mul(u[0], v[2]),
        mul(u[0], v[1]) - mul(u[1], v[0]),
    ];
    let det = (0..3)
        .map(|k| mul(cross[k], w[k]))
        .try_fold(0i128, i128::checked_add)
        .expect("no overflow");
    det.signum() as i32
}

/// A closed, outward tetrahedron on corners `a b c d` with faces `a b c` and `b a d` sharing
/// the edge `a b`.
fn tetrahedron(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> TriMesh {
    let mut mesh = TriMesh {
        positions: vec![a, b, c, d],
        triangles: vec![[0, 1, 2], [1, 0, 3], [0, 2, 3], [1, 3, 2]],
    };
    if mesh.signed_volume() < 0.0 {
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
    }
    mesh
}

/// Points a few 1e-19 m off a face of a small tetrahedron (corners on a 2^-20 grid, points
/// on a 2^-60 grid, so that the truth is an exact integer determinant): the plain
/// floating-point side test (the foot of the perpendicular, then the sign of the offset
/// along the face normal) gets some of them wrong; drape's signed distance, decided by the
/// exact predicate, gets every one right.
#[test]
fn the_side_of_a_point_a_hair_off_a_face_is_exact_where_plain_floating_point_is_wrong() {
    let mut rng = Lcg(17);
    let grid = |x: f64, bits: i32| (x * 2f64.powi(bits)).round() / 2f64.powi(bits);
    let (mut float_wrong, mut checked) = (0, 0);
    for _ in 0..40 {
        let corner = |rng: &mut Lcg| {
            DVec3::new(
                grid(rng.next() - 0.5, 20),
                grid(rng.next() + 0.5, 20),
                grid(rng.next() - 0.5, 20),
            )
        };
        let (a, b, c, d) = (corner(&mut rng), corner(&mut rng), corner(&mut rng), corner(&mut rng));
        let mesh = tetrahedron(a, b, c, d);
        let Ok(index) = BodyIndex::from_mesh(&mesh) else {
            continue;
        };
        let face = mesh.triangles[0].map(|i| mesh.positions[i as usize]);
        let normal = (face[1] - face[0]).cross(face[2] - face[0]).normalize();
        for _ in 0..50 {
            // A point of the face, rounded to the fine grid: within about 1e-19 m of the plane.
            let (u, v) = (rng.next() * 0.5 + 0.1, rng.next() * 0.3 + 0.05);
            let on = face[0] + (face[1] - face[0]) * u + (face[2] - face[0]) * v;
            let p = DVec3::new(grid(on.x, 60), grid(on.y, 60), grid(on.z, 60));
            let truth = exact_side(face[0], face[1], face[2], p, 2f64.powi(20), 2f64.powi(60));
            if truth == 0 {
                continue;
            }
            let near = index.nearest(p, 1.0).expect("near");
            if near.feature != Feature::Face || near.triangle != 0 {
                continue;
            }
            checked += 1;
            // drape: negative inside, the face's outward normal is (b - a) x (c - a).
            let s = near.signed(p);
            assert_eq!(near.behind, Some(truth < 0), "{p}: exact side {truth}");
            assert_eq!(
                s.is_sign_negative(),
                truth < 0,
                "{p}: drape says {s}, exact side {truth}"
            );
            // Plain floating point: the same foot, the sign of the offset along the normal.
            let (foot, _) = closest_on_triangle(p, face);
            if ((p - foot).dot(normal) < 0.0) != (truth < 0) {
                float_wrong += 1;
            }
        }
    }
    assert!(checked >= 500, "{checked} points checked");
    assert!(
        float_wrong > 0,
        "plain floating point got all {checked} right: the case shows nothing"
    );
    eprintln!("{float_wrong} of {checked} points a hair off a face: plain floating point wrong, drape right");
}

/// A garment edge through a point exactly on the body edge shared by two triangles
/// (found by a search over random dyadic tetrahedra): the rounded Möller-Trumbore test
/// misses both triangles, letting the edge through the crack; drape's exact test finds
/// the crossing, and so does the brute-force truth. The truth is checked here in integers:
/// the ends lie strictly either side of the face's plane and the crossing point is on its
/// closed edge.
#[test]
fn an_edge_through_a_shared_body_edge_is_found_where_plain_floating_point_lets_it_through() {
    let a = DVec3::new(0.01802825927734375, 1.227081298828125, 0.41988086700439453);
    let b = DVec3::new(0.25834083557128906, 0.7166643142700195, 0.060050010681152344);
    let c = DVec3::new(-0.1505107879638672, 0.5127344131469727, -0.018610000610351563);
    let d = DVec3::new(-0.2928037643432617, 0.8248825073242188, 0.30541229248046875);
    let p = DVec3::new(0.05347063019871712, 1.1533677820116282, 0.35603227093815804);
    let q = DVec3::new(0.05862228944897652, 1.1392956916242838, 0.3698767311871052);
    // Truth, exactly: p and q strictly on either side of the plane a b c, and the line p q
    // passes through the closed triangle (it turns the same way about each edge, or not).
    let scale = 2f64.powi(30);
    let sides = (
        exact_side(a, b, c, p, scale, scale),
        exact_side(a, b, c, q, scale, scale),
    );
    assert!(sides.0 * sides.1 == -1, "{sides:?}");
    let turns = [
        exact_side(p, q, a, b, scale, scale),
        exact_side(p, q, b, c, scale, scale),
        exact_side(p, q, c, a, scale, scale),
    ];
    assert!(
        turns.iter().all(|&s| s >= 0) || turns.iter().all(|&s| s <= 0),
        "{turns:?}"
    );
    assert!(turns.contains(&0), "through the edge itself: {turns:?}");
    // Plain floating point lets the edge through both triangles.
    for tri in [[a, b, c], [b, a, d]] {
        assert_eq!(
            ray_triangle(p, q - p, tri, 0.0, 1.0),
            None,
            "Möller-Trumbore found it after all"
        );
    }
    // drape finds the crossing, in the index and in the ground truth.
    let mesh = tetrahedron(a, b, c, d);
    let index = BodyIndex::from_mesh(&mesh).expect("closed");
    assert!(index.segment_hits(p, q));
    let truth = ground_truth(&mesh, &[p, q], &[[0, 1]]);
    assert_eq!(truth.crossing, vec![true]);
    let quality = quality(&index, &[p, q], &[p, q], &[[0, 1]], &[]);
    assert_eq!(quality.crossing_edges, 1);

    // The same over random cases: two dyadic triangles sharing the edge a b, a segment
    // through a point exactly on it, at up to about 20 degrees from the first face's normal.
    let mut rng = Lcg(12345);
    let grid = |x: f64, bits: i32| (x * 2f64.powi(bits)).round() / 2f64.powi(bits);
    let (mut cases, mut leaks) = (0, 0);
    while cases < 5000 {
        let mut corner = || {
            DVec3::new(
                grid(rng.next() - 0.5, 20),
                grid(rng.next() + 0.5, 20),
                grid(rng.next() - 0.5, 20),
            )
        };
        let (a, b, c, d) = (corner(), corner(), corner(), corner());
        let m = a + (b - a) * grid(rng.next(), 10);
        let n = (b - a).cross(c - a).normalize_or_zero();
        let jitter = DVec3::new(rng.next(), rng.next(), rng.next()) - 0.5;
        let dir = (n * 0.01 + jitter * 0.004) * 64.0;
        let dir = DVec3::new(grid(dir.x, 20), grid(dir.y, 20), grid(dir.z, 20)) / 64.0;
        let (p, q) = (m + dir, m - dir);
        if p - dir != m || q + dir != m {
            continue;
        }
        // Truth in integers: the ends strictly either side of a b c, the line through the
        // closed triangle.
        let sides = exact_side(a, b, c, p, scale, scale) * exact_side(a, b, c, q, scale, scale);
        let turns = [
            exact_side(p, q, a, b, scale, scale),
            exact_side(p, q, b, c, scale, scale),
            exact_side(p, q, c, a, scale, scale),
        ];
        if sides != -1 || !(turns.iter().all(|&s| s >= 0) || turns.iter().all(|&s| s <= 0)) {
            continue;
        }
        cases += 1;
        let mesh = tetrahedron(a, b, c, d);
        let Ok(index) = BodyIndex::from_mesh(&mesh) else {
            continue;
        };
        assert!(index.segment_hits(p, q), "{a} {b} {c} {d}: {p} -> {q}");
        if [[a, b, c], [b, a, d]]
            .iter()
            .all(|&t| ray_triangle(p, q - p, t, 0.0, 1.0).is_none())
        {
            leaks += 1;
        }
    }
    assert!(leaks > 0);
    eprintln!(
        "{leaks} of {cases} segments through a shared edge: plain floating point lets them through, drape finds them"
    );
}

/// Keeps the control points of the named ring after each curves stage.
#[derive(Default)]
struct Anchors(Vec<(String, DVec3)>);

impl StageSink for Anchors {
    fn garment(&mut self, _: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        if let GarmentStage::Part(fw, GarmentPart::Curves) = stage {
            self.0 = fw
                .rings
                .iter()
                .filter(|r| r.name == "waist")
                .flat_map(|r| r.anchors.iter().map(|a| (format!("waist.{}", a.name), a.point)))
                .collect();
        }
        Ok(())
    }
}

/// Dragging a waist control point exactly onto another and to 1e-12 m and 1e-9 m of it
/// (coincident and nearly coincident control points): no panic and no NaN; either the edit
/// is refused with a message naming the curve, or the garment it leaves is clear of the
/// body by the brute-force truth.
#[test]
fn coincident_and_nearly_coincident_control_points_are_refused_or_kept_clear() {
    let head = "drape 1\ngarment jumpsuit resolution=4\n";
    let mut anchors = Anchors::default();
    let session = parse_session(head, "anchors.drape", Path::new(".")).expect("parses");
    run_session(&session, &RunOptions::default(), &mut [&mut anchors]);
    assert!(anchors.0.len() >= 4, "{:?}", anchors.0);
    let (moved, _) = &anchors.0[0];
    let (_, onto) = anchors.0[1];
    let body = real_body();
    for off in [0.0, 1e-12, 1e-9] {
        let to = onto + DVec3::new(off, 0.0, 0.0);
        let text = format!("{head}drag {moved} to={},{},{}\n", to.x, to.y, to.z);
        let outcome = drape::stress::run_one(&text, None, false);
        assert!(
            outcome.panic.is_none() && outcome.non_finite.is_empty(),
            "{off}: {outcome:?}"
        );
        assert!(outcome.guarantee_failures.is_empty(), "{off}: {outcome:?}");
        let session = parse_session(&text, "nasty.drape", Path::new(".")).expect("parses");
        let report = run_session(&session, &RunOptions::default(), &mut []);
        assert!(report.error.is_none(), "{off}: {:?}", report.error);
        if let Some((_, drape::session::Shortfall::Refused(message))) = report.shortfalls.first() {
            assert!(message.contains("waist"), "{off}: {message}");
            continue;
        }
        let mut last = LastGarment::default();
        run_session(&session, &RunOptions::default(), &mut [&mut last]);
        let (positions, edges, triangles) = last.0.expect("a collided garment");
        let truth = ground_truth(&body.mesh.mesh, &positions, &edges);
        assert_eq!((truth.inside_count(), truth.crossing_count()), (0, 0), "{off}");
        let pierced = super::common::faces_pierced_by(&body.mesh.mesh, &positions, &triangles);
        assert!(pierced.is_empty(), "{off}: faces pierced {pierced:?}");
    }
}

/// Section planes exactly through body vertices, and nearly tangent to the body (1e-12 m
/// and 1e-9 m below the crown, 1e-12 m above the soles, exactly at both): every loop is
/// closed and finite, and the girth equals the segment soup's; on every shipped body.
#[test]
fn section_planes_through_a_body_vertex_or_nearly_tangent_give_closed_loops_of_the_true_girth() {
    for path in shipped_bodies() {
        let mesh = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("loads");
        let (lo, hi) = mesh.mesh.bounds().expect("bounds");
        let name = path.display();
        let mut heights: Vec<f64> = (0..8)
            .map(|k| mesh.mesh.positions[k * mesh.mesh.positions.len() / 8].y)
            .collect();
        heights.extend([hi.y, hi.y - 1e-12, hi.y - 1e-9, lo.y, lo.y + 1e-12]);
        for y in heights {
            let loops = section_mesh(&mesh.mesh, &mesh.adjacency, &Plane::horizontal(y));
            assert!(
                loops.iter().all(|l| l.closed && l.points.iter().all(|p| p.is_finite())),
                "{name} y={y}"
            );
            let walked: f64 = loops.iter().map(|l| l.length()).sum();
            let soup = soup_girth(&mesh.mesh, y);
            assert!((walked - soup).abs() < 1e-9, "{name} y={y}: walk {walked} soup {soup}");
        }
    }
}

/// A garment with a zero-length edge (two vertices at one point) and a zero-area face,
/// partly inside the body: the collision handles it with no NaN, and afterwards nothing is
/// inside or crossing by the brute-force truth.
#[test]
fn zero_length_edges_and_zero_area_faces_in_the_garment_break_nothing() {
    let body = real_body();
    let index = BodyIndex::new(body, &SliceOptions::default());
    let mut g = GarmentMesh::from_framework(super::common::real_jumpsuit(), index.height);
    // The ends of an edge moved onto one point (the edge has zero length, the faces at it
    // zero area), 5 mm inside the body.
    let [i, j] = g.edges[g.edges.len() / 2].map(|v| v as usize);
    let near = index.nearest(g.mesh.positions[i], 1.0).expect("near the body");
    let out = (g.mesh.positions[i] - near.foot).normalize();
    let at = near.foot - out * 0.005;
    g.mesh.positions[i] = at;
    g.mesh.positions[j] = at;
    g.normals = g.mesh.vertex_normals();
    assert!(g.normals.iter().all(|n| n.is_finite()));
    let before = ground_truth(&body.mesh.mesh, &g.mesh.positions, &g.edges);
    assert!(before.inside[i] && before.inside[j], "planted inside");
    let c = collide(
        &index,
        &g,
        0.005,
        &CollisionOptions::default(),
        &mut DetectState::default(),
    );
    assert!(c.mesh.positions.iter().all(|p| p.is_finite()));
    let after = ground_truth(&body.mesh.mesh, &c.mesh.positions, &g.edges);
    assert_eq!((after.inside_count(), after.crossing_count()), (0, 0));
}

/// A body with a hole under the arm (the eight triangles nearest the torso's side just
/// below the left armpit removed): it loads with the hole's boundary counted here, is
/// closed again by the fill with about its volume, analyses, and tells inside from outside
/// as the closed body's winding number does at points around the armpit farther off the
/// skin than twice the fill's sag (and 1 mm), up to 2 cm; on every shipped body.
#[test]
fn a_body_with_a_hole_under_the_arm_is_closed_and_keeps_its_inside() {
    for (name, body, closed) in shipped() {
        // Under the left arm: from the armpit landmark (on the torso's centre line), 1 cm
        // lower, straight out to the left until the skin.
        let centre = DVec3::from(
            body.landmarks
                .get(LandmarkKind::Armpit, Side::Centre)
                .expect("armpit")
                .point,
        ) - DVec3::Y * 0.01;
        let (t, _) = closed.cast_ray(centre, DVec3::X, 0.0, 1.0).expect("the torso's side");
        let armpit = centre + DVec3::X * t;
        let mesh = &body.mesh.mesh;
        // The hole: the eight triangles whose centroids lie nearest that point.
        let mut by_distance: Vec<(f64, usize)> = (0..mesh.triangles.len())
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                (((a + b + c) / 3.0).distance(armpit), t)
            })
            .collect();
        by_distance.sort_by(|x, y| x.0.total_cmp(&y.0));
        let hole: std::collections::BTreeSet<usize> = by_distance[..8].iter().map(|&(_, t)| t).collect();
        let area: f64 = hole.iter().map(|&t| 0.5 * mesh.scaled_normal(t).length()).sum();
        let kept: Vec<[u32; 3]> = (0..mesh.triangles.len())
            .filter(|t| !hole.contains(t))
            .map(|t| mesh.triangles[t])
            .collect();
        // The hole's rim: edges of the kept triangles used by one kept triangle.
        let mut edges: Vec<(u32, u32)> = kept
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
            .collect();
        edges.sort_unstable();
        let rim = edges.chunk_by(|x, y| x == y).filter(|run| run.len() == 1).count();
        let mut obj = String::new();
        for p in &mesh.positions {
            obj.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
        }
        for t in &kept {
            obj.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
        }
        let holed = BodyMesh::from_obj_text(&obj, "holed.obj", 1.0).expect("loads");
        assert_eq!(holed.report.boundary_edges, rim, "{name}");
        // Closed again (a rim that pinches at a vertex is closed as two loops), enclosing
        // the body's volume up to a cap over the hole no deeper than its width.
        assert!(holed.report.holes_filled >= 1, "{name}");
        assert_eq!(
            drape::mesh::Adjacency::try_new(&holed.mesh)
                .expect("manifold")
                .boundary_edges,
            0
        );
        let dv = (holed.mesh.signed_volume() - mesh.signed_volume()).abs();
        assert!(
            dv < area * area.sqrt(),
            "{name}: volume changed by {dv} m3 over a hole of {area} m2"
        );
        // How far the fill strays from the skin it replaces.
        let sag = holed.mesh.triangles[kept.len()..]
            .iter()
            .flat_map(|t| {
                let [a, b, c] = t.map(|i| holed.mesh.positions[i as usize]);
                [a, b, c, (a + b + c) / 3.0]
            })
            .map(|p| closed.signed_distance(p, 0.5).map_or(0.0, f64::abs))
            .fold(0.0, f64::max);
        let holed = Body::analyse(holed, &LandmarkOptions::default(), &PartitionOptions::default()).expect("analyses");
        let index = BodyIndex::new(&holed, &SliceOptions::default());
        let mut rng = Lcg(5);
        let mut checked = 0;
        for _ in 0..400 {
            let p = armpit + (DVec3::new(rng.next(), rng.next(), rng.next()) - 0.5) * 0.08;
            let w = winding_number(mesh, p);
            let Some(s) = index.signed_distance(p, 0.5) else {
                continue;
            };
            let clear = closed.signed_distance(p, 0.5).map_or(0.0, f64::abs);
            if !(2.0 * sag + 0.001..0.02).contains(&clear) {
                continue;
            }
            checked += 1;
            assert_eq!(s < 0.0, w > 0.5, "{name}: {p} signed {s}, winding {w}");
        }
        assert!(checked >= 50, "{name}: {checked} points checked");
    }
}

/// One tolerance for "inside": points at the skin (a body vertex, an edge's middle, a
/// face's centroid) and 1e-7 m either side of a face, with an ease of 0: the quality check
/// and the brute-force truth (winding number, every triangle) agree on every one, the truth
/// here decided in the test (the winding number over one half, and the least distance to a
/// triangle over the stated tolerance, both summed over every triangle); and after the
/// response to the check's inside points, none is inside by the truth. On every shipped
/// body.
#[test]
fn points_at_the_skin_and_a_tenth_of_a_micrometre_off_it_are_judged_alike_and_pushed_out() {
    use drape::collision::SKIN;
    use drape::collision::{Hit, ResponseOptions, respond, response_ease};
    for (name, body, index) in shipped() {
        let mesh = &body.mesh.mesh;
        let skin = SKIN * body.mesh.height();
        let mut points = Vec::new();
        for t in picked(mesh, 8) {
            let [a, b, c] = mesh.corners(t);
            let n = (b - a).cross(c - a).normalize();
            let centroid = (a + b + c) / 3.0;
            points.extend([a, (a + b) / 2.0, centroid]);
            points.extend([-1e-7, 1e-7].map(|o| centroid + n * o));
        }
        // The truth, written here.
        let truth_inside = |p: DVec3| {
            let nearest = (0..mesh.triangles.len())
                .map(|t| super::common::triangle_distance(p, mesh.corners(t)))
                .fold(f64::INFINITY, f64::min);
            winding_number(mesh, p) > 0.5 && nearest > skin
        };
        let truth: Vec<bool> = points.iter().map(|&p| truth_inside(p)).collect();
        let q = quality(&index, &points, &points, &[], &[]);
        let checked: Vec<bool> = (0..points.len() as u32).map(|v| q.inside.contains(&v)).collect();
        assert_eq!(checked, truth, "{name}: the check and the truth disagree");
        assert_eq!(
            truth.iter().filter(|i| **i).count(),
            8,
            "{name}: one point inside a face each"
        );
        // The response with an ease of 0 (its least gap) takes every inside point out.
        let hits: Vec<Hit> = q
            .inside
            .iter()
            .map(|&v| {
                let p = points[v as usize];
                let near = index.nearest(p, 0.1).expect("near");
                Hit {
                    vertex: v,
                    partition: index.partition_at(p.y).unwrap_or(0),
                    method: drape::body::DetectionMethod::PointFace,
                    depth: -near.signed(p),
                    foot: near.foot,
                    normal: near.normal,
                    triangle: Some(near.triangle),
                }
            })
            .collect();
        let normals: Vec<DVec3> = hits.iter().fold(vec![DVec3::ZERO; points.len()], |mut n, h| {
            n[h.vertex as usize] = h.normal;
            n
        });
        let plain = super::common::PlainRoles::new(points.len());
        let roles = plain.with(&normals);
        let options = ResponseOptions::default();
        let ease = response_ease(&index, 0.0, &options);
        let (after, _) = respond(&index, &points, &hits, &roles, ease, &options);
        for h in &hits {
            let p = after[h.vertex as usize];
            assert!(
                !truth_inside(p),
                "{name}: point {} still inside after the response",
                h.vertex
            );
        }
    }
}

/// The way out of a point on the skin is the surface's normal, not an axis the rounding of
/// its foot happens to point along: at a triangle's centroid (its nearest point a rounding
/// away, 1e-17 m or so), and 1e-15 m off it, the way out is the triangle's own normal,
/// computed here from its corners; 1 um off it, where the way from the foot is a direction,
/// the same. On every shipped body, 200 triangles each.
#[test]
fn the_way_out_of_a_point_on_the_skin_is_the_skins_normal() {
    for (name, body, index) in shipped() {
        let mesh = &body.mesh.mesh;
        let mut checked = 0;
        for t in picked(mesh, 200) {
            let [a, b, c] = mesh.corners(t);
            let normal = (b - a).cross(c - a).normalize();
            let centroid = (a + b + c) / 3.0;
            for offset in [0.0, 1e-15, 1e-6] {
                let p = centroid + normal * offset;
                let Some(near) = index.nearest(p, 0.01) else {
                    continue;
                };
                // Only where this triangle is the nearest (another part of a self-crossing
                // body may be nearer).
                if near.triangle as usize != t {
                    continue;
                }
                let way = near.way_out(p, index.resolved());
                assert!(
                    way.dot(normal) > 1.0 - 1e-9,
                    "{name}: triangle {t}, {offset} m off: way out {way} against the normal {normal}"
                );
                checked += 1;
            }
        }
        assert!(checked >= 300, "{name}: only {checked} points checked");
    }
}
