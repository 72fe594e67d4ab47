//! NURBS collision: derivatives against finite differences of the Cox-de Boor definition,
//! hulls that contain their sub-surfaces and overlap exactly when the intervals written
//! here overlap, the true distance against a brute-force search, the control-point
//! distance's convergence within the nets' measured deviation, the `.nurbs` files, and the
//! experiment's poses and crossing verdicts.

use drape::nurbs::{
    Direction, ExperimentOptions, Kdop, NurbsSurface, PatchTree, coverage, experiment, file, nearest_control_points,
    net_deviation, pairs_within, run_experiment, shipped_pair, surface_distance,
};
use glam::{DMat3, DVec3};

use super::common::Lcg;
use super::nurbs::{random_surface, reference};

/// The paper's 7 directions (not normalised), written here apart from the library's.
const DIRECTIONS: [[f64; 3]; 7] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, -1.0],
    [1.0, -1.0, -1.0],
];

/// Whether two point sets' projections overlap on every direction.
fn intervals_overlap(a: &[DVec3], b: &[DVec3]) -> bool {
    DIRECTIONS.iter().all(|d| {
        let d = DVec3::from_array(*d);
        let range = |s: &[DVec3]| {
            s.iter()
                .map(|p| p.dot(d))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)))
        };
        let ((a0, a1), (b0, b1)) = (range(a), range(b));
        a1 >= b0 && b1 >= a0
    })
}

#[test]
fn first_and_second_derivatives_agree_with_finite_differences_of_the_definition() {
    let mut rng = Lcg(41);
    for (degree, count) in [([3, 2], [6, 5]), ([3, 3], [7, 7]), ([2, 4], [5, 6])] {
        let (s, kn, pts, w) = random_surface(&mut rng, degree, count);
        let f = |u: f64, v: f64| reference(degree, &kn, count, &pts, &w, u, v);
        let near_knot = |t: f64, k: &[f64]| k.iter().any(|&x| (x - t).abs() < 1e-3);
        let mut checked = 0;
        while checked < 60 {
            let (u, v) = (0.01 + 0.98 * rng.next(), 0.01 + 0.98 * rng.next());
            if near_knot(u, &kn[0]) || near_knot(v, &kn[1]) {
                continue;
            }
            checked += 1;
            let j = s.jet(u, v);
            let h = 1e-5;
            let du = (f(u + h, v) - f(u - h, v)) / (2.0 * h);
            let dv = (f(u, v + h) - f(u, v - h)) / (2.0 * h);
            let scale = du.length().max(dv.length()).max(1e-3);
            assert!(j.point.distance(f(u, v)) <= 1e-12);
            assert!(
                (j.du - du).length() <= 1e-6 * scale,
                "du at ({u}, {v}): {} vs {du}",
                j.du
            );
            assert!(
                (j.dv - dv).length() <= 1e-6 * scale,
                "dv at ({u}, {v}): {} vs {dv}",
                j.dv
            );
            let h = 1e-4;
            let duu = (f(u + h, v) - 2.0 * f(u, v) + f(u - h, v)) / (h * h);
            let dvv = (f(u, v + h) - 2.0 * f(u, v) + f(u, v - h)) / (h * h);
            let duv = (f(u + h, v + h) - f(u + h, v - h) - f(u - h, v + h) + f(u - h, v - h)) / (4.0 * h * h);
            let scale2 = j.duu.length().max(j.dvv.length()).max(j.duv.length()).max(1e-2);
            for (name, got, want) in [("duu", j.duu, duu), ("duv", j.duv, duv), ("dvv", j.dvv, dvv)] {
                assert!(
                    (got - want).length() <= 1e-4 * scale2,
                    "{name} degree {degree:?} at ({u}, {v}): {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn the_hull_of_every_sub_surface_contains_its_points_sampled_on_the_original() {
    let mut rng = Lcg(51);
    for (degree, count) in [([3, 3], [9, 9]), ([2, 3], [5, 8]), ([3, 1], [6, 3])] {
        let (s, ..) = random_surface(&mut rng, degree, count);
        for level in 0..=3u8 {
            let tree = PatchTree::build(&s, level);
            assert_eq!(tree.patches.len(), 4usize.pow(u32::from(level)));
            let mut area = 0.0;
            for p in &tree.patches {
                let hull = Kdop::from_points(p.points.iter().copied());
                let [(u0, u1), (v0, v1)] = p.range;
                area += (u1 - u0) * (v1 - v0);
                for a in 0..7 {
                    for b in 0..7 {
                        let (u, v) = (u0 + (u1 - u0) * a as f64 / 6.0, v0 + (v1 - v0) * b as f64 / 6.0);
                        let x = s.point(u, v);
                        assert!(
                            hull.contains(x, 1e-12),
                            "level {level}: ({u}, {v}) outside its leaf's hull"
                        );
                    }
                }
            }
            assert!((area - 1.0).abs() < 1e-12, "the leaves tile the range: {area}");
        }
    }
}

#[test]
fn hulls_overlap_exactly_when_the_intervals_on_all_seven_directions_do() {
    let mut rng = Lcg(61);
    let (mut overlapping, mut apart) = (0, 0);
    for _ in 0..3000 {
        let cloud = |rng: &mut Lcg, c: DVec3| -> Vec<DVec3> {
            (0..12)
                .map(|_| c + DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 0.3)
                .collect()
        };
        let a = cloud(&mut rng, DVec3::ZERO);
        let c = DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 0.6;
        let b = cloud(&mut rng, c);
        let want = intervals_overlap(&a, &b);
        let got = Kdop::from_points(a.iter().copied()).overlaps(&Kdop::from_points(b.iter().copied()));
        assert_eq!(got, want, "clouds {a:?} and {b:?}");
        if want { overlapping += 1 } else { apart += 1 }
    }
    assert!(overlapping > 500 && apart > 500, "both cases: {overlapping} / {apart}");
    // The descent of two trees finds exactly the leaf pairs whose hulls overlap.
    let (s, ..) = random_surface(&mut rng, [3, 3], [6, 6]);
    let (t, ..) = random_surface(&mut rng, [2, 3], [5, 6]);
    let t = t.mapped(
        DMat3::from_rotation_x(1.2) * DMat3::from_rotation_y(0.4),
        DVec3::new(0.1, 0.05, 0.1),
    );
    let (a, b) = (PatchTree::build(&s, 3), PatchTree::build(&t, 3));
    let (pairs, tests) = pairs_within(&a, &b, 0.0);
    let mut want = Vec::new();
    for (i, p) in a.patches.iter().enumerate() {
        for (j, q) in b.patches.iter().enumerate() {
            if intervals_overlap(&p.points, &q.points) {
                want.push([i as u32, j as u32]);
            }
        }
    }
    let got: Vec<[u32; 2]> = pairs.iter().map(|p| p.patches).collect();
    assert!(!want.is_empty(), "the surfaces cross");
    assert_eq!(got, want);
    assert!(
        tests < (64 * 64) as u64,
        "the hierarchy discards early: {tests} hull tests"
    );
}

/// Brute force: the least distance over grids of both surfaces, then over fine grids
/// around the best coarse pair.
fn brute_distance(a: &NurbsSurface, b: &NurbsSurface) -> f64 {
    let grid = |s: &NurbsSurface, n: usize, lo: [f64; 2], hi: [f64; 2]| -> Vec<(DVec3, [f64; 2])> {
        let mut out = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let u = lo[0] + (hi[0] - lo[0]) * i as f64 / (n - 1) as f64;
                let v = lo[1] + (hi[1] - lo[1]) * j as f64 / (n - 1) as f64;
                out.push((s.point(u, v), [u, v]));
            }
        }
        out
    };
    let best_pair = |ga: &[(DVec3, [f64; 2])], gb: &[(DVec3, [f64; 2])]| {
        let mut best = (f64::INFINITY, [0.0; 2], [0.0; 2]);
        for (p, s) in ga {
            for (q, t) in gb {
                let d = p.distance(*q);
                if d < best.0 {
                    best = (d, *s, *t);
                }
            }
        }
        best
    };
    let n = 70;
    let (d0, s, t) = best_pair(&grid(a, n, [0.0; 2], [1.0; 2]), &grid(b, n, [0.0; 2], [1.0; 2]));
    let h = 2.0 / (n - 1) as f64;
    let window = |c: [f64; 2]| {
        (
            [(c[0] - h).max(0.0), (c[1] - h).max(0.0)],
            [(c[0] + h).min(1.0), (c[1] + h).min(1.0)],
        )
    };
    let ((la, ha), (lb, hb)) = (window(s), window(t));
    let (d1, ..) = best_pair(&grid(a, 60, la, ha), &grid(b, 60, lb, hb));
    d0.min(d1)
}

#[test]
fn the_true_distance_matches_a_brute_force_search() {
    let mut rng = Lcg(71);
    for k in 0..6 {
        let (s, ..) = random_surface(&mut rng, [3, 3], [5, 5]);
        let (t, ..) = random_surface(&mut rng, [3, 2], [4, 5]);
        // Tilted and lifted a little above the first, so the nearest points are interior.
        let lift = 0.02 + 0.03 * k as f64;
        let t = t.mapped(
            DMat3::from_rotation_z(0.1 * k as f64) * DMat3::from_rotation_y(0.7),
            DVec3::new(0.15, lift, 0.05),
        );
        let found = surface_distance(&PatchTree::build(&s, 3), &PatchTree::build(&t, 3));
        let brute = brute_distance(&s, &t);
        let d = found.best.distance;
        assert!(d <= brute + 1e-12, "pair {k}: {d} above the brute force {brute}");
        assert!(brute - d <= 2e-6, "pair {k}: {d} far below the brute force {brute}");
        // The points it reports are on the surfaces at the parameters it reports.
        let [u, v, s2, t2] = found.best.params;
        assert!(found.best.points[0].distance(s.point(u, v)) <= 1e-12);
        assert!(found.best.points[1].distance(t.point(s2, t2)) <= 1e-12);
    }
}

#[test]
fn the_control_point_distance_converges_within_the_nets_measured_deviation() {
    let mut rng = Lcg(81);
    let (mut dev_ratios, mut cov_ratios) = (Vec::new(), Vec::new());
    for k in 0..10 {
        let (s, ..) = random_surface(&mut rng, [3, 3], [5, 6]);
        let (t, ..) = random_surface(&mut rng, [3, 3], [6, 5]);
        let t = t.mapped(
            DMat3::from_rotation_x(0.3 + 0.1 * k as f64) * DMat3::from_rotation_y(0.5),
            DVec3::new(0.1 * rng.next(), 0.03 + 0.02 * rng.next(), 0.1 * rng.next()),
        );
        let truth = surface_distance(&PatchTree::build(&s, 4), &PatchTree::build(&t, 4)).best;
        let mut last: Option<([f64; 2], [f64; 2])> = None;
        for level in 1..=6u8 {
            let (a, b) = (PatchTree::build(&s, level), PatchTree::build(&t, level));
            let cp = nearest_control_points(&a, &b).distance;
            let dev = [net_deviation(&a), net_deviation(&b)];
            let cov = [coverage(&a, 9), coverage(&b, 9)];
            // Below the truth by at most the nets' distance from their surfaces.
            assert!(
                truth.distance - cp <= dev[0] + dev[1] + 1e-12,
                "pair {k} level {level}: cp {cp} truth {} dev {dev:?}",
                truth.distance
            );
            // Above it by at most how far the true nearest points are from a control point.
            let nearest_cp = |tree: &PatchTree, p: DVec3| {
                tree.patches
                    .iter()
                    .flat_map(|q| q.points.iter())
                    .map(|q| q.distance(p))
                    .fold(f64::INFINITY, f64::min)
            };
            let reach = nearest_cp(&a, truth.points[0]) + nearest_cp(&b, truth.points[1]);
            assert!(cp - truth.distance <= reach + 1e-12, "pair {k} level {level}");
            assert!(
                cp - truth.distance <= cov[0] + cov[1] + 1e-9,
                "pair {k} level {level}: {cov:?}"
            );
            if let Some((d, c)) = last
                && level >= 5
            {
                // The deepest levels, where the rates have settled (a doubled knot, or a
                // strongly rational net, slows the first levels).
                for side in 0..2 {
                    dev_ratios.push(d[side] / dev[side]);
                    cov_ratios.push(c[side] / cov[side]);
                }
            }
            last = Some((dev, cov));
        }
    }
    let geo = |r: &[f64]| (r.iter().map(|x| x.ln()).sum::<f64>() / r.len() as f64).exp();
    let (dev, cov) = (geo(&dev_ratios), geo(&cov_ratios));
    println!("per level: net deviation shrinks {dev:.2}x, coverage {cov:.2}x (geometric means)");
    assert!(
        (3.2..=4.6).contains(&dev),
        "the net's deviation shrinks about fourfold: {dev}"
    );
    assert!(
        (1.6..=2.3).contains(&cov),
        "the control points' coverage about halves: {cov}"
    );
}

#[test]
fn the_shipped_nets_have_the_papers_counts_are_rational_on_non_uniform_knots_and_round_trip() {
    let (butterfly, leaf) = shipped_pair().expect("the shipped nets parse");
    assert_eq!(butterfly.count(), [9, 9]);
    assert_eq!(butterfly.net().len(), 81);
    assert_eq!(leaf.count(), [7, 25]);
    assert_eq!(leaf.net().len(), 175);
    for s in [&butterfly, &leaf] {
        let weights: Vec<f64> = s.net().iter().map(|h| h.w).collect();
        assert!(weights.iter().any(|&w| w != weights[0]), "rational");
        for dir in [Direction::U, Direction::V] {
            let k = &s.knots()[dir.index()];
            let p = s.degree()[dir.index()];
            let spans: Vec<f64> = k[p..k.len() - p].windows(2).map(|w| w[1] - w[0]).collect();
            assert!(
                spans.iter().any(|&d| (d - spans[0]).abs() > 1e-6),
                "non-uniform in {dir}"
            );
        }
        let again = file::parse(&file::write("x", s)).expect("round trip").surface;
        for (u, v) in [(0.1, 0.2), (0.5, 0.5), (0.93, 0.71)] {
            assert!(again.point(u, v).distance(s.point(u, v)) <= 1e-15);
        }
    }
    assert!(experiment::BUTTERFLY.contains("scripts/make_nurbs_assets.py"));
}

#[test]
fn bad_nurbs_files_are_refused_naming_the_line_or_what_is_missing() {
    let good = experiment::BUTTERFLY;
    let cases: [(String, &str); 6] = [
        (good.replace("nurbs 1", "nurbs 2"), "format version 2"),
        (good.replace("degree 3 3", "degree 3 x"), "`x` is not a number"),
        (good.replacen("point ", "pointy ", 1), "unknown keyword `pointy`"),
        (good.replace("knots v", "# knots v"), "no `knots v` line"),
        (
            good.replacen("point -0.", "point 0.1 -0.", 1),
            "point (x y z w) takes 4 numbers, got 5",
        ),
        (
            good.replace("count 9 9", "count 9 8"),
            "knot vector in v has 13 knots, expected 12",
        ),
    ];
    for (text, want) in cases {
        let e = file::parse(&text).unwrap_err().to_string();
        assert!(e.contains(want), "{e} lacks {want}");
    }
    let e = file::parse(&good.replace("degree 3 3", "degree 3 x"))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("line 5:"), "{e}");
}

#[test]
fn the_experiment_holds_the_butterfly_at_its_distance_and_detects_the_crossing_at_every_level() {
    let (butterfly, leaf) = shipped_pair().expect("shipped");
    let options = ExperimentOptions {
        levels: 2..=4,
        timing_ms: 0.0,
        coverage_samples: 3,
        ..ExperimentOptions::default()
    };
    let e = run_experiment(&butterfly, &leaf, &options);
    // The truth, by brute force on the placed surfaces.
    let brute = brute_distance(&e.near, &e.leaf);
    for r in &e.levels {
        assert!(
            (r.true_distance_m - options.near_distance_m).abs() <= 1e-7,
            "level {}: {}",
            r.level,
            r.true_distance_m
        );
        assert!(
            r.true_distance_m <= brute + 1e-12 && brute - r.true_distance_m <= 2e-5,
            "brute {brute}"
        );
        // The paper's figure, by brute force: every control point of every leaf of one
        // surface against every one of the other's, no hull passed by.
        let points = |s: &NurbsSurface| -> Vec<DVec3> {
            PatchTree::build(s, r.level)
                .patches
                .iter()
                .flat_map(|p| p.surface.control_points().collect::<Vec<_>>())
                .collect()
        };
        let (a, b) = (points(&e.near), points(&e.leaf));
        let cp = a
            .iter()
            .flat_map(|p| b.iter().map(move |q| p.distance(*q)))
            .fold(f64::INFINITY, f64::min);
        assert!(
            (r.cp_min_distance_m - cp).abs() <= 1e-12,
            "level {}: {} against the brute force {cp}",
            r.level,
            r.cp_min_distance_m
        );
        assert!(r.pairs_tested > 0);
    }
    assert_eq!(e.crossing.len(), 3);
    for c in &e.crossing {
        assert!(c.detected, "level {}: crossing missed", c.level);
        assert!(c.true_distance_m <= 1e-9, "level {}: {}", c.level, c.true_distance_m);
    }
    // The crossing pose does cross: butterfly points lie on both sides of the leaf (the
    // side of the nearest leaf sample's normal), well away from it.
    let (positions, _) = e.crossing_butterfly.grid(30, 30);
    let n = 80;
    let leaf_samples: Vec<(DVec3, DVec3)> = (0..n * n)
        .map(|k| {
            let j = leaf.jet((k / n) as f64 / (n - 1) as f64, (k % n) as f64 / (n - 1) as f64);
            (j.point, j.du.cross(j.dv).normalize())
        })
        .collect();
    let sides: Vec<f64> = positions
        .iter()
        .map(|p| {
            let (q, normal) = leaf_samples
                .iter()
                .min_by(|a, b| a.0.distance(*p).total_cmp(&b.0.distance(*p)))
                .expect("samples");
            (*p - *q).dot(*normal)
        })
        .collect();
    assert!(
        sides.iter().any(|&s| s < -5e-4) && sides.iter().any(|&s| s > 5e-4),
        "one side only"
    );
}

/// One `nurbs` stage: its step, the parts' surfaces after it, its contacts and refusal.
type NurbsStageSeen = (
    usize,
    Vec<(String, NurbsSurface)>,
    Vec<drape::nurbs::Contact>,
    Option<String>,
);

/// Every `nurbs` stage of a run.
#[derive(Default)]
struct NurbsStages(Vec<NurbsStageSeen>);

impl drape::session::StageSink for NurbsStages {
    fn nurbs(
        &mut self,
        info: &drape::session::StageInfo,
        stage: drape::session::NurbsStage<'_>,
    ) -> Result<(), drape::session::SinkError> {
        let parts = stage
            .parts
            .iter()
            .map(|p| (p.name.clone(), p.surface.clone()))
            .collect();
        self.0.push((
            info.step,
            parts,
            stage.contacts.to_vec(),
            stage.refused.map(str::to_string),
        ));
        Ok(())
    }
}

fn run_nurbs_session(text: &str) -> (drape::session::RunReport, NurbsStages) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/sessions");
    let session = drape::session::parse_session(text, "nurbs-test.drape", &dir).expect("parses");
    let mut sink = NurbsStages::default();
    let report = drape::session::run_session(&session, &drape::session::RunOptions::default(), &mut [&mut sink]);
    (report, sink)
}

#[test]
fn a_part_moved_into_the_body_is_refused_and_stays_outside_by_the_ray_parity_truth() {
    let (report, stages) = run_nurbs_session(
        "drape 1\nbody builtin\nnurbs \"../nurbs/butterfly.nurbs\" name=b\nmove b by=0.25,1.40,0\n\
         move b by=-0.20,0,0\nmove b by=-0.05,0,0 turn=90\n",
    );
    assert!(report.error.is_none(), "{:?}", report.error);
    assert_eq!(stages.0.len(), 4);
    let mesh = &super::common::real_body().mesh.mesh;
    let inside_count = |s: &NurbsSurface| {
        let (points, _) = s.grid(30, 30);
        points
            .iter()
            .filter(|p| super::common::inside_by_parity(mesh, **p))
            .count()
    };
    // Step 3 (into the shoulder) is refused: the move would put points inside the body by
    // the independent truth, and the part stays where step 2 left it.
    let (_, before, _, _) = &stages.0[1];
    let (_, after, contacts, refused) = &stages.0[2];
    let why = refused.as_deref().expect("refused");
    assert!(
        why.contains("'b' would have") && why.contains("inside the body"),
        "{why}"
    );
    assert_eq!(before[0].1, after[0].1, "the part stays");
    let would = before[0].1.mapped(DMat3::IDENTITY, DVec3::new(-0.20, 0.0, 0.0));
    assert!(inside_count(&would) > 0, "the truth agrees the move goes into the body");
    assert!(contacts.iter().any(|c| c.other == "body" && c.colliding));
    // Every accepted pose is outside the body by the truth.
    for (step, parts, _, refused) in &stages.0 {
        if refused.is_none() {
            assert_eq!(inside_count(&parts[0].1), 0, "step {step}");
        }
    }
    assert_eq!(report.shortfalls.len(), 1, "{:?}", report.shortfalls);
}

#[test]
fn parts_collide_with_each_other_by_their_true_distance_and_a_scene_without_parts_does_no_nurbs_work() {
    // The butterfly held 0.7 mm over the leaf (the experiment's pose): not colliding at the
    // 0.5 mm threshold. The leaf moved away, then back and 0.4 mm up towards it: refused,
    // with the distance the brute force finds for that pose.
    let (butterfly, leaf) = shipped_pair().expect("shipped");
    let held = experiment::hold_at(&butterfly, &leaf, ExperimentOptions::default().pose, 0.7e-3);
    let placed = experiment::place(&butterfly, &leaf, held);
    let dir = std::env::temp_dir().join("drape-nurbs-session");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("placed.nurbs");
    std::fs::write(&path, file::write("placed", &placed)).expect("written");
    let text = format!(
        "drape 1\nbody builtin\nnurbs \"../nurbs/corn-leaf.nurbs\" name=leaf\nnurbs \"{}\" name=b\nmove leaf by=0.5,0,0\nmove leaf by=-0.5,0.0004,0\n",
        path.display()
    );
    let (report, stages) = run_nurbs_session(&text);
    assert!(report.error.is_none(), "{:?}", report.error);
    let (_, _, contacts, refused) = &stages.0[1];
    assert!(refused.is_none());
    assert!(contacts.iter().all(|c| !c.colliding), "{contacts:?}");
    if let Some(c) = contacts.iter().find(|c| c.other == "leaf") {
        assert!((c.distance_m - 0.7e-3).abs() <= 1e-6, "{}", c.distance_m);
    }
    assert!(stages.0[2].3.is_none(), "moving away is accepted");
    let why = stages.0[3].3.as_deref().expect("refused");
    assert!(why.contains("'leaf' would come") && why.contains("from 'b'"), "{why}");
    let raised = leaf.mapped(DMat3::IDENTITY, DVec3::new(0.0, 0.0004, 0.0));
    let brute = brute_distance(&placed, &raised);
    let c = stages.0[3].2.iter().find(|c| c.other == "b").expect("the contact");
    // The brute force's grids over the 0.6 m leaf resolve to a few micrometres.
    assert!(
        c.distance_m <= brute + 1e-12 && brute - c.distance_m <= 1e-5 && brute < 0.5e-3,
        "{} vs brute {brute}",
        c.distance_m
    );
    assert_eq!(stages.0[3].1[0].1, stages.0[2].1[0].1, "the leaf stays where it was");
    // Without parts: no NURBS timings, no NURBS stages.
    let (report, stages) = run_nurbs_session("drape 1\nbody builtin\nsection y=1.0 name=waist\n");
    assert!(report.error.is_none());
    assert!(stages.0.is_empty());
    for step in &report.steps {
        assert!(
            step.timings_ms.keys().all(|k| !k.starts_with("nurbs")),
            "{:?}",
            step.timings_ms
        );
    }
}

#[test]
fn nurbs_steps_with_bad_files_or_unknown_parts_name_the_problem() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/sessions");
    let e = drape::session::parse_session("drape 1\nmove wing by=0,1,0\n", "x.drape", &dir).unwrap_err();
    assert!(e.to_string().contains("no NURBS part 'wing'"), "{e}");
    let e = drape::session::parse_session(
        "drape 1\nnurbs \"../nurbs/butterfly.nurbs\" name=b\nnurbs \"../nurbs/butterfly.nurbs\" name=b\n",
        "x.drape",
        &dir,
    )
    .unwrap_err();
    assert!(e.to_string().contains("already added on line 2"), "{e}");
    let e = drape::session::parse_session("drape 1\nnurbs \"a.nurbs\" name=b\nmove b\n", "x.drape", &dir).unwrap_err();
    assert!(e.to_string().contains("expected by=x,y,z"), "{e}");
    let (report, _) = run_nurbs_session("drape 1\nbody builtin\nnurbs \"missing.nurbs\" name=m\n");
    let e = report.error.expect("fails").to_string();
    assert!(e.contains("NURBS part 'm'") && e.contains("missing.nurbs"), "{e}");
}
