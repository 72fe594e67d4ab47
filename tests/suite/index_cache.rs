//! The body index cache: an index read back from its file answers every query as the index
//! built in memory does (and as a brute-force search over the body's triangles), on every
//! shipped body; a damaged, truncated, foreign or unreadable file is never used; a session
//! logs the same figures and the same garment whether its index was built or read.

use std::path::{Path, PathBuf};

use drape::body::index::BodyIndex;
use drape::body::index_cache::{CacheOutcome, IndexCache};
use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::collision::SliceOptions;
use drape::mesh::TriMesh;
use drape::session::{RunOptions, parse_session, run_session};
use glam::DVec3;

use super::common::{LastGarment, Lcg, brute_distance, shipped_bodies};

/// A fresh folder under the system's temporary folder (removed by [`Folder`]'s drop).
struct Folder(PathBuf);

impl Folder {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("drape-test-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        Self(dir)
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn analyse(path: &Path) -> Body {
    let mesh = BodyMesh::load(&BodySource::File(path.to_path_buf()), 1.0).expect("body loads");
    Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("body analyses")
}

/// Points in the body's box grown by a tenth of its height, and points just off the skin
/// (vertices pushed a millimetre along their pseudo-normal, either way).
fn probes(index: &BodyIndex, n: usize, seed: u64) -> Vec<DVec3> {
    let lo = index.positions.iter().fold(DVec3::INFINITY, |a, &b| a.min(b)) - DVec3::splat(0.1 * index.height);
    let hi = index.positions.iter().fold(DVec3::NEG_INFINITY, |a, &b| a.max(b)) + DVec3::splat(0.1 * index.height);
    let mut rng = Lcg(seed);
    let mut out: Vec<DVec3> = (0..n)
        .map(|_| lo + (hi - lo) * DVec3::new(rng.next(), rng.next(), rng.next()))
        .collect();
    let step = (index.positions.len() / n).max(1);
    for (k, v) in (0..index.positions.len()).step_by(step).enumerate() {
        let side = if k % 2 == 0 { 1e-3 } else { -1e-3 };
        out.push(index.positions[v] + index.vertex_normals[v] * side);
    }
    out
}

/// `read` answers as `built` on `points`: nearest (whole body and each partition), winding
/// numbers and rays, field for field; the distances are the brute-force ones.
fn same_answers(name: &str, built: &BodyIndex, read: &BodyIndex, points: &[DVec3]) {
    assert_eq!(built.positions, read.positions, "{name}");
    assert_eq!(built.triangles, read.triangles, "{name}");
    assert_eq!(built.face_normals, read.face_normals, "{name}");
    assert_eq!(built.edge_normals, read.edge_normals, "{name}");
    assert_eq!(built.vertex_normals, read.vertex_normals, "{name}");
    assert_eq!(built.shell, read.shell, "{name}");
    assert_eq!(built.slices, read.slices, "{name}");
    assert_eq!(built.partitions.len(), read.partitions.len(), "{name}");
    for (a, b) in built.partitions.iter().zip(&read.partitions) {
        assert_eq!(
            (a.id, a.lower_y, a.upper_y, &a.triangles),
            (b.id, b.lower_y, b.upper_y, &b.triangles)
        );
    }
    let shell = TriMesh {
        positions: built.positions.clone(),
        triangles: built.shell_triangles().map(|t| built.triangles[t as usize]).collect(),
    };
    let reach = 0.05 * built.height;
    for (k, &p) in points.iter().enumerate() {
        let (a, b) = (built.nearest(p, f64::INFINITY), read.nearest(p, f64::INFINITY));
        assert_eq!(a, b, "{name}: nearest of point {k} {p}");
        assert_eq!(built.nearest(p, reach), read.nearest(p, reach), "{name}: point {k}");
        if k % 7 == 0 {
            let truth = brute_distance(&shell, p);
            let d = a.expect("a body has triangles").distance;
            assert!(
                (d - truth).abs() <= 1e-12 * built.height,
                "{name}: point {k}: {d} vs brute force {truth}"
            );
            assert_eq!(built.winding(p), read.winding(p), "{name}: winding at point {k}");
            let dir = (built.positions[k % built.positions.len()] - p).normalize_or_zero();
            assert_eq!(
                built.cast_ray(p, dir, 0.0, 2.0 * built.height),
                read.cast_ray(p, dir, 0.0, 2.0 * built.height),
                "{name}: ray from point {k}"
            );
        }
        let part = built.partition_at(p.y).expect("partitions");
        assert_eq!(
            built.nearest_in_partition(part, p, reach),
            read.nearest_in_partition(part, p, reach),
            "{name}: partition {part} of point {k}"
        );
    }
}

#[test]
fn a_cached_index_answers_as_the_built_one_on_every_shipped_body() {
    let folder = Folder::new("index-cache");
    let cache = IndexCache::new(&folder.0);
    let slices = SliceOptions::default();
    for (i, path) in shipped_bodies().iter().enumerate() {
        let name = path.display().to_string();
        let body = analyse(path);
        let (first, outcome) = cache.load_or_build(&body, &slices);
        let CacheOutcome::Built {
            path: file,
            unusable: None,
            write_error: None,
        } = outcome
        else {
            panic!("{name}: a fresh cache builds and writes: {outcome}");
        };
        assert!(file.exists(), "{name}: {} written", file.display());
        let (read, outcome) = cache.load_or_build(&body, &slices);
        assert!(
            matches!(outcome, CacheOutcome::Read(ref p) if *p == file),
            "{name}: {outcome}"
        );
        let built = BodyIndex::new(&body, &slices);
        let points = probes(&built, 300, 17 + i as u64);
        same_answers(&name, &built, &read, &points);
        same_answers(&name, &built, &first, &points[..50]);
    }
    // One file per body.
    let files = std::fs::read_dir(&folder.0).expect("the folder").count();
    assert_eq!(files, 5);
}

#[test]
fn a_damaged_truncated_or_foreign_cache_file_is_not_used_and_is_written_again() {
    let folder = Folder::new("index-cache-bad");
    let cache = IndexCache::new(&folder.0);
    let slices = SliceOptions::default();
    let bodies = shipped_bodies();
    let (body, other) = (analyse(&bodies[0]), analyse(&bodies[1]));
    let file = cache.path_for(&body, &slices);
    let built = BodyIndex::new(&body, &slices);
    let points = probes(&built, 60, 5);
    let _ = cache.load_or_build(&body, &slices);
    let good = std::fs::read(&file).expect("written");

    // Each bad file: not used (the reason named), the index built right, the file written
    // again whole (the next load reads it).
    let mut flipped = good.clone();
    let middle = flipped.len() / 2;
    flipped[middle] ^= 0x10;
    let mut garbage = b"not an index at all".to_vec();
    garbage.resize(200, b'x');
    let _ = cache.load_or_build(&other, &slices);
    let foreign = std::fs::read(cache.path_for(&other, &slices)).expect("the other body's file");
    let cases: [(&str, Vec<u8>, &str); 5] = [
        ("one bit flipped", flipped, "checksum"),
        ("truncated", good[..good.len() - 1000].to_vec(), "truncated"),
        (
            "cut inside the header",
            good[..20].to_vec(),
            "not a drape body index file",
        ),
        ("garbage", garbage, "not a drape body index file"),
        ("another body's file", foreign, "another body"),
    ];
    for (what, bytes, reason) in cases {
        std::fs::write(&file, &bytes).expect("writes the bad file");
        let (index, outcome) = cache.load_or_build(&body, &slices);
        let CacheOutcome::Built {
            unusable: Some(e),
            write_error: None,
            ..
        } = &outcome
        else {
            panic!("{what}: the file must not be used: {outcome}");
        };
        assert!(e.to_string().contains(reason), "{what}: {e}");
        same_answers(what, &built, &index, &points);
        assert_eq!(
            std::fs::read(&file).expect("rewritten"),
            good,
            "{what}: the file written again"
        );
        let (_, again) = cache.load_or_build(&body, &slices);
        assert!(matches!(again, CacheOutcome::Read(_)), "{what}: then read: {again}");
    }

    // A cache that cannot be written (its folder is a file) costs the build, nothing else.
    let blocked = folder.0.join("blocked");
    std::fs::write(&blocked, b"a file, not a folder").expect("writes");
    let (index, outcome) = IndexCache::new(&blocked).load_or_build(&body, &slices);
    assert!(
        matches!(
            outcome,
            CacheOutcome::Built {
                write_error: Some(_),
                ..
            }
        ),
        "{outcome}"
    );
    assert!(outcome.to_string().contains("not cached"), "{outcome}");
    same_answers("unwritable cache", &built, &index, &points);
}

/// The figures of every step and the last collided garment of a short session on `body`.
fn session_result(body: &Path, cache: Option<IndexCache>) -> (Vec<serde_json::Value>, Vec<DVec3>, Vec<Vec<String>>) {
    let text = "drape 1\nbody builtin\nunits m\ngarment jumpsuit fit=tight resolution=6\nset ease 0.004\n\
                drag waist.front_left by=0,0,0.02\n";
    let session = parse_session(text, "cache.drape", Path::new(".")).expect("parses");
    let options = RunOptions {
        body_override: Some(body.to_path_buf()),
        index_cache: cache,
        ..RunOptions::default()
    };
    let mut last = LastGarment::default();
    let report = run_session(&session, &options, &mut [&mut last]);
    assert!(report.error.is_none(), "{:?}", report.error);
    let figures = report
        .steps
        .iter()
        .map(|s| serde_json::Value::Object(s.figures.clone()))
        .collect();
    let notes = report.steps.iter().map(|s| s.notes.clone()).collect();
    (figures, last.0.expect("a collision ran").0, notes)
}

#[test]
fn a_session_gives_the_same_figures_and_garment_with_its_index_built_or_read() {
    let folder = Folder::new("index-cache-session");
    let body = &shipped_bodies()[3];
    let (figures, garment, notes) = session_result(body, None);
    assert!(notes.iter().all(Vec::is_empty), "no cache, no note: {notes:?}");
    for how in ["built", "read"] {
        let (f, g, notes) = session_result(body, Some(IndexCache::new(&folder.0)));
        assert_eq!(f, figures, "{how}: the same figures");
        assert_eq!(g.len(), garment.len());
        assert!(
            g.iter()
                .zip(&garment)
                .all(|(a, b)| a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits))
        );
        let said: Vec<&String> = notes.iter().flatten().collect();
        assert!(
            said.len() == 1 && said[0].starts_with(&format!("body index {how}")),
            "{how}: {said:?}"
        );
    }
}

/// The files of `dir` (none when it does not exist).
fn files_in(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    out.sort();
    out
}

/// `drape run` of a short session with `args`: the notes of its steps (from `--metrics`).
fn cli_notes(folder: &Path, args: &[&str]) -> Vec<String> {
    let session = folder.join("short.drape");
    std::fs::write(
        &session,
        "drape 1\nbody builtin\nunits m\nlog detail=metrics\ngarment jumpsuit fit=tight resolution=3\n",
    )
    .expect("session written");
    let metrics = folder.join("metrics.json");
    let out = super::common::drape_cli()
        .args(args)
        .arg("run")
        .arg(&session)
        .arg("--save")
        .arg(folder.join("short.rrd"))
        .arg("--metrics")
        .arg(&metrics)
        .output()
        .expect("drape runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let steps: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(&metrics).expect("metrics written")).expect("JSON");
    steps
        .iter()
        .filter_map(|s| s.get("notes").and_then(|n| n.as_array()).cloned())
        .flatten()
        .filter_map(|n| n.as_str().map(str::to_string))
        .collect()
}

#[test]
fn the_command_line_reads_writes_or_skips_the_cache_as_told() {
    let folder = Folder::new("index-cache-cli");
    std::fs::create_dir_all(&folder.0).expect("folder");
    let cache = folder.0.join("cache");
    let cache_arg = cache.to_str().expect("utf-8 path");
    // --no-index-cache: no note, and nothing written anywhere (the tests' user cache folder
    // is checked before and after).
    let default_dir = super::common::cache_home().join("drape").join("index");
    let before = files_in(&default_dir);
    assert!(cli_notes(&folder.0, &["--no-index-cache"]).is_empty());
    assert_eq!(files_in(&default_dir), before, "--no-index-cache wrote to the cache");
    // --index-cache DIR: built and written on the first run, read on the second.
    let first = cli_notes(&folder.0, &["--index-cache", cache_arg]);
    assert!(
        first.len() == 1 && first[0].starts_with("body index built and cached"),
        "{first:?}"
    );
    let written = files_in(&cache);
    assert_eq!(written.len(), 1, "{written:?}");
    assert!(written[0].extension().is_some_and(|e| e == "index"), "{written:?}");
    let second = cli_notes(&folder.0, &["--index-cache", cache_arg]);
    assert!(
        second.len() == 1 && second[0].starts_with("body index read from the cache"),
        "{second:?}"
    );
    assert_eq!(files_in(&cache), written);
    // Without either flag: the user cache folder (here the tests' own).
    let default = cli_notes(&folder.0, &[]);
    assert_eq!(default.len(), 1, "{default:?}");
    assert!(
        files_in(&default_dir)
            .iter()
            .any(|f| f.extension().is_some_and(|e| e == "index")),
        "nothing in {}",
        default_dir.display()
    );
}
