//! The speed shortcuts change no result: the partial quality check against the full one
//! over whole sessions, and the warm-started, capped nearest-point queries against a brute
//! force over perturbed garments on every shipped body. (1 and 2 threads: see
//! `snapshot::two_runs_write_the_same_chunks_in_the_same_order_on_one_thread_or_two`.)

use drape::body::index::BodyIndex;
use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::collision::{Quality, SliceOptions};
use drape::mesh::TriMesh;
use drape::session::{
    CollisionPart, CollisionStage, RunOptions, SinkError, StageInfo, StageSink, parse_session, run_session,
};
use glam::DVec3;

use super::common::{
    Lcg, brute_distance, inside_by_parity, ray_hits, real_jumpsuit, shipped_bodies, triangle_distance,
};

/// Each collision's quality and what it reused.
#[derive(Default)]
struct Qualities(Vec<(usize, Quality, usize)>);

impl StageSink for Qualities {
    fn collision(&mut self, info: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        if stage.part == CollisionPart::Respond {
            let c = &stage.outcome.collision;
            self.0
                .push((info.step, c.quality.clone(), c.reused.vertices + c.reused.quality_edges));
        }
        Ok(())
    }
}

fn qualities(text: &str, full: bool) -> Vec<(usize, Quality, usize)> {
    let session = parse_session(text, "quality.drape", std::path::Path::new(".")).expect("parses");
    let mut options = RunOptions::default();
    options.collision.full_quality = full;
    let mut sink = Qualities::default();
    let report = run_session(&session, &options, &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    sink.0
}

/// A session of random drags (some refused), a dimension change and an undo.
fn random_drags(seed: u64) -> String {
    const POINTS: [&str; 8] = [
        "waist.front_left",
        "waist.front",
        "chest.front_left",
        "left_knee",
        "crotch.point",
        "left_hem.outer",
        "right_thigh.inner",
        "hip.back",
    ];
    let mut rng = Lcg(seed);
    let mut text = String::from("drape 1\nbody builtin\ngarment jumpsuit fit=tight resolution=6\nset ease 0.006\n");
    for k in 0..6 {
        let point = POINTS[(rng.next() * POINTS.len() as f64) as usize % POINTS.len()];
        let by: Vec<String> = (0..3).map(|_| format!("{:.4}", 0.05 * (rng.next() - 0.5))).collect();
        text += &format!("drag {point} by={}\n", by.join(","));
        if k == 2 {
            text += "set hip_girth +0.02\n";
        }
        if k == 4 {
            text += "undo\n";
        }
    }
    text
}

/// The partial check (only vertices and edges at new positions measured) gives the full
/// check's figures, bit for bit (counts, depths, the sets of inside vertices and crossing
/// edges, every vertex's clearance), on every step of the demo and of random drag sessions,
/// and it did skip work.
#[test]
fn partial_quality_equals_the_full_check_on_every_step() {
    let demo = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/sessions/demo.drape"))
        .expect("the demo session");
    let mut sessions = vec![demo];
    sessions.extend([11, 23, 47].map(random_drags));
    for text in &sessions {
        let (partial, full) = (qualities(text, false), qualities(text, true));
        assert_eq!(partial.len(), full.len(), "{text}");
        assert!(partial.len() >= 4, "{} collisions", partial.len());
        for ((step, a, _), (_, b, reused)) in partial.iter().zip(&full) {
            assert_eq!(*reused, 0, "the full check reuses nothing");
            assert_eq!(a.penetrating_vertices, b.penetrating_vertices, "step {step}");
            assert_eq!(a.crossing_edges, b.crossing_edges, "step {step}");
            assert_eq!(a.inside, b.inside, "step {step}: inside vertices");
            assert_eq!(a.crossing, b.crossing, "step {step}: crossing edges");
            assert_eq!(a, b, "step {step}: every figure");
        }
        let reused: usize = partial.iter().map(|p| p.2).sum();
        assert!(reused > 0, "the partial check measured everything again:\n{text}");
    }
}

/// The body of `path`, analysed.
fn body(path: &std::path::Path) -> Body {
    let mesh = BodyMesh::load(&BodySource::File(path.to_path_buf()), 1.0).expect("the body loads");
    Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("the body analyses")
}

/// The body of `path`, its index, its shell and the shift that moves the jumpsuit onto it.
fn on_body(path: &std::path::Path) -> (Body, BodyIndex, TriMesh, DVec3) {
    let body = body(path);
    let index = BodyIndex::new(&body, &SliceOptions::default());
    let (shell, shift) = shell_and_shift(&body, &index);
    (body, index, shell, shift)
}

/// The surface the queries see, the body's outer shell (on a body that crosses itself, the
/// triangles buried inside another part are left out), and the shift that moves the
/// jumpsuit onto the body (its bounding box centre onto the body's).
fn shell_and_shift(body: &Body, index: &BodyIndex) -> (TriMesh, DVec3) {
    let mesh = &body.mesh.mesh;
    let shell = TriMesh {
        positions: mesh.positions.clone(),
        triangles: index.shell_triangles().map(|t| mesh.triangles[t as usize]).collect(),
    };
    let (lo, hi) = mesh.bounds().expect("a body");
    let (glo, ghi) = real_jumpsuit().m0.mesh.bounds().expect("a garment");
    (shell, 0.5 * (lo + hi) - 0.5 * (glo + ghi))
}

/// On every shipped body, the jumpsuit's M0 perturbed at random (up to 3 cm each way): the
/// nearest-point query, warm-started from the last triangle found (in garment order), from
/// a random triangle, or capped at 1 cm, agrees with a brute force over every triangle
/// written in the test (distance to 1e-12 m, inside by ray parity away from the surface,
/// and the cap: an answer exactly when the brute distance is within it).
#[test]
fn warm_started_and_capped_queries_agree_with_a_brute_force_on_every_body() {
    let garment: Vec<DVec3> = real_jumpsuit().m0.mesh.positions.clone();
    let bodies = shipped_bodies();
    assert_eq!(bodies.len(), 5);
    let mut rng = Lcg(5);
    for path in &bodies {
        let body = body(path);
        let index = BodyIndex::new(&body, &SliceOptions::default());
        let mesh = &body.mesh.mesh;
        // The garment moved onto this body, every 9th vertex.
        let (shell, shift) = shell_and_shift(&body, &index);
        let points: Vec<DVec3> = garment
            .iter()
            .step_by(9)
            .map(|p| *p + shift + 0.06 * DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5))
            .collect();
        let triangles = index.triangles.len() as f64;
        let mut inside = 0;
        for &p in &points {
            let truth = brute_distance(&shell, p);
            let warm = index.nearest(p, f64::INFINITY).expect("a nearest point");
            let hint = (rng.next() * triangles) as u32;
            let random = index
                .nearest_from(p, f64::INFINITY, Some(hint))
                .expect("a nearest point");
            assert!(
                (warm.distance - truth).abs() < 1e-12,
                "{p}: {} vs {truth}",
                warm.distance
            );
            assert_eq!(warm, random, "{p}: the hint changed the answer");
            let capped = index.nearest(p, 0.01);
            assert_eq!(capped.is_some(), truth <= 0.01, "{p}: cap, brute {truth}");
            if let Some(c) = capped {
                assert_eq!(c, warm, "{p}: the cap changed the answer");
            }
            if truth > 1e-6 {
                let parity = inside_by_parity(mesh, p);
                assert_eq!(warm.signed(p) < 0.0, parity, "{p}: side");
                inside += usize::from(parity);
            }
        }
        assert!(
            inside > 20 && inside < points.len() - 20,
            "{}: {inside} of {} inside, both sides must be tested",
            path.display(),
            points.len()
        );
    }
}

/// On every shipped body, segments between the jumpsuit's M0 vertices moved onto the body
/// and perturbed (edges of 0.5 to 6 cm, as M0's and M1's are, many of them through the
/// skin): the index's segment test (the nearest-point tree picks the triangles, the exact
/// predicate decides) and its ray cast along the segment (the tree's walk rules out the
/// misses) agree with a Möller-Trumbore test of every shell triangle written in the test (segments whose ends lie within a micrometre of a triangle's plane hit are left
/// out: there the rounded test cannot tell). And each partition's nearest point agrees with
/// a brute-force distance over that partition's triangles.
#[test]
fn segment_and_partition_queries_through_the_nearest_point_tree_agree_with_a_brute_force_on_every_body() {
    let garment: Vec<DVec3> = real_jumpsuit().m0.mesh.positions.clone();
    let mut rng = Lcg(17);
    for path in &shipped_bodies() {
        let (body, index, shell, shift) = on_body(path);
        let (mut hits, mut misses) = (0, 0);
        for p in garment.iter().step_by(5) {
            let a = *p + shift + 0.04 * DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
            // Every other segment aimed at the skin (the index only aims it).
            let mut dir = DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
            if rng.next() < 0.5
                && let Some(n) = index.nearest(a, f64::INFINITY)
            {
                dir = 0.3 * dir + (n.foot - a).normalize_or_zero();
            }
            let b = a + dir.normalize() * (0.005 + 0.055 * rng.next());
            let ts: Vec<f64> = ray_hits(&shell, a, b - a).collect();
            if ts
                .iter()
                .any(|t| (t - 1.0).abs() * a.distance(b) < 1e-6 || *t * a.distance(b) < 1e-6)
            {
                continue;
            }
            let truth = ts.iter().any(|&t| t < 1.0);
            assert_eq!(index.segment_hits(a, b), truth, "{}: {a} -> {b}", path.display());
            // The ray along it: met exactly where a triangle is, at the first hit.
            let first = ts.iter().copied().filter(|&t| t < 1.0).fold(f64::INFINITY, f64::min);
            match index.cast_ray(a, b - a, 0.0, 1.0) {
                Some((t, _)) => assert!(
                    (t - first).abs() < 1e-9,
                    "{}: {a} -> {b}: {t} vs {first}",
                    path.display()
                ),
                None => assert!(
                    !truth,
                    "{}: {a} -> {b}: the ray missed a hit at {first}",
                    path.display()
                ),
            }
            if truth {
                hits += 1;
            } else {
                misses += 1;
            }
        }
        assert!(
            hits > 30 && misses > 30,
            "{}: {hits} hits, {misses} misses",
            path.display()
        );
        // Long rays across the body (in at one side, out at the other, often through an arm
        // or the other leg too): the first of several hits.
        let (lo, hi) = body.mesh.mesh.bounds().expect("a body");
        let centre = 0.5 * (lo + hi);
        let mut through = 0;
        for p in garment.iter().step_by(37) {
            let a = *p + shift;
            let aim = DVec3::new(centre.x, a.y, centre.z) + 0.1 * DVec3::new(rng.next() - 0.5, 0.0, rng.next() - 0.5);
            let d = (aim - a).normalize_or_zero() * 1.2;
            let ts: Vec<f64> = ray_hits(&shell, a, d).filter(|&t| t <= 1.0).collect();
            if ts.iter().any(|t| *t * 1.2 < 1e-6 || (t - 1.0).abs() * 1.2 < 1e-6) {
                continue;
            }
            let first = ts.iter().copied().fold(f64::INFINITY, f64::min);
            match index.cast_ray(a, d, 0.0, 1.0) {
                Some((t, _)) => assert!(
                    (t - first).abs() < 1e-9,
                    "{}: {a} along {d}: {t} vs {first}",
                    path.display()
                ),
                None => assert!(ts.is_empty(), "{}: {a} along {d}: missed {first}", path.display()),
            }
            through += usize::from(ts.len() >= 2);
        }
        assert!(through > 20, "{}: {through} rays crossed the body", path.display());
        let mesh = &body.mesh.mesh;
        for (k, part) in index.partitions.iter().enumerate() {
            let mut tested = 0;
            for p in garment.iter().step_by(23) {
                let q = *p + shift + 0.06 * DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
                if index.partition_at(q.y) != Some(k) {
                    continue;
                }
                let brute = part
                    .triangles
                    .iter()
                    .map(|&t| triangle_distance(q, mesh.corners(t as usize)))
                    .fold(f64::INFINITY, f64::min);
                let n = index
                    .nearest_in_partition(k, q, f64::INFINITY)
                    .expect("a nearest point");
                assert!(
                    (n.distance - brute).abs() < 1e-12,
                    "{}: partition {k}, {q}",
                    path.display()
                );
                assert!(part.triangles.binary_search(&n.triangle).is_ok());
                tested += 1;
            }
            assert!(tested > 0, "{}: partition {k} untested", path.display());
        }
    }
}

/// On every shipped body, the jumpsuit's M0 moved onto it and perturbed (up to 3 cm each
/// way; 30 edges made to touch the skin at an end and stand off it): the edge rounds give the same lifts, rounds and positions, bit for bit, whether the
/// first round tests every edge or skips those the measured distances of their ends show
/// clear; a brute-force ray test over every shell triangle finds none of the skipped edges
/// meeting the body; and the first round's crossing edges are exactly those that pass
/// through some shell triangle by the exact segment test, tried on every one (the quality
/// check's crossing edges, whose verdicts the check takes from the round).
#[test]
fn edge_rounds_skipping_edges_known_clear_change_no_result_on_every_body() {
    use drape::collision::quality::measure_vertices;
    use drape::collision::{KnownClearance, ResponseOptions, respond_edges, response_ease};
    use drape::geom::predicates::segment_crosses_triangle;
    let jumpsuit = &real_jumpsuit().m0;
    let edges = &jumpsuit.edges;
    let mut rng = Lcg(11);
    for path in &shipped_bodies() {
        let body = body(path);
        let index = BodyIndex::new(&body, &SliceOptions::default());
        let (shell, shift) = shell_and_shift(&body, &index);
        let garment = TriMesh {
            positions: jumpsuit.mesh.positions.iter().map(|p| *p + shift).collect(),
            triangles: jumpsuit.mesh.triangles.clone(),
        };
        let normals = garment.vertex_normals();
        let mut positions: Vec<DVec3> = garment
            .positions
            .iter()
            .zip(&normals)
            .map(|(p, n)| *p + *n * (rng.next() * 0.06 - 0.03))
            .collect();
        // Edges that touch the skin at an end and stand off it along the body's normal
        // there: their far end on a body vertex, exactly. They do not pass through it.
        let body_normals = shell.vertex_normals();
        for k in 0..30 {
            let [a, b] = edges[k * edges.len() / 30];
            let v = shell.triangles[k * shell.triangles.len() / 30][0] as usize;
            positions[b as usize] = shell.positions[v];
            positions[a as usize] = shell.positions[v] + body_normals[v] * 0.01;
        }
        let partition: Vec<usize> = positions.iter().map(|p| index.partition_at(p.y).unwrap_or(0)).collect();
        let plain = super::common::PlainRoles::new(positions.len());
        let roles = plain.with(&normals);
        let options = ResponseOptions::default();
        let ease = response_ease(&index, 0.01, &options);
        let measured = measure_vertices(&index, &positions, None);
        let free = measured.free();
        let known = KnownClearance {
            at: &measured.at,
            free: &free,
        };
        let run = |known: Option<KnownClearance<'_>>| {
            let mut moved = positions.clone();
            let out = respond_edges(
                &index, &mut moved, edges, &partition, &roles, ease, &options, None, known,
            );
            (out, moved)
        };
        let (every, every_positions) = run(None);
        let (skipping, skipping_positions) = run(Some(known));
        let name = path.display();
        assert!(
            every.0.len() > 10,
            "{name}: {} lifts, the rounds must do something",
            every.0.len()
        );
        assert!(
            every == skipping,
            "{name}: lifts, rounds or first crossings differ ({} vs {} lifts, rounds {:?} vs {:?})",
            every.0.len(),
            skipping.0.len(),
            every.1,
            skipping.1
        );
        assert!(
            every_positions
                .iter()
                .zip(&skipping_positions)
                .all(|(a, b)| a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)),
            "{name}: positions differ"
        );
        // The edges the distances show clear, checked against every triangle.
        let clear: Vec<&[u32; 2]> = edges
            .iter()
            .filter(|&&[a, b]| {
                let (pa, pb) = (positions[a as usize], positions[b as usize]);
                free[a as usize] + free[b as usize] > pa.distance(pb) + 1e-6 * index.height
            })
            .collect();
        assert!(
            clear.len() > edges.len() / 2,
            "{name}: only {} of {} edges known clear",
            clear.len(),
            edges.len()
        );
        for &&[a, b] in clear.iter().step_by(40) {
            let (pa, pb) = (positions[a as usize], positions[b as usize]);
            let hit = super::common::ray_hit(&shell, pa, pb - pa);
            assert!(
                hit.is_none_or(|t| t > 1.0),
                "{name}: edge {a}-{b} meets the body at {hit:?}"
            );
        }
        let corners: Vec<[DVec3; 3]> = shell
            .triangles
            .iter()
            .map(|t| t.map(|v| shell.positions[v as usize]))
            .collect();
        let boxes: Vec<[DVec3; 2]> = corners
            .iter()
            .map(|[p, q, r]| [p.min(*q).min(*r), p.max(*q).max(*r)])
            .collect();
        let mut through: Vec<[u32; 2]> = edges
            .iter()
            .copied()
            .filter(|&[a, b]| {
                let (pa, pb) = (positions[a as usize], positions[b as usize]);
                let [lo, hi] = [pa.min(pb), pa.max(pb)];
                corners.iter().zip(&boxes).any(|(c, [tlo, thi])| {
                    lo.cmple(*thi).all() && hi.cmpge(*tlo).all() && segment_crosses_triangle(pa, pb, *c)
                })
            })
            .collect();
        let mut first = every.2.clone();
        through.sort_unstable();
        first.sort_unstable();
        assert!(through.len() > 10, "{name}: {} edges through the skin", through.len());
        assert_eq!(first, through, "{name}: the first round's crossing edges");
    }
}

/// M1's selection reads each M0 vertex's nearest body triangle from M0's quality check
/// instead of searching again: the same patches by the same rules as its own search, on
/// the jumpsuit perturbed three ways (the body rule made strict enough to fire), and the
/// triangles the check found are the nearest by a brute force over every shell triangle.
#[test]
fn the_selection_reading_the_quality_checks_nearest_triangles_selects_the_same_patches() {
    use drape::collision::{CollisionOptions, DetectState, GarmentMesh, collide};
    use drape::m1::{SelectInput, SelectOptions, select};
    let index = super::common::real_probe().index();
    let mesh = &super::common::real_body().mesh.mesh;
    let shell = TriMesh {
        positions: mesh.positions.clone(),
        triangles: index.shell_triangles().map(|t| mesh.triangles[t as usize]).collect(),
    };
    let mut options = SelectOptions::default();
    options.body_edge = 1.5;
    let mut fired = 0;
    for seed in [1, 2, 3] {
        let mut g = GarmentMesh::from_framework(real_jumpsuit(), index.height);
        let mut rng = Lcg(seed);
        for (p, n) in g.mesh.positions.iter_mut().zip(&g.normals) {
            *p += *n * (rng.next() * 0.03 - 0.01);
        }
        g.normals = g.mesh.vertex_normals();
        let c = collide(
            index,
            &g,
            0.01,
            &CollisionOptions::default(),
            &mut DetectState::default(),
        );
        let measured = c.quality.measured(&c.mesh.positions);
        let input = |measured| SelectInput {
            mesh: &c.mesh,
            face_patch: &g.face_patch,
            patches: real_jumpsuit().m0.patch_names.len(),
            standard: Some(&g.mesh.positions),
            measured,
            edges: None,
        };
        let own = select(&input(None), index, &options);
        let read = select(&input(Some(&measured)), index, &options);
        assert_eq!(own, read, "seed {seed}");
        // M0's edges kept from a step before (the same faces) read as if found anew.
        let kept = select::EdgeFaces::of(&c.mesh, None);
        let with_kept = SelectInput {
            edges: Some(&kept),
            ..input(Some(&measured))
        };
        assert_eq!(own, select(&with_kept, index, &options), "seed {seed}: kept edges");
        fired += own.by_rule().get("body").copied().unwrap_or(0);
        for v in (0..c.mesh.positions.len()).step_by(37) {
            let p = c.mesh.positions[v];
            let t = c.quality.nearest[v];
            let truth = brute_distance(&shell, p);
            let found = triangle_distance(p, mesh.triangles[t as usize].map(|i| mesh.positions[i as usize]));
            assert!(
                (found - truth).abs() < 1e-12,
                "seed {seed}, vertex {v}: {found} vs {truth}"
            );
        }
    }
    assert!(fired > 0, "the body rule never fired");
}

/// The line-line test as a plain scan of every edge of every loop, in order, written here
/// as the reference the library's pruned scan must equal bit for bit.
fn line_line_by_scan(
    slice: &drape::body::slices::Slice,
    k: usize,
    p: DVec3,
    normal: DVec3,
    reach: &drape::collision::Reach,
) -> drape::collision::line_line::LineLine {
    use glam::DVec2;
    let q = DVec2::new(p.x, p.z);
    let mut d = DVec2::new(normal.x, normal.z).normalize_or_zero();
    if d == DVec2::ZERO {
        d = slice
            .centres
            .map_or(DVec2::ZERO, |c| (q - c.global).normalize_or_zero());
    }
    if d == DVec2::ZERO {
        d = DVec2::Y;
    }
    let mut best: Option<(f64, DVec2)> = None;
    let mut clearance = f64::INFINITY;
    for l in &slice.loops {
        let points = l.points();
        let n = points.len();
        for i in 0..n {
            let (a, b) = (points[i], points[(i + 1) % n]);
            let e = b - a;
            let len2 = e.length_squared();
            let s = if len2 > 0.0 {
                ((q - a).dot(e) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            clearance = clearance.min(q.distance(a + e * s));
            let den = d.perp_dot(e);
            if den == 0.0 {
                continue;
            }
            let w = a - q;
            let (t, s) = (w.perp_dot(e) / den, w.perp_dot(d) / den);
            if (0.0..=1.0).contains(&s)
                && t >= -reach.outside
                && t <= reach.inside
                && best.is_none_or(|(bt, _)| t.abs() < bt.abs())
            {
                best = Some((t, DVec2::new(e.y, -e.x).normalize_or_zero()));
            }
        }
    }
    let at = |v: DVec2| DVec3::new(v.x, slice.y, v.y);
    match best {
        Some((t, n)) => {
            let depth = t.abs() * d.dot(n).abs();
            let inside = t * d.dot(n) > 0.0 && depth > reach.surface;
            drape::collision::line_line::LineLine {
                slice: k,
                inside,
                depth: if inside { depth } else { 0.0 },
                foot: at(q + d * t),
                normal: DVec3::new(n.x, 0.0, n.y),
                clearance: if inside { 0.0 } else { clearance },
            }
        }
        None => drape::collision::line_line::LineLine {
            slice: k,
            inside: false,
            depth: 0.0,
            foot: at(q),
            normal: DVec3::ZERO,
            clearance: if slice
                .loops
                .iter()
                .any(|l| drape::geom::polygon::contains(l.points(), q))
            {
                0.0
            } else {
                clearance
            },
        },
    }
}

/// On every shipped body, the line-line test, which reads only the runs of ring edges
/// whose boxes lie near the vertex or on its line, gives what a scan of every edge gives,
/// bit for bit: for the jumpsuit moved onto the body and perturbed (up to 3 cm each way)
/// with random normals, also flat or vertical ones, visited in garment order and shuffled
/// (the hint from the last vertex changes), and for points on ring corners aimed through
/// other corners (ties between edges), and for points standing off an edge by just the
/// reach along its normal (a crossing at either end of the part of the line read).
#[test]
fn line_line_reading_only_the_runs_near_the_vertex_equals_a_scan_of_every_edge_on_every_body() {
    let garment: Vec<DVec3> = real_jumpsuit().m0.mesh.positions.clone();
    let mut rng = Lcg(11);
    let mut compared = 0;
    let mut inside = 0;
    for path in &shipped_bodies() {
        let body = body(path);
        let index = BodyIndex::new(&body, &SliceOptions::default());
        let stack = &index.slices;
        let reach = drape::collision::DetectOptions::default().reach(index.height);
        let (_, shift) = shell_and_shift(&body, &index);
        let mut cases: Vec<(DVec3, DVec3)> = garment
            .iter()
            .map(|p| {
                let p = *p + shift + 0.06 * DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
                let n = match (rng.next() * 10.0) as u32 {
                    0 => DVec3::Y,
                    1 => DVec3::new(1.0, 0.0, 0.0),
                    _ => DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5),
                };
                (p, n)
            })
            .collect();
        // Ring corners aimed through other corners of the same slice.
        for (k, slice) in stack.slices.iter().enumerate().step_by(7) {
            let corners: Vec<glam::DVec2> = slice.loops.iter().flat_map(|l| l.points().iter().copied()).collect();
            for j in (0..corners.len()).step_by(5) {
                let other = corners[(j * 7 + 3) % corners.len()];
                let (a, y) = (corners[j], stack.y0 + k as f64 * stack.dy);
                let d = other - a;
                cases.push((DVec3::new(a.x, y, a.y), DVec3::new(d.x, 0.0, d.y)));
            }
            // Points standing off an edge's midpoint along its outward normal by just the
            // reach, aimed along it: the crossing there lies at an end of the part of the
            // line read (`t` = `w1` inside, `-w2` outside).
            for l in &slice.loops {
                let points = l.points();
                for j in (0..points.len()).step_by(3) {
                    let m = 0.5 * (points[j] + points[(j + 1) % points.len()]);
                    let n = l.edge_normal(j);
                    for b in [m - n * reach.inside, m + n * reach.outside] {
                        cases.push((
                            DVec3::new(b.x, stack.y0 + k as f64 * stack.dy, b.y),
                            DVec3::new(n.x, 0.0, n.y),
                        ));
                    }
                }
            }
        }
        let shuffled: Vec<usize> = {
            let mut order: Vec<(u64, usize)> = (0..cases.len()).map(|i| ((rng.next() * 1e12) as u64, i)).collect();
            order.sort_unstable();
            order.into_iter().map(|(_, i)| i).collect()
        };
        for i in (0..cases.len()).chain(shuffled) {
            let (p, n) = cases[i];
            let k = ((p.y - stack.y0) / stack.dy).round();
            let Some(slice) = stack.at(p.y) else { continue };
            let k = k as usize;
            let got = drape::collision::line_line::line_line(slice, k, p, n, &reach);
            let want = line_line_by_scan(slice, k, p, n, &reach);
            assert_eq!(got, want, "{}: {p} normal {n}", path.display());
            compared += 1;
            inside += usize::from(want.inside);
        }
    }
    assert!(
        compared > 20_000 && inside > 500,
        "{compared} compared, {inside} inside"
    );
}

/// A point drawn uniformly from the unit ball (by rejection).
fn in_unit_ball(rng: &mut Lcg) -> DVec3 {
    loop {
        let v = DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 2.0;
        if v.length_squared() <= 1.0 {
            return v;
        }
    }
}

/// On every shipped body, a search scanning the triangles gathered about a point
/// ([`BodyIndex::nearby`], as the relaxation of a patch's samples makes them) from points
/// moved anywhere within the ball gives the whole tree's answer, field for field, and the
/// distance of a scan of every shell triangle written in the test; outside the ball it
/// declines. So does a ball gathered knowing only a distance the body lies within
/// ([`BodyIndex::nearby_within`]), and the first triangle of a ball is the tree's answer at
/// its centre. Balls of 2 mm and 2 cm (the clearance of a tight garment and more), about
/// garment points near and through the skin.
#[test]
fn searches_among_the_triangles_gathered_about_a_point_agree_with_a_brute_force_on_every_body() {
    let garment: Vec<DVec3> = real_jumpsuit().m0.mesh.positions.clone();
    let mut rng = Lcg(29);
    let unit = in_unit_ball;
    for path in &shipped_bodies() {
        let (_, index, shell, shift) = on_body(path);
        let (mut scanned, mut declined) = (0, 0);
        for p in garment.iter().step_by(23) {
            let centre = *p + shift + 0.03 * unit(&mut rng);
            let found = index.nearest(centre, f64::INFINITY).expect("a nearest point");
            for room in [0.002, 0.02] {
                let near = index.nearby(centre, &found, room);
                assert_eq!(index.nearest_at_centre(&near), Some(found), "{centre}: at the centre");
                // Gathered knowing only some distance the body lies within (at least the
                // nearest one's): the same answers.
                let within = found.distance * (1.0 + rng.next()) + 0.005 * rng.next();
                let wider = index.nearby_within(centre, within, room);
                for _ in 0..3 {
                    let q = centre + room * unit(&mut rng);
                    let got = index.nearest_nearby(&near, q).expect("within the ball");
                    let tree = index.nearest(q, f64::INFINITY).expect("a nearest point");
                    assert_eq!(
                        got,
                        tree,
                        "{}: {q} in a ball of {room} m about {centre}",
                        path.display()
                    );
                    assert_eq!(index.nearest_nearby(&wider, q), Some(tree), "{q}: in the wider ball");
                    let truth = brute_distance(&shell, q);
                    assert!((got.distance - truth).abs() < 1e-12, "{q}: {} vs {truth}", got.distance);
                    scanned += 1;
                }
                let away = centre + 1.01 * room * unit(&mut rng).normalize_or(DVec3::X);
                assert!(index.nearest_nearby(&near, away).is_none(), "{away}: outside the ball");
                declined += 1;
            }
        }
        assert!(
            scanned > 300 && declined > 100,
            "{scanned} scanned, {declined} declined"
        );
    }
}

/// On every shipped body, clearing a point off the body while keeping the ball about where
/// it stops ([`BodyProbe::clear_keeping_ball`], as the assembly clears a patch's samples)
/// gives the point and nearest point of the clearing by tree searches, bit for bit, and
/// the distance of a scan of every shell triangle (a point left where it was stands the
/// clearance off by that scan); it keeps
/// a ball exactly when the point moved, and the ball's searches anywhere within it give
/// the tree's answers. Garment points moved up to 2 cm either way, so that some start
/// inside the body, at a tight and a loose clearance.
#[test]
fn clearing_that_keeps_its_ball_equals_clearing_by_tree_searches_on_every_body() {
    use drape::garment::BodyProbe;
    let garment: Vec<DVec3> = real_jumpsuit().m0.mesh.positions.clone();
    let mut rng = Lcg(31);
    let unit = in_unit_ball;
    for path in &shipped_bodies() {
        let (_, index, shell, shift) = on_body(path);
        let probe = BodyProbe::from_index(index);
        let (mut moved, mut still, mut searched) = (0, 0, 0);
        for p in garment.iter().step_by(11) {
            for gap in [0.004, 0.02] {
                let start = *p + shift + 0.02 * unit(&mut rng);
                let (q, n, ball) = probe.clear_keeping_ball(start, gap);
                let (want_q, want_n) = probe.clear_measuring(start, gap);
                assert_eq!((q, n), (want_q, want_n), "{}: {start} cleared by {gap}", path.display());
                assert_eq!(ball.is_some(), q != start, "{start}: a ball exactly when moved");
                // And against a scan of every shell triangle: the nearest distance where it
                // stops (and a point left where it was stood the clearance off).
                let truth = brute_distance(&shell, q);
                let found = n.expect("a nearest point");
                assert!(
                    (found.distance - truth).abs() < 1e-12,
                    "{q}: {} vs {truth}",
                    found.distance
                );
                if q == start {
                    assert!(
                        truth >= gap * (1.0 - 1e-6) && found.signed(q) > 0.0,
                        "{q}: left at {truth}"
                    );
                }
                let Some(ball) = ball else {
                    still += 1;
                    continue;
                };
                moved += 1;
                for _ in 0..2 {
                    let r = 0.5 * gap * unit(&mut rng);
                    let Some(got) = probe.index().nearest_nearby(&ball, q + r) else {
                        // Outside the ball: the ball may be centred where an earlier pass stood.
                        continue;
                    };
                    assert_eq!(Some(got), probe.index().nearest(q + r, f64::INFINITY), "{}", q + r);
                    searched += 1;
                }
            }
        }
        assert!(
            moved > 100 && still > 100 && searched > 100,
            "{moved} moved, {still} still, {searched} searched"
        );
    }
}

/// The body's nearest points the assembly hands to the collision (found while clearing the
/// patches' samples off the body) are the nearest points of the M0 vertices they name: their
/// distances agree with a scan of every shell triangle written in the test, their sides
/// with ray parity, on the jumpsuit on the shipped body.
#[test]
fn the_assemblys_measured_nearest_points_agree_with_a_brute_force() {
    let fw = real_jumpsuit();
    let probe = super::common::real_probe();
    let body = super::common::real_body();
    let built = drape::garment::assemble::assemble(fw, probe, None).expect("assembles");
    let shell = TriMesh {
        positions: body.mesh.mesh.positions.clone(),
        triangles: probe
            .index()
            .shell_triangles()
            .map(|t| body.mesh.mesh.triangles[t as usize])
            .collect(),
    };
    assert!(
        built.measured.len() > built.m0.mesh.positions.len() / 2,
        "{} measured",
        built.measured.len()
    );
    for (v, n) in built.measured.iter().step_by(7) {
        let p = &built.m0.mesh.positions[*v as usize];
        let truth = brute_distance(&shell, *p);
        assert!((n.distance - truth).abs() < 1e-12, "{p}: {} vs {truth}", n.distance);
        if truth > 1e-6 {
            assert_eq!(n.signed(*p) < 0.0, inside_by_parity(&body.mesh.mesh, *p), "{p}: side");
        }
    }
}

/// An assembly that takes the unchanged contours' cleared spans (and patches, and M0's faces
/// and edges) from the framework before gives what an assembly from nothing gives, sample
/// for sample and edge for edge, after one contour's shape changed (a clamped end slope
/// where it was natural): and it did take some.
#[test]
fn an_assembly_reusing_the_last_frameworks_spans_equals_one_from_nothing() {
    let before = real_jumpsuit();
    let probe = super::common::real_probe();
    let mut after = before.clone();
    let contour = after
        .contours
        .iter_mut()
        .find(|c| c.tangents[0].is_none())
        .expect("a contour with a natural end");
    let slope = (contour.end_tangent(0) + DVec3::new(0.15, 0.0, 0.1)).normalize();
    let name = contour.name.clone();
    contour
        .refit(contour.points.clone(), [Some(slope), contour.tangents[1]])
        .expect("refits");
    let reused = drape::garment::assemble::assemble(&after, probe, Some(before)).expect("assembles");
    let fresh = drape::garment::assemble::assemble(&after, probe, None).expect("assembles");
    assert!(
        reused.resurfaced.len() < fresh.resurfaced.len(),
        "{name}: every patch surfaced again"
    );
    assert!(!reused.resurfaced.is_empty(), "{name}: no patch surfaced again");
    assert_eq!(reused.spans, fresh.spans, "{name}: spans");
    assert_eq!(reused.patches, fresh.patches, "{name}: patches");
    // M0 whole: positions, faces, edges, welds (the faces and edges taken from before).
    assert_eq!(reused.m0, fresh.m0, "{name}: M0");
    let changed = reused.spans.keys().filter(|k| k.0 == name).count();
    assert!(
        changed > 0 && changed < reused.spans.len(),
        "{changed} of {} spans on {name}",
        reused.spans.len()
    );
}
