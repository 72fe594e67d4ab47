//! The garment framework on the real body: girths against their targets measured on M0
//! itself, welding against a brute-force pair count, M0's topology (manifold, oriented,
//! five boundary loops, fixed over random dimension sets), and no M0 vertex inside the body
//! by the brute-force winding number.

use std::collections::BTreeMap;

use drape::garment::{Dimensions, Fit, FrameworkOptions, TemplateKind, build_framework, weld};
use drape::geom::inside::winding_number;
use drape::mesh::Adjacency;
use glam::DVec3;

use super::common::{Lcg, real_body, real_jumpsuit, real_probe};

/// Perimeter of the M0 vertices lying exactly in the horizontal plane `y` on one side of
/// `x = split` (`side` -1, 0 for all, +1), ordered by angle about their centroid.
fn m0_row_perimeter(positions: &[DVec3], y: f64, side: i32) -> (f64, usize) {
    let mut row: Vec<DVec3> = positions
        .iter()
        .filter(|p| (p.y - y).abs() < 1e-12 && (side == 0 || (p.x > 0.0) == (side > 0)))
        .copied()
        .collect();
    let c = row.iter().sum::<DVec3>() / row.len().max(1) as f64;
    row.sort_by(|a, b| (a.x - c.x).atan2(a.z - c.z).total_cmp(&(b.x - c.x).atan2(b.z - c.z)));
    let n = row.len();
    ((0..n).map(|i| row[i].distance(row[(i + 1) % n])).sum(), n)
}

#[test]
fn every_ring_girth_matches_its_target_measured_on_m0() {
    let body = real_body();
    let base = real_jumpsuit();
    let mut rng = Lcg(7);
    let mut dims = Dimensions::default();
    // Each horizontal ring gets a target 0-8 cm above its default girth.
    for r in &base.rings {
        if r.name != "neckline" {
            dims.values
                .insert(format!("{}_girth", r.name), r.girth + 0.08 * rng.next());
        }
    }
    let fw = build_framework(
        body,
        real_probe(),
        TemplateKind::Jumpsuit,
        &dims,
        &FrameworkOptions::default(),
    )
    .unwrap();
    let mut worst: f64 = 0.0;
    for r in fw.rings.iter().filter(|r| r.name != "neckline") {
        let target = dims.values[&format!("{}_girth", r.name)];
        assert!(
            ((r.girth - target) / target).abs() < 1e-8,
            "{}: spline girth {} vs {target}",
            r.name,
            r.girth
        );
        // Independent: the polygon of M0's own vertices on that ring.
        let side = if r.name.starts_with("left") {
            1
        } else if r.name.starts_with("right") {
            -1
        } else {
            0
        };
        let (perimeter, count) = m0_row_perimeter(&fw.m0.mesh.positions, r.plane.offset, side);
        let expected = if side == 0 { 48 } else { 24 };
        assert_eq!(count, expected, "{}: M0 vertices on the ring", r.name);
        let error = (perimeter - target) / target;
        worst = worst.max(error.abs());
        assert!(
            error.abs() < 0.005,
            "{}: M0 ring perimeter {perimeter:.5} vs target {target:.5} ({error:+.4})",
            r.name
        );
        // A polygon inscribed in the convex ring is never longer than it.
        assert!(perimeter <= r.girth * (1.0 + 1e-9), "{}", r.name);
    }
    assert!(worst > 0.0);
}

#[test]
fn a_girth_below_the_body_is_refused_with_the_ring_named() {
    let mut dims = Dimensions::default();
    dims.values.insert("waist_girth".into(), 0.5);
    let e = build_framework(
        real_body(),
        real_probe(),
        TemplateKind::Jumpsuit,
        &dims,
        &FrameworkOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("ring 'waist': girth 0.5000 m is less than"), "{e}");
}

#[test]
fn welding_merges_exactly_the_pairs_within_the_threshold() {
    let mut rng = Lcg(11);
    let threshold = 1e-6;
    // Well-separated base points (a jittered 3D lattice, spacing 1 cm).
    let mut points: Vec<DVec3> = (0..400)
        .map(|i| {
            DVec3::new((i % 8) as f64, ((i / 8) % 8) as f64, (i / 64) as f64) * 0.01
                + DVec3::new(rng.next(), rng.next(), rng.next()) * 1e-3
        })
        .collect();
    // Planted partners: half just inside the threshold, half just outside, a few exact.
    let mut expect_merged = 0;
    for i in 0..120 {
        let dir = DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5).normalize();
        let d = match i % 3 {
            0 => 0.0,
            1 => threshold * (0.5 + 0.49 * rng.next()),
            _ => threshold * (1.01 + rng.next()),
        };
        if d <= threshold {
            expect_merged += 1;
        }
        points.push(points[i] + dir * d);
    }
    let (map, count) = weld(&points, threshold);
    // Brute force: every pair within the threshold shares an index, every other pair does not.
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            let near = points[i].distance(points[j]) <= threshold;
            assert_eq!(
                map[i] == map[j],
                near,
                "pair {i} {j} at {:e}",
                points[i].distance(points[j])
            );
        }
    }
    assert_eq!(count, points.len() - expect_merged);
}

/// Boundary loops of a mesh (chains of edges used by one face).
fn boundary_loops(triangles: &[[u32; 3]]) -> usize {
    let mut count: BTreeMap<(u32, u32), i32> = BTreeMap::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut next: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for (&(a, b), &c) in &count {
        if c == 1 {
            next.entry(a).or_default().push(b);
            next.entry(b).or_default().push(a);
        }
    }
    assert!(
        next.values().all(|v| v.len() == 2),
        "boundary vertices have two boundary edges"
    );
    let mut seen = std::collections::BTreeSet::new();
    let mut loops = 0;
    for &start in next.keys() {
        if !seen.insert(start) {
            continue;
        }
        loops += 1;
        let mut stack = vec![start];
        while let Some(v) = stack.pop() {
            for &w in &next[&v] {
                if seen.insert(w) {
                    stack.push(w);
                }
            }
        }
    }
    loops
}

#[test]
fn m0_is_manifold_consistently_oriented_outward_with_five_openings() {
    let fw = real_jumpsuit();
    let m0 = &fw.m0;
    let adjacency = Adjacency::try_new(&m0.mesh).expect("no edge has more than two faces");
    // Consistent orientation: no directed edge is used twice.
    let mut directed = m0.directed_edges.to_vec();
    directed.sort_unstable();
    let before = directed.len();
    directed.dedup();
    assert_eq!(
        directed.len(),
        before,
        "a directed edge repeats: faces disagree in orientation"
    );
    assert_eq!(
        m0.edges.len(),
        (3 * m0.mesh.triangles.len() + adjacency.boundary_edges) / 2
    );
    // Two armholes, the neckline, two hems.
    assert_eq!(boundary_loops(&m0.mesh.triangles), 5);
    // Outward: seen from inside the body (torso centre at the waist and hip, leg centres at
    // the knees), the open M0 winds positively, nearly once (only its five openings are
    // missing from the full solid angle); flipped faces would give a negative number.
    let lm = &real_body().landmarks;
    let mut centres = Vec::new();
    for kind in [drape::body::LandmarkKind::Waist, drape::body::LandmarkKind::Hip] {
        let y = lm.height(kind);
        let t = lm.torso_at(y).unwrap();
        centres.push(DVec3::new(t.x, y, t.y));
    }
    let knee = lm.height(drape::body::LandmarkKind::Knee);
    let (l, r) = lm.legs_at(knee).unwrap();
    centres.push(DVec3::new(l.x, knee, l.y));
    centres.push(DVec3::new(r.x, knee, r.y));
    for c in centres {
        let w = winding_number(&m0.mesh, c);
        assert!(w > 0.6 && w < 1.0, "winding number {w} at {c}");
    }
    assert_eq!(m0.report.degenerate_faces + m0.report.duplicate_faces, 0);
    // Euler characteristic of a sphere with 5 holes: V - E + F = 2 - 5.
    let chi = m0.mesh.positions.len() as i64 - m0.edges.len() as i64 + m0.mesh.triangles.len() as i64;
    assert_eq!(chi, -3);
}

#[test]
fn topology_is_fixed_over_100_random_dimension_sets_and_nothing_is_nan() {
    let body = real_body();
    let base = real_jumpsuit();
    let h = body.mesh.height();
    let mut rng = Lcg(2026);
    for case in 0..100 {
        let mut dims = Dimensions::default();
        dims.values.insert("ease".into(), h * (0.004 + 0.02 * rng.next()));
        for r in ["bust", "waist", "hip", "left_knee", "right_thigh"] {
            if rng.next() < 0.5 {
                let g = base.ring(r).unwrap().girth;
                dims.values.insert(format!("{r}_girth"), g + 0.1 * rng.next());
            }
        }
        if rng.next() < 0.5 {
            dims.values.insert("left_hem_ease".into(), 0.05 * rng.next());
        }
        let inseam = base.dimension("inseam").unwrap();
        dims.values.insert("inseam".into(), inseam * (0.7 + 0.3 * rng.next()));
        dims.values.insert("strap_position".into(), 0.3 + 0.3 * rng.next());
        dims.values.insert("neck_rise".into(), 0.01 * rng.next());
        let fit = if case % 4 == 3 { Fit::Loose } else { Fit::Tight };
        let fw = build_framework(
            body,
            real_probe(),
            TemplateKind::Jumpsuit,
            &dims,
            &FrameworkOptions::default().with_fit(fit),
        )
        .unwrap_or_else(|e| panic!("case {case}: {e}"));
        assert_eq!(fw.m0.mesh.positions.len(), base.m0.mesh.positions.len(), "case {case}");
        assert_eq!(fw.m0.mesh.triangles, base.m0.mesh.triangles, "case {case}");
        assert_eq!(fw.m0.edges, base.m0.edges, "case {case}");
        assert!(fw.m0.mesh.positions.iter().all(|p| p.is_finite()), "case {case}: NaN");
        assert!(fw.rings.iter().all(|r| r.girth.is_finite()), "case {case}");
    }
}

fn assert_outside(name: &str, positions: &[DVec3]) {
    let body = &real_body().mesh.mesh;
    let inside: Vec<(usize, f64)> = positions
        .iter()
        .enumerate()
        .map(|(i, p)| (i, winding_number(body, *p)))
        .filter(|(_, w)| *w > 0.5)
        .collect();
    assert!(
        inside.is_empty(),
        "{name}: {} vertices inside the body: {:?}",
        inside.len(),
        &inside[..inside.len().min(5)]
    );
}

/// M0 after the mesh-layer collision response.
fn collided(fw: &drape::garment::Framework) -> Vec<DVec3> {
    use drape::collision::{CollisionOptions, DetectState, GarmentMesh, collide};
    let index = real_probe().index();
    let g = GarmentMesh::from_framework(fw, index.height);
    collide(
        index,
        &g,
        fw.ease(),
        &CollisionOptions::default(),
        &mut DetectState::default(),
    )
    .mesh
    .positions
}

#[test]
fn the_initial_jumpsuit_and_dress_have_no_vertex_inside_the_body_after_response() {
    let fw = real_jumpsuit();
    assert_outside("jumpsuit", &collided(fw));
    let dress = build_framework(
        real_body(),
        real_probe(),
        TemplateKind::Dress,
        &Dimensions::default(),
        &FrameworkOptions::default(),
    )
    .unwrap();
    assert_outside("dress", &collided(&dress));
    // The check can fail: the body's own vertices pulled 1 mm inward are all inside.
    let body = &real_body().mesh;
    let normals = body.mesh.vertex_normals();
    let sunk: Vec<DVec3> = body
        .mesh
        .positions
        .iter()
        .zip(&normals)
        .step_by(97)
        .map(|(p, n)| *p - *n * 1e-3)
        .collect();
    assert!(sunk.iter().all(|p| winding_number(&body.mesh, *p) > 0.5));
}

#[test]
fn loose_fit_straightens_the_legs_below_the_thigh_and_keeps_the_thigh() {
    let tight = real_jumpsuit();
    let loose = build_framework(
        real_body(),
        real_probe(),
        TemplateKind::Jumpsuit,
        &Dimensions::default(),
        &FrameworkOptions::default().with_fit(Fit::Loose),
    )
    .unwrap();
    assert_eq!(loose.straightened.len(), 8);
    for s in &loose.straightened {
        // The fixed ring's point (a virtual control point) is unchanged; the others lie on one line.
        assert_eq!(s.before[0], s.after[0]);
        let (a, b) = (s.after[0], s.after[s.after.len() - 1]);
        for p in &s.after[1..s.after.len() - 1] {
            let t = (p.y - a.y) / (b.y - a.y);
            assert!(p.distance(a.lerp(b, t)) < 1e-12, "{}", s.contour);
        }
    }
    for name in ["left_thigh", "right_thigh", "hip", "waist"] {
        assert_eq!(
            loose.ring(name).unwrap().girth,
            tight.ring(name).unwrap().girth,
            "{name}"
        );
    }
    for name in ["left_hem", "left_knee"] {
        assert!(
            loose.ring(name).unwrap().girth > tight.ring(name).unwrap().girth,
            "{name} grows"
        );
    }
}

/// The names a template declares (for checking a session before anything runs) are the
/// names its built framework has: every control point and every curve, every template in
/// every style.
#[test]
fn the_templates_declared_names_are_the_built_frameworks() {
    use drape::garment::{Collar, Sleeves, Style};
    let mut cases: Vec<(TemplateKind, Style)> = vec![(TemplateKind::Dress, Style::default())];
    for kind in [TemplateKind::Jumpsuit, TemplateKind::Shirt] {
        for sleeves in Sleeves::ALL {
            for collar in Collar::ALL {
                cases.push((kind, Style { sleeves, collar }));
            }
        }
    }
    for (kind, style) in cases {
        let fw = build_framework(
            real_body(),
            real_probe(),
            kind,
            &Dimensions::default(),
            &FrameworkOptions::default().with_style(style),
        )
        .expect("builds");
        let spec = drape::garment::template::styled(kind, style);
        let built: Vec<String> = fw.control_points().into_iter().map(|(n, _)| n).collect();
        assert_eq!(spec.point_names(), built, "{kind:?} {style:?} points");
        let curves: Vec<String> = drape::constraint::curves::curve_nodes(&fw)
            .into_iter()
            .map(|c| c.name)
            .collect();
        assert_eq!(spec.curve_names(), curves, "{kind:?} {style:?} curves");
    }
}
