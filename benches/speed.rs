//! Speed benchmark: the collision queries on one thread, their scaling, and the points for
//! the peer libraries, measured in one run.
//!
//! `cargo bench --bench speed` prints, every figure on one worker thread (`--threads N` for
//! more), medians of repeated runs timed here:
//!
//! 1. the body index build (pseudo-normals, the BVHs, the shell, the slices), and the same
//!    index read back from its cache file;
//! 2. for the demo's tight jumpsuit (waist +4 cm, ease 4 mm) at resolutions 3, 6, 12 and 24
//!    and for its M1 (every patch refined once): cold detection (a fresh state, every
//!    vertex tested by its partition's test), the exact signed distance of every vertex
//!    over the whole body (the query the peers answer), the full quality check, and
//!    parry3d's own `project_point` on the same points (its BVH, pseudo-normal sign) with
//!    how many of its inside verdicts differ from drape's exact ones;
//! 3. the same exact query against the body split flat into 4x and 16x the triangles (the
//!    same surface, so the same answers).
//!
//! `-- --export DIR` also writes, for the resolutions 6 and 24, the points, the body and
//! drape's answers (signed distance, inside) as little-endian binaries for
//! `scripts/speed.py`, which times FCPW and libigl on exactly those points. `-- --json PATH`
//! writes the figures as JSON.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use drape::bench::{answers_differing, demo_jumpsuit, signed_distances};
use drape::body::index_cache::{CacheOutcome, IndexCache};
use drape::body::{Body, BodyMesh, LandmarkOptions, PartitionOptions};
use drape::collision::{BodyIndex, CollisionOptions, DetectOptions, DetectState, collide, detect, quality};
use drape::garment::BodyProbe;
use drape::m1::{self, M1Options, Selection};
use drape::mesh::TriMesh;
use glam::DVec3;
use parry3d::query::PointQuery;
use parry3d::shape::{TriMesh as ParryMesh, TriMeshFlags};
use serde_json::json;

#[path = "timing.rs"]
mod timing;
use timing::median_ms;

/// parry3d's own query: `project_point` on its oriented `TriMesh` (f32), inside by
/// pseudo-normals.
fn parry_mesh(body: &TriMesh) -> ParryMesh {
    let vertices = body.positions.iter().map(|p| p.as_vec3()).collect();
    ParryMesh::with_flags(vertices, body.triangles.clone(), TriMeshFlags::ORIENTED).expect("parry builds the body")
}

fn parry_inside(mesh: &ParryMesh, points: &[DVec3]) -> Vec<bool> {
    points
        .iter()
        .map(|p| mesh.project_local_point(p.as_vec3(), true).is_inside)
        .collect()
}

fn write_f64(path: &Path, values: impl Iterator<Item = f64>) {
    let bytes: Vec<u8> = values.flat_map(f64::to_le_bytes).collect();
    std::fs::write(path, bytes).expect("writes the export");
}

fn export(dir: &Path, name: &str, body: &TriMesh, points: &[DVec3], signed: &[f64], inside: &[bool]) {
    std::fs::create_dir_all(dir).expect("creates the export folder");
    write_f64(
        &dir.join("body.vertices.f64"),
        body.positions.iter().flat_map(|p| p.to_array()),
    );
    let tris: Vec<u8> = body.triangles.iter().flatten().flat_map(|i| i.to_le_bytes()).collect();
    std::fs::write(dir.join("body.triangles.u32"), tris).expect("writes the export");
    write_f64(
        &dir.join(format!("{name}.points.f64")),
        points.iter().flat_map(|p| p.to_array()),
    );
    write_f64(&dir.join(format!("{name}.signed.f64")), signed.iter().copied());
    write_f64(
        &dir.join(format!("{name}.detected.f64")),
        inside.iter().map(|&i| f64::from(u8::from(i))),
    );
}

/// The body index read back from a cache file (written first, in a fresh folder), ms.
fn cache_read_ms(body: &Body, runs: usize) -> f64 {
    let slices = drape::collision::SliceOptions::default();
    let dir = std::env::temp_dir().join(format!("drape-speed-cache-{}", std::process::id()));
    let cache = IndexCache::new(&dir);
    let (_, first) = cache.load_or_build(body, &slices);
    assert!(
        matches!(first, CacheOutcome::Built { write_error: None, .. }),
        "the cache was written: {first}"
    );
    let ms = median_ms(runs, || {
        let (index, outcome) = cache.load_or_build(body, &slices);
        assert!(
            matches!(outcome, CacheOutcome::Read(_)),
            "read from the cache: {outcome}"
        );
        black_box(index);
    });
    let _ = std::fs::remove_dir_all(&dir);
    ms
}

struct Args {
    export: Option<PathBuf>,
    json: Option<PathBuf>,
    threads: usize,
    runs: usize,
}

fn args() -> Args {
    let mut out = Args {
        export: None,
        json: None,
        threads: 1,
        runs: 7,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--export" => out.export = it.next().map(PathBuf::from),
            "--json" => out.json = it.next().map(PathBuf::from),
            "--threads" => out.threads = it.next().and_then(|t| t.parse().ok()).unwrap_or(1),
            "--runs" => out.runs = it.next().and_then(|t| t.parse().ok()).unwrap_or(7),
            _ => {} // cargo bench passes --bench
        }
    }
    out
}

fn main() {
    let args = args();
    drape::par::set_threads(args.threads);
    let runs = args.runs;
    let mesh = BodyMesh::from_obj_text(drape::body::BUILTIN_BODY_OBJ, "builtin", 1.0).expect("builtin body");
    let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("body");
    let mut index_build = None;
    let index_ms = median_ms(runs.min(5), || {
        index_build = Some(BodyIndex::new(&body, &drape::collision::SliceOptions::default()));
    });
    let probe = BodyProbe::from_index(index_build.expect("built"));
    let index = probe.index();
    let body_mesh = &body.mesh.mesh;
    let cached_ms = cache_read_ms(&body, runs.min(5));
    println!(
        "# drape speed, {} thread(s): body {} triangles, index build {index_ms:.1} ms, read from the cache {cached_ms:.1} ms\n",
        drape::par::threads(),
        body_mesh.triangles.len()
    );
    println!(
        "| garment | vertices | cold detect us/vertex | exact signed us/vertex | full quality ms | parry3d us/vertex | parry inside verdicts differing |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let parry = parry_mesh(body_mesh);
    let mut rows = Vec::new();
    let mut garments = Vec::new();
    for resolution in [3, 6, 12, 24] {
        let (g, ease) = demo_jumpsuit(&body, &probe, resolution).expect("the jumpsuit builds");
        garments.push((
            format!("M0 resolution {resolution}"),
            g.mesh.positions.clone(),
            g.edges.to_vec(),
            Some((g, ease)),
        ));
    }
    // M1 over every patch of the collided resolution-6 M0.
    {
        let (g, ease) = demo_jumpsuit(&body, &probe, 6).expect("the jumpsuit builds");
        let c = collide(
            index,
            &g,
            ease,
            &CollisionOptions::default(),
            &mut DetectState::default(),
        );
        let mut options = M1Options::default();
        options.all_patches = true;
        let built = m1::build(&c.mesh, &g.face_patch, Selection::all(g.patch_curves.len()), &options);
        let edges = built.edges().to_vec();
        garments.push((
            "M1 (resolution 6, all patches)".into(),
            built.mesh.positions,
            edges,
            None,
        ));
    }
    for (name, points, edges, garment) in &garments {
        let n = points.len();
        let detect_us = garment.as_ref().map(|(g, _)| {
            let input = g.input();
            let options = DetectOptions::default();
            let mut hits = 0;
            let ms = median_ms(runs, || {
                let d = detect(index, &input, &options, &mut DetectState::default());
                hits = d.hits.len();
            });
            black_box(hits);
            ms * 1e3 / n as f64
        });
        let mut exact = Vec::new();
        let exact_us = median_ms(runs, || exact = signed_distances(index, points)) * 1e3 / n as f64;
        let quality_ms = median_ms(runs.min(5), || {
            black_box(quality(index, points, points, edges, &[]));
        });
        let mut parry_in = Vec::new();
        let parry_us = median_ms(runs, || parry_in = parry_inside(&parry, points)) * 1e3 / n as f64;
        let differ = parry_in.iter().zip(&exact).filter(|(p, s)| **p != (**s < 0.0)).count();
        println!(
            "| {name} | {n} | {} | {exact_us:.3} | {quality_ms:.2} | {parry_us:.3} | {differ} |",
            detect_us.map_or("-".into(), |u| format!("{u:.3}")),
        );
        rows.push(json!({
            "garment": name, "vertices": n, "cold_detect_us": detect_us, "exact_signed_us": exact_us,
            "quality_ms": quality_ms, "parry_us": parry_us, "parry_differing": differ,
        }));
        if let (Some(dir), Some((g, _))) = (&args.export, garment)
            && (name.ends_with(" 6") || name.ends_with(" 24"))
        {
            let d = detect(
                index,
                &g.input(),
                &DetectOptions::default(),
                &mut DetectState::default(),
            );
            let mut inside = vec![false; n];
            for h in &d.hits {
                inside[h.vertex as usize] = true;
            }
            let tag = name.rsplit(' ').next().unwrap_or("x");
            export(dir, &format!("res{tag}"), body_mesh, points, &exact, &inside);
        }
    }
    // Scaling in body triangles: the same surface split flat, one partition (point-face).
    println!(
        "\n| body triangles | index build ms | exact signed us/vertex (resolution 24) | answers differing from 1x |"
    );
    println!("|---:|---:|---:|---:|");
    let points = &garments[3].1;
    let mut scaled = body_mesh.clone();
    let mut base: Option<Vec<f64>> = None;
    let mut scaling = Vec::new();
    for factor in [1, 4, 16] {
        if factor > 1 {
            scaled = scaled.split_in_four();
        }
        let start = Instant::now();
        let flat = BodyIndex::from_mesh(&scaled).expect("the split body is manifold");
        let build_ms = start.elapsed().as_secs_f64() * 1e3;
        let mut answers = Vec::new();
        let us = median_ms(runs, || answers = signed_distances(&flat, points)) * 1e3 / points.len() as f64;
        let differ = base.as_ref().map_or(0, |b| answers_differing(b, &answers));
        base.get_or_insert(answers);
        println!("| {} | {build_ms:.1} | {us:.3} | {differ} |", scaled.triangles.len());
        scaling.push(json!({"triangles": scaled.triangles.len(), "build_ms": build_ms, "exact_signed_us": us, "differing": differ}));
    }
    if let Some(path) = &args.json {
        let out = json!({
            "threads": drape::par::threads(), "body_triangles": body_mesh.triangles.len(),
            "index_build_ms": index_ms, "index_cached_ms": cached_ms, "garments": rows, "body_scaling": scaling,
        });
        std::fs::write(path, serde_json::to_string_pretty(&out).expect("json")).expect("writes the json");
    }
}
