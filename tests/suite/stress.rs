//! Stress: the bounded sweep CI runs (`drape stress --sessions 20 --seed 1` on the shipped
//! body), its last garments checked against the brute-force truth; shards that merge into
//! the whole sweep; and every session a stress run found a bug with, kept as a regression.

use std::path::{Path, PathBuf};

use super::common::LastGarment;
use drape::collision::ground_truth;
use drape::session::{RunOptions, parse_session, run_session};
use drape::stress::{StressOptions, run_one, sessions_of};

/// `drape stress ARGS` as JSON; it must exit 0 (1 would mean it found a bug: a panic, a
/// non-finite output or a garment left in the body).
fn stress_json(args: &[&str]) -> serde_json::Value {
    let out = super::common::drape_cli()
        .arg("stress")
        .args(args)
        .output()
        .expect("drape stress runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.code() == Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("not JSON ({e}): {stdout}"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("drape-stress-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The CI sweep reports no panic, no NaN and no garment left in the body, and exits 0;
/// and it is not idle: most steps are accepted and some are refused. Then, independently
/// of drape's own quality check, the garment each session ends with is tested by the
/// brute-force truth (winding number for every vertex, every edge against every body
/// triangle): nothing inside, nothing crossing.
#[test]
fn the_ci_sweep_on_the_shipped_body_finds_no_bug_and_its_garments_are_clear() {
    let all = &sweep_without_bugs("ci", &["--sessions", "20"]);
    let steps = all["steps"].as_u64().unwrap();
    let accepted = all["accepted"].as_u64().unwrap();
    assert!(steps >= 150 && accepted * 2 > steps, "{all}");
    assert!(!all["refused"].as_object().unwrap().is_empty(), "{all}");
    // Why the loops stopped: the solver and the bisections report, and a solve or a
    // bisection that says it converged is within its stated tolerance (the solver's
    // below; 1e-13 of a ring's size, at most a body height of 2.5 m; 1e-12 of a chord
    // under 2.5 m).
    let loops = &all["loops"];
    for (name, bound) in [
        // A solve is converged only within 6e-7 of the body's height (under 2.5 m) for a
        // residual in metres, 6e-7 rad for an angle.
        ("constraint.passes", 1.5e-6),
        ("garment.ease.bisection", 2.5e-13),
        ("garment.resample.bisection", 2.5e-12),
    ] {
        let l = &loops[name];
        assert!(l["converged"].as_u64().unwrap() > 0, "{name}: {l}");
        assert!(l["max_residual_converged"].as_f64().unwrap() <= bound, "{name}: {l}");
    }

    let body = super::common::real_body();
    let options = StressOptions {
        sessions: 20,
        seed: 1,
        ..StressOptions::default()
    };
    let mut checked = 0;
    for (k, text) in sessions_of(&options) {
        let session = parse_session(&text, "stress.drape", Path::new(".")).expect("parses");
        let mut last = LastGarment::default();
        run_session(&session, &RunOptions::default(), &mut [&mut last]);
        let Some((positions, edges, triangles)) = last.0 else {
            continue;
        };
        let truth = ground_truth(&body.mesh.mesh, &positions, &edges);
        assert_eq!(
            (truth.inside_count(), truth.crossing.iter().filter(|c| **c).count()),
            (0, 0),
            "session {k}:\n{text}"
        );
        let pierced = super::common::faces_pierced_by(&body.mesh.mesh, &positions, &triangles);
        assert!(pierced.is_empty(), "session {k}: faces pierced {pierced:?}\n{text}");
        checked += 1;
    }
    assert!(checked >= 15, "{checked} sessions ended with a garment");
}

/// `drape stress ARGS --seed 1 --json` (sessions that found a bug written to a scratch
/// folder named `name`): its overall figures, with no panic, non-finite value, guarantee
/// failure or session that did not parse.
fn sweep_without_bugs(name: &str, args: &[&str]) -> serde_json::Value {
    let dir = scratch(name);
    let mut all_args = args.to_vec();
    all_args.extend(["--seed", "1", "--json", "--out", dir.to_str().expect("a UTF-8 path")]);
    let all = stress_json(&all_args)["overall"].clone();
    for key in ["panics", "non_finite", "guarantee_failures", "parse_errors"] {
        assert_eq!(all[key], 0, "{key}: {all}");
    }
    std::fs::remove_dir_all(&dir).ok();
    all
}

/// A sweep split in three shards, each run alone and written with --report, merged by
/// `drape stress merge`, holds the same sessions with the same outcomes as the sweep run
/// whole (times aside, which no two runs share).
#[test]
fn three_shards_merged_equal_the_whole_sweep() {
    let dir = scratch("shards");
    let common = ["--sessions", "7", "--steps", "3", "--seed", "5", "--no-shrink"];
    let out = dir.join("out");
    let whole = stress_json(&[&common[..], &["--json", "--out", out.to_str().unwrap()]].concat());
    let mut reports = Vec::new();
    for i in 0..3 {
        let file = dir.join(format!("shard{i}.json"));
        let shard = format!("{i}/3");
        stress_json(
            &[
                &common[..],
                &[
                    "--shard",
                    &shard,
                    "--json",
                    "--report",
                    file.to_str().unwrap(),
                    "--out",
                    out.to_str().unwrap(),
                ],
            ]
            .concat(),
        );
        reports.push(file);
    }
    let mut args = vec!["merge".to_string(), "--json".to_string()];
    args.extend(reports.iter().map(|p| p.display().to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let merged = stress_json(&args);
    let without_times = |r: &serde_json::Value| -> Vec<serde_json::Value> {
        r["records"]
            .as_array()
            .expect("records")
            .iter()
            .map(|rec| {
                let mut rec = rec.clone();
                rec["outcome"]["step_ms"] = serde_json::Value::Null;
                rec
            })
            .collect()
    };
    assert_eq!(without_times(&whole).len(), 7);
    assert_eq!(without_times(&merged), without_times(&whole));
    assert_eq!(merged["shards"], serde_json::json!([[0, 3], [1, 3], [2, 3]]));
    std::fs::remove_dir_all(&dir).ok();
}

/// Every session a stress run found a bug with (shrunk, in tests/fixtures/stress/) runs
/// clean now: no panic, no non-finite output, no garment left in the body, every collision
/// verified (its quality check against the brute-force truth and a full check); and its
/// last garment passes the brute-force truth.
#[test]
fn every_stress_regression_session_runs_clean() {
    let mut files: Vec<PathBuf> = std::fs::read_dir("tests/fixtures/stress")
        .expect("tests/fixtures/stress")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "drape"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    let body = super::common::real_body();
    for file in files {
        let text = std::fs::read_to_string(&file).expect("reads");
        let outcome = run_one(&text, None, true);
        assert!(!outcome.is_bug(), "{}: {outcome:?}", file.display());
        assert!(outcome.verified.collisions > 0, "{}: {outcome:?}", file.display());
        assert!(outcome.failed.is_none(), "{}: {outcome:?}", file.display());
        let session = parse_session(&text, "fixture.drape", Path::new(".")).expect("parses");
        let mut last = LastGarment::default();
        run_session(&session, &RunOptions::default(), &mut [&mut last]);
        let (positions, edges, triangles) = last.0.expect("a garment");
        let truth = ground_truth(&body.mesh.mesh, &positions, &edges);
        assert_eq!(truth.inside_count(), 0, "{}", file.display());
        assert!(truth.crossing.iter().all(|c| !c), "{}", file.display());
        let pierced = super::common::faces_pierced_by(&body.mesh.mesh, &positions, &triangles);
        assert!(pierced.is_empty(), "{}: faces pierced {pierced:?}", file.display());
    }
}

/// `drape stress --verify` on every shipped body: each collision of a random session is
/// checked against the brute-force truth (winding number for every vertex, every edge
/// against every body triangle) and its partial quality check against a full one; none
/// disagrees, on any body, and the check did run (collisions, vertices and edges counted).
#[test]
fn verified_stress_sessions_on_every_shipped_body_agree_with_the_truth() {
    let options = StressOptions {
        sessions: 1,
        seed: 3,
        generate: drape::stress::GenerateOptions {
            steps: 4,
            ..Default::default()
        },
        ..StressOptions::default()
    };
    let (_, text) = sessions_of(&options).remove(0);
    for body in super::common::shipped_bodies() {
        let outcome = run_one(&text, Some(&body), true);
        let v = &outcome.verified;
        assert!(!outcome.is_bug(), "{}: {outcome:?}", body.display());
        assert!(v.collisions >= 2, "{}: {v:?}", body.display());
        assert!(v.vertices > 100 * v.collisions && v.edges > v.vertices, "{v:?}");
        assert_eq!(
            (&v.wrong_quality, &v.partial_differs),
            (&vec![], &vec![]),
            "{}",
            body.display()
        );
        assert_eq!(v.quality_ms.len(), v.collisions);
        // The inert and patch skips give the verdicts a detection testing every vertex
        // gives, and the exact point-face test misses nothing off the skin.
        assert_eq!(
            (v.skips_changed, v.missed_by.point_face),
            (0, 0),
            "{}: {v:?}",
            body.display()
        );
    }
}

/// Refusals name a limit of the user's edit, never a failure inside drape: a sweep of 75
/// random sessions on each shipped body (among them sessions whose solves left a patch's
/// corners a micrometre apart, and drags that fold a ring onto itself) refuses no edit for
/// a patch that cannot be surfaced or a curve that cannot be refitted, and leaves no
/// garment in the body.
#[test]
fn a_sweep_on_every_shipped_body_refuses_only_for_the_users_reasons() {
    let all = &sweep_without_bugs("reasons", &["--bodies", "assets/bodies", "--sessions", "75"]);
    let refused = all["refused"].as_object().expect("refusals by reason");
    let internal: Vec<&String> = refused
        .keys()
        .filter(|r| {
            ["cannot be surfaced", "cannot be refitted", "knots", "Coons"]
                .iter()
                .any(|w| r.contains(w))
        })
        .collect();
    assert!(internal.is_empty(), "internal reasons: {internal:?}");
    // The sweep did meet the edits that fold a curve: they are refused by name.
    assert!(
        refused.keys().any(|r| r.contains("would fold onto itself")),
        "{refused:?}"
    );
}
