//! Mesh-layer collision on the real body: detection against the brute-force ground truth,
//! response directions by rule, zero penetrations after response, skipping that changes
//! nothing, and degenerate input.

use std::collections::BTreeSet;

use drape::body::DetectionMethod;
use drape::collision::{
    Acceleration, AppliedRule, BodyIndex, CollisionOptions, DetectOptions, DetectState, GarmentMesh, Reach, Search,
    collide, compare, detect, ground_truth, point_face, quality,
};
use drape::garment::{Dimensions, FrameworkOptions, TemplateKind, build_framework};
use drape::mesh::TriMesh;
use drape::session::{
    CollisionPart, CollisionStage, RunOptions, SinkError, StageInfo, StageSink, parse_session, run_session,
};
use glam::DVec3;

use super::common::{Lcg, brute_distance, inside_by_parity, ray_hit, real_body, real_jumpsuit, real_probe};

fn index() -> &'static BodyIndex {
    real_probe().index()
}

/// The default jumpsuit's M0 with every vertex pushed along its normal by a random amount
/// in `[-in_m, out_m]` (negative: into the body).
fn perturbed(seed: u64, in_m: f64, out_m: f64) -> GarmentMesh {
    let mut g = GarmentMesh::from_framework(real_jumpsuit(), index().height);
    let mut rng = Lcg(seed);
    for (p, n) in g.mesh.positions.iter_mut().zip(&g.normals) {
        *p += *n * (rng.next() * (in_m + out_m) - in_m);
    }
    g.normals = g.mesh.vertex_normals();
    g
}

fn hit_set(d: &drape::collision::Detection) -> BTreeSet<u32> {
    d.hits.iter().map(|h| h.vertex).collect()
}

#[test]
fn point_face_detection_matches_the_brute_force_truth_on_perturbed_garments() {
    let g = perturbed(11, 0.04, 0.02);
    let truth = ground_truth(&real_body().mesh.mesh, &g.mesh.positions, &[]);
    let inside: BTreeSet<u32> = (0..truth.inside.len() as u32)
        .filter(|&v| truth.inside[v as usize])
        .collect();
    assert!(
        inside.len() > 300,
        "the perturbation must push many vertices in: {}",
        inside.len()
    );
    let mut results = Vec::new();
    for acceleration in [
        Acceleration::BruteForce,
        Acceleration::Partitioned,
        Acceleration::PartitionedBvh,
    ] {
        let options = DetectOptions::default()
            .with_acceleration(acceleration)
            .with_method(Some(DetectionMethod::PointFace));
        let d = detect(index(), &g.input(), &options, &mut DetectState::default());
        let found = hit_set(&d);
        let missed = inside.difference(&found).count();
        let false_hits = found.difference(&inside).count();
        assert_eq!((missed, false_hits), (0, 0), "{acceleration:?}");
        results.push(d.hits);
    }
    // The three searches find the same nearest points, bit for bit.
    assert_eq!(results[0], results[1]);
    assert_eq!(results[1], results[2]);
}

#[test]
fn line_line_misses_are_reported_and_bounded() {
    let g = perturbed(12, 0.03, 0.02);
    let truth = ground_truth(&real_body().mesh.mesh, &g.mesh.positions, &[]);
    let d = detect(
        index(),
        &g.input(),
        &DetectOptions::default(),
        &mut DetectState::default(),
    );
    let found = hit_set(&d);
    let exact = detect(
        index(),
        &g.input(),
        &DetectOptions::default().with_method(Some(DetectionMethod::PointFace)),
        &mut DetectState::default(),
    );
    let line: Vec<usize> = (0..g.mesh.positions.len())
        .filter(|&v| d.methods[v] == Some(DetectionMethod::LineLine))
        .collect();
    assert!(
        line.len() > 1000,
        "legs and abdomen are tested line-line: {}",
        line.len()
    );
    let inside_line = line.iter().filter(|&&v| truth.inside[v]).count();
    let missed: Vec<usize> = line
        .iter()
        .copied()
        .filter(|&v| truth.inside[v] && !found.contains(&(v as u32)))
        .collect();
    let false_hits = line
        .iter()
        .filter(|&&v| !truth.inside[v] && found.contains(&(v as u32)))
        .count();
    // Every miss and false hit lies near the skin: its exact depth is at most the slice
    // spacing's worth of surface change plus a little (the paper's bound is a quarter of
    // a ring edge).
    let depth_of = |v: usize| {
        exact
            .hits
            .iter()
            .find(|h| h.vertex as usize == v)
            .map_or(0.0, |h| h.depth)
    };
    let worst_missed = missed.iter().map(|&v| depth_of(v)).fold(0.0, f64::max);
    eprintln!(
        "line-line: {} vertices, {} inside, {} missed (deepest {:.2} mm), {} false hits",
        line.len(),
        inside_line,
        missed.len(),
        worst_missed * 1e3,
        false_hits
    );
    assert!(missed.len() * 50 <= inside_line, "line-line misses more than 2%");
    // A false hit is only pushed out to the ease; it must lie at the skin (brute-force
    // distance), and be rare.
    let worst_false = line
        .iter()
        .filter(|&&v| !truth.inside[v] && found.contains(&(v as u32)))
        .map(|&v| brute_distance(&real_body().mesh.mesh, g.mesh.positions[v]))
        .fold(0.0, f64::max);
    assert!(
        worst_false < 0.001,
        "a line-line false hit {worst_false} m off the skin"
    );
    assert!(false_hits * 20 <= inside_line, "line-line false hits more than 5%");
    assert!(worst_missed < 0.005, "a line-line miss 5 mm deep");
    // Point-face partitions stay exact under the default (mixed) methods.
    let pf_wrong = (0..g.mesh.positions.len())
        .filter(|&v| d.methods[v] == Some(DetectionMethod::PointFace))
        .filter(|&v| truth.inside[v] != found.contains(&(v as u32)))
        .count();
    assert_eq!(pf_wrong, 0);
}

/// The demo's edits: the jumpsuit, 4 cm more at the waist, then the ease down to 4 mm.
fn tight_jumpsuit() -> GarmentMesh {
    let mut dims = Dimensions::default();
    dims.values.insert("waist_girth".into(), 0.8096);
    dims.values.insert("ease".into(), 0.004);
    let fw = build_framework(
        real_body(),
        real_probe(),
        TemplateKind::Jumpsuit,
        &dims,
        &FrameworkOptions::default(),
    )
    .expect("the tight jumpsuit builds");
    GarmentMesh::from_framework(&fw, index().height)
}

fn parallel(a: DVec3, b: DVec3) -> bool {
    let (a, b) = (a.normalize_or_zero(), b.normalize_or_zero());
    a != DVec3::ZERO && a.dot(b) > 1.0 - 1e-9
}

fn check_rules(g: &GarmentMesh, c: &drape::collision::Collision) -> BTreeSet<AppliedRule> {
    let mut seen = BTreeSet::new();
    for r in &c.responses {
        seen.insert(r.rule);
        let v = r.vertex as usize;
        let plane = |d: DVec3| r.iso.map_or(d, |n| d - n * d.dot(n));
        if let Some(n) = r.iso {
            assert!(
                r.direction.dot(n).abs() < 1e-9,
                "v{v}: iso-height broken ({:?})",
                r.rule
            );
        }
        assert!((r.direction.length() - 1.0).abs() < 1e-9 || r.rule == AppliedRule::Fallback);
        match r.rule {
            AppliedRule::VertexNormal => assert!(parallel(r.direction, plane(g.normals[v])), "v{v} vertex normal"),
            AppliedRule::ViewDirection => {
                assert!(g.boundary[v], "v{v}: view direction off the boundary");
                assert!(parallel(r.direction, plane(DVec3::Z)) || parallel(r.direction, plane(-DVec3::Z)));
            }
            AppliedRule::BodyNormal => {
                let hit = c.detection.hits.iter().find(|h| h.vertex == r.vertex);
                if let Some(h) = hit.filter(|_| r.edge_round == 0) {
                    assert!(parallel(r.direction, plane(h.normal)), "v{v} body normal");
                }
            }
            AppliedRule::GlobalCentre | AppliedRule::LocalCentre | AppliedRule::Guard => {
                let centre = r.centre.expect("a centre rule records its centre");
                let radial = DVec3::new(r.from.x - centre.x, 0.0, r.from.z - centre.y);
                assert!(r.direction.y.abs() < 1e-12, "v{v}: centre ray not horizontal");
                assert!(parallel(r.direction, radial), "v{v}: not along the centre ray");
                if r.rule == AppliedRule::Guard {
                    assert!(r.proposed.dot(radial) <= 0.0, "v{v}: guard acted on a good direction");
                }
            }
            AppliedRule::EdgeLift | AppliedRule::FaceLift => {
                // Lifted along the way out at a crossing edge's deepest point, or along a
                // pierced face's outer normal: out of the body, never in.
                assert!(r.edge_round > 0, "v{v}: a lift outside the rounds");
                let s = index().signed_distance(r.to, 1.0).expect("near the body");
                assert!(s >= 0.0, "v{v}: an edge lift left it inside");
            }
            AppliedRule::Fallback => {
                // Out along the shortest way: the new point stands off the body.
                let s = index().signed_distance(r.to, 1.0).expect("near the body");
                assert!(s > 0.0, "v{v}: fallback left it inside");
            }
        }
        // The guard: within 90 degrees of the ray from the local centre (legs to abdomen).
        // Fallbacks take the shortest way out, and edge lifts the body's way out at their
        // edge's deepest point (within 75 degrees of the end's own): no centre ray.
        if !matches!(
            r.rule,
            AppliedRule::Fallback | AppliedRule::EdgeLift | AppliedRule::FaceLift
        ) && let Some(cs) = index().slices.at(r.from.y).and_then(|s| s.centres)
        {
            let p = glam::DVec2::new(r.from.x, r.from.z);
            let g2 = p - cs.local_of(p);
            assert!(
                r.direction.x * g2.x + r.direction.z * g2.y > 0.0,
                "v{v}: response folds back over its centre"
            );
        }
    }
    seen
}

#[test]
fn after_response_the_demo_m0_has_no_vertex_inside_and_no_crossing_edge() {
    // The demo's tight jumpsuit, every vertex pushed along its normal by up to 1 cm in or
    // 2 mm out, so that hundreds of vertices start inside.
    let mut g = tight_jumpsuit();
    let mut rng = Lcg(5);
    for (p, n) in g.mesh.positions.iter_mut().zip(&g.normals) {
        *p += *n * (rng.next() * 0.012 - 0.01);
    }
    g.normals = g.mesh.vertex_normals();
    let mut state = DetectState::default();
    let c = collide(index(), &g, 0.004, &CollisionOptions::default(), &mut state);
    assert!(
        c.detection.hits.len() > 100,
        "the push puts M0 in: {}",
        c.detection.hits.len()
    );
    let before = ground_truth(&real_body().mesh.mesh, &g.mesh.positions, &[]);
    assert!(before.inside_count() > 100);
    let after = ground_truth(&real_body().mesh.mesh, &c.mesh.positions, &g.edges);
    assert_eq!(after.inside_count(), 0, "vertices left inside");
    assert_eq!(after.crossing_count(), 0, "edges left crossing");
    assert_eq!(c.quality.penetrating_vertices, 0);
    assert_eq!(c.quality.crossing_edges, 0);
    let seen = check_rules(&g, &c);
    for rule in [AppliedRule::LocalCentre, AppliedRule::VertexNormal] {
        assert!(seen.contains(&rule), "{rule:?} not exercised");
    }
    assert!(!c.responses.is_empty());
    assert_meets_the_ease(&c, &real_body().mesh.mesh);
}

/// Every responded vertex meets its gap, measured by this test's own distance to the body
/// (every triangle tried) at its final position. A vertex pushed out stands at its gap
/// within 0.1% of it either way; the gap is the ease, or less where the body leaves no room,
/// which the test confirms with its own rays: along the line the vertex moved on, the body
/// lies within two eases both ahead and behind. An edge or face lift never leaves its vertex
/// inside, nor nearer the body than the ease (or than it stood, when it stood nearer).
pub(super) fn assert_meets_the_ease(c: &drape::collision::Collision, body: &TriMesh) -> usize {
    let mut last: std::collections::BTreeMap<u32, &drape::collision::Response> = std::collections::BTreeMap::new();
    for r in &c.responses {
        last.insert(r.vertex, r);
    }
    let mut squeezed = 0;
    for (v, r) in last {
        let d = brute_distance(body, c.mesh.positions[v as usize]);
        assert!(!inside_by_parity(body, r.to), "v{v} ({:?}) ends inside", r.rule);
        if matches!(r.rule, AppliedRule::EdgeLift | AppliedRule::FaceLift) {
            // Never nearer the body than the ease, or than it stood when nearer.
            let before = brute_distance(body, r.from);
            let least = before.min((1.0 - 1e-3) * c.ease);
            assert!(
                d >= least - 1e-9,
                "v{v}: a lift from {before:e} to {d:e} m, the ease {:e} m",
                c.ease
            );
            continue;
        }
        assert!(
            r.gap <= c.ease * (1.0 + 1e-12),
            "v{v}: gap {:e} beyond the ease {:e}",
            r.gap,
            c.ease
        );
        assert!(
            (d - r.gap).abs() <= 1e-3 * r.gap,
            "v{v} ({:?}) stands {d:e} m off, its gap is {:e} m (the ease {:e} m)",
            r.rule,
            r.gap,
            c.ease
        );
        if r.gap < c.ease * (1.0 - 1e-3) {
            squeezed += 1;
            let line = (r.to - r.from).normalize();
            let ahead = ray_hit(body, r.to, line).expect("body ahead");
            let behind = ray_hit(body, r.to, -line).expect("body behind");
            assert!(
                ahead <= 2.0 * c.ease + 1e-9 && behind <= 2.0 * c.ease + 1e-9,
                "v{v}: squeezed to {:e} m with the body {ahead:e} m ahead and {behind:e} m behind",
                r.gap
            );
        }
    }
    squeezed
}

#[test]
fn every_response_rule_keeps_its_direction_on_a_garment_pushed_in_everywhere() {
    let g = perturbed(13, 0.03, 0.0);
    let c = collide(
        index(),
        &g,
        0.019,
        &CollisionOptions::default(),
        &mut DetectState::default(),
    );
    let seen = check_rules(&g, &c);
    for rule in [
        AppliedRule::VertexNormal,
        AppliedRule::ViewDirection,
        AppliedRule::BodyNormal,
        AppliedRule::LocalCentre,
        AppliedRule::GlobalCentre,
    ] {
        assert!(seen.contains(&rule), "{rule:?} not exercised: {seen:?}");
    }
    let after = ground_truth(&real_body().mesh.mesh, &c.mesh.positions, &[]);
    assert_eq!(after.inside_count(), 0);
    assert!(!c.responses.is_empty());
    assert_meets_the_ease(&c, &real_body().mesh.mesh);
}

/// Keeps each step's M0 after response (with its detection counts) and before it.
#[derive(Default)]
struct Meshes(Vec<(TriMesh, usize, usize, usize)>, Vec<TriMesh>);

impl StageSink for Meshes {
    fn collision(&mut self, _: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        if stage.part == CollisionPart::Respond {
            let o = stage.outcome;
            let d = &o.collision.detection;
            self.0
                .push((o.collision.mesh.clone(), d.tested, d.skipped_inert, d.skipped_patch));
            self.1.push(o.garment.mesh.clone());
        }
        Ok(())
    }
}

#[test]
fn inert_points_and_patch_skipping_change_no_result() {
    let text = "drape 1\nbody builtin\ngarment jumpsuit\nset waist_girth +0.04\nset ease 0.004\n\
                set waist_girth +0.002\nset left_knee_girth +0.01\n";
    let session = parse_session(text, "skip.drape", std::path::Path::new(".")).expect("parses");
    let run = |skip: bool| {
        let mut options = RunOptions::default();
        options.collision.detect.inert = skip;
        options.collision.detect.patch_skipping = skip;
        let mut sink = Meshes::default();
        let report = run_session(&session, &options, &mut [&mut sink]);
        assert!(report.error.is_none(), "{:?}", report.error);
        sink.0
    };
    let (on, off) = (run(true), run(false));
    assert_eq!(on.len(), 5);
    for (k, (a, b)) in on.iter().zip(&off).enumerate() {
        assert_eq!(a.0, b.0, "step {k}: meshes differ");
        assert_eq!((b.2, b.3), (0, 0), "nothing skipped with skipping off");
    }
    let skipped: usize = on.iter().map(|s| s.2 + s.3).sum();
    let inert: usize = on.iter().map(|s| s.2).sum();
    let patch: usize = on.iter().map(|s| s.3).sum();
    assert!(
        inert > 0 && patch > 0,
        "both skips must act: inert {inert}, patch {patch}"
    );
    eprintln!("skipped {skipped} vertex tests over the session (inert {inert}, patch {patch})");
}

/// A closed unit cube with a zero-area triangle: the top face's front edge is split at its
/// midpoint, the front face's is not, and a sliver of three collinear corners closes the
/// seam between them.
fn cube_with_sliver() -> TriMesh {
    let mut positions: Vec<DVec3> = (0..8)
        .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
        .collect();
    // Midpoint of the top front edge (y = 1, z = 1), from corner 6 (0,1,1) to 7 (1,1,1).
    positions.push(DVec3::new(0.5, 1.0, 1.0));
    let triangles = vec![
        // bottom y = 0 (normal -y)
        [0, 1, 5],
        [0, 5, 4],
        // top y = 1 (normal +y): 2 (0,1,0), 3 (1,1,0), 7 (1,1,1), 6 (0,1,1), 8 mid of 6-7
        [2, 6, 8],
        [2, 8, 3],
        [3, 8, 7],
        [6, 7, 8], // zero area (6, 7, 8 collinear): closes the top's split edge
        // front z = 1 (normal +z): 4 5 7 6, its edge 6-7 not split
        [4, 5, 7],
        [4, 7, 6],
        // back z = 0 (normal -z)
        [0, 2, 3],
        [0, 3, 1],
        // left x = 0 (normal -x)
        [0, 4, 6],
        [0, 6, 2],
        // right x = 1 (normal +x)
        [1, 3, 7],
        [1, 7, 5],
    ];
    TriMesh { positions, triangles }
}

#[test]
fn degenerate_triangles_and_points_on_edges_vertices_and_faces_do_not_break_detection() {
    let mesh = cube_with_sliver();
    assert!(
        mesh.signed_volume() > 0.99 && mesh.signed_volume() < 1.01,
        "closed and outward"
    );
    let index = BodyIndex::from_mesh(&mesh).expect("manifold");
    let reach = Reach {
        inside: 1.0,
        outside: 1.0,
        surface: 1e-12,
    };
    let on_surface = [
        DVec3::new(0.5, 1.0, 1.0),  // the sliver's middle corner
        DVec3::new(0.25, 1.0, 1.0), // on the sliver (and on a cube edge)
        DVec3::new(1.0, 1.0, 1.0),  // a cube corner
        DVec3::new(1.0, 0.5, 0.0),  // on a cube edge
        DVec3::new(0.3, 0.0, 0.6),  // on a face
        DVec3::new(0.5, 0.5, 1.0),  // on a face, on an inner diagonal
    ];
    for search in [Search::Brute, Search::PartitionBvh(0)] {
        for p in on_surface {
            let r = point_face(&index, search, p, &reach);
            let n = r.nearest.expect("on the surface");
            assert!(n.distance <= 1e-15 && !r.inside, "{p}: on the surface is not inside");
            assert!(n.foot.is_finite() && n.normal.is_finite());
        }
        // Just inside and just outside each of them, along the way into the cube's centre.
        for p in on_surface {
            let into = (DVec3::splat(0.5) - p).normalize();
            for (eps, want) in [(1e-6, true), (-1e-6, false)] {
                let q = p + into * eps;
                let r = point_face(&index, search, q, &reach);
                assert_eq!(r.inside, want, "{q} ({search:?})");
                let wn = drape::geom::inside::winding_number(&mesh, q);
                assert_eq!(wn > 0.5, want, "truth at {q}");
            }
        }
    }
    // No NaN anywhere when a whole garment sits on the surface.
    let garment = GarmentMesh {
        mesh: TriMesh {
            positions: on_surface.to_vec(),
            triangles: vec![],
        },
        face_patch: std::sync::Arc::new(vec![]),
        edges: std::sync::Arc::new(vec![[0, 1], [1, 2], [4, 5]]),
        normals: vec![DVec3::Y; 6],
        boundary: std::sync::Arc::new(vec![false; 6]),
        ring_normal: vec![None; 6],
        vertex_patches: std::sync::Arc::new(vec![vec![]; 6]),
        patch_curves: vec![],
        controls: Default::default(),
    };
    let c = collide(
        &index,
        &garment,
        0.01,
        &CollisionOptions::default(),
        &mut DetectState::default(),
    );
    assert!(c.detection.hits.is_empty());
    assert!(c.mesh.positions.iter().all(|p| p.is_finite()));
}

#[test]
fn export_writes_each_steps_m0_after_response() {
    let text = "drape 1\nbody builtin\ngarment jumpsuit\nset ease 0.004\n";
    let session = parse_session(text, "export.drape", std::path::Path::new(".")).expect("parses");
    let dir = std::env::temp_dir().join(format!("drape-export-test-{}", std::process::id()));
    let mut exporter = drape::session::export::ObjExporter::new(dir.clone()).expect("folder");
    let mut meshes = Meshes::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut exporter, &mut meshes]);
    assert!(report.error.is_none(), "{:?}", report.error);
    for (step, (responded, ..)) in [1, 2].iter().zip(&meshes.0) {
        let path = dir.join(format!("step{step:02}_jumpsuit_m0.obj"));
        let obj =
            drape::mesh::read_obj(&path, 1.0, drape::input::DEFAULT_MAX_INPUT_BYTES).expect("the export reads back");
        assert_eq!(obj.mesh.triangles, responded.triangles);
        let worst = obj
            .mesh
            .positions
            .iter()
            .zip(&responded.positions)
            .map(|(a, b)| a.distance(*b))
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-6,
            "step {step}: export differs from M0 after response by {worst}"
        );
    }
    // Step 2's response moved vertices: the export is not the raw M0.
    assert_ne!(meshes.0[1].0.positions, meshes.1[1].positions);
    std::fs::remove_dir_all(&dir).ok();
}

/// `--verify`'s comparison must catch a garment vertex planted 5 mm inside the body after a
/// clean response: the quality that missed it disagrees with the truth, the quality
/// measured on the planted mesh agrees, and both name that vertex and its edges. The truth
/// here is the plant itself, confirmed by the test's own ray-parity count over every
/// vertex.
#[test]
fn verify_catches_a_vertex_planted_inside_the_body() {
    let g = tight_jumpsuit();
    let c = collide(
        index(),
        &g,
        0.004,
        &CollisionOptions::default(),
        &mut DetectState::default(),
    );
    let body = &real_body().mesh.mesh;
    // The vertex nearest the front of the waist; its plant 5 mm behind the skin there.
    let waist = real_body().landmarks.height(drape::body::LandmarkKind::Waist);
    let v = (0..c.mesh.positions.len())
        .max_by(|&a, &b| {
            let key = |p: DVec3| p.z - 10.0 * (p.y - waist).abs() - 10.0 * p.x.abs();
            key(c.mesh.positions[a]).total_cmp(&key(c.mesh.positions[b]))
        })
        .expect("vertices");
    let near = index().nearest(c.mesh.positions[v], 1.0).expect("near the body");
    let plant = near.foot - near.normal * 0.005;
    let mut planted = c.mesh.positions.clone();
    planted[v] = plant;
    let inside: Vec<usize> = (0..planted.len())
        .filter(|&k| inside_by_parity(body, planted[k]))
        .collect();
    assert_eq!(inside, vec![v], "the plant is the only vertex inside");
    let incident: Vec<u32> = (0..g.edges.len())
        .filter(|&e| g.edges[e].contains(&(v as u32)))
        .map(|e| e as u32)
        .collect();
    let before = ground_truth(body, &g.mesh.positions, &g.edges);
    let after = ground_truth(body, &planted, &g.edges);
    // The collision's own quality (of the clean mesh) is now wrong: verify says so.
    let missed = compare(&before, &c.detection, &after, &c.quality, |_| false);
    assert_eq!(missed.inside_after, 1);
    assert_eq!(missed.crossing_after, incident.len(), "every edge at the plant crosses");
    assert!(!missed.quality_agrees);
    // The quality measured on the planted mesh finds it and agrees.
    let honest = quality(index(), &c.mesh.positions, &planted, &g.edges, &c.responses);
    assert_eq!(honest.inside, vec![v as u32]);
    assert_eq!(honest.crossing, incident);
    let depth = brute_distance(body, plant);
    assert!((depth - 0.005).abs() < 1e-4, "planted {depth} m deep");
    assert!(
        (honest.max_depth_m - depth).abs() < 1e-9,
        "depth {} vs {depth}",
        honest.max_depth_m
    );
    assert!(compare(&before, &c.detection, &after, &honest, |_| false).quality_agrees);
}

/// `drape run --verify` checks every collision step and writes the figures under `verify`
/// in the metrics: the demo's first two garment steps against the ground truth.
#[test]
fn run_with_verify_reports_the_ground_truth_per_collision_step() {
    let dir = std::env::temp_dir().join(format!("drape-verify-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("v.drape");
    std::fs::write(
        &session,
        "drape 1\nbody builtin\ngarment jumpsuit resolution=3\nset ease 0.004\n",
    )
    .unwrap();
    let metrics = dir.join("v.json");
    let (code, stderr) = super::session_errors::drape(&[
        "run",
        session.to_str().unwrap(),
        "--verify",
        "--save",
        dir.join("v.rrd").to_str().unwrap(),
        "--metrics",
        metrics.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&metrics).unwrap()).unwrap();
    let steps = json.as_array().unwrap();
    for step in &steps[1..] {
        let v = &step["verify"];
        assert!(v.is_object(), "no verify on step {}", step["step"]);
        // The fast quality check's figures are the ground truth's.
        assert_eq!(v["quality_agrees"], true);
        assert_eq!(v["inside_after"], step["penetrating_vertices"]);
        assert_eq!(v["crossing_after"], step["crossing_edges"]);
        assert_eq!(
            v["inside_before"],
            step["hits"].as_u64().unwrap() + v["missed"].as_u64().unwrap() - v["false_hits"].as_u64().unwrap()
        );
    }
    assert!(stderr.contains("verify: truth"), "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}
