//! drape benchmarks: run time beside error, measured in one run.
//!
//! `cargo bench` times each case with criterion, then prints tables that put criterion's
//! median time next to the error of the same case:
//!
//! * body: load (parse + validate), landmarks at several section densities (error: the
//!   largest landmark height difference from a 1280-level reference), rings, partitions;
//! * mannequin: polar and chord-length refinement for several grid densities (error: max
//!   and RMS distance to the dress form's true surface over all regions);
//! * garment: the jumpsuit's framework solve plus M0 at several resolutions (size: M0's
//!   vertices and faces; error: each ring's girth measured on M0's own vertices against
//!   the ring's girth dimension, the waist set to +4 cm as in the demo).

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion};
use drape::body::Body;
use drape::body::{self, BUILTIN_BODY_OBJ, BodyMesh, LandmarkKind, LandmarkOptions, PartitionOptions};
use drape::garment::{BodyProbe, ContourKind, Dimensions, FrameworkOptions, TemplateKind, build_framework};
use drape::mannequin::{DressForm, ErrorStats, MannequinOptions, refine_chord, refine_polar, run_mannequin};
use glam::DVec3;

const LEVELS: [usize; 4] = [80, 160, 320, 640];
const GRIDS: [(usize, usize); 4] = [(10, 8), (18, 12), (36, 24), (72, 48)];

fn landmark_options(levels: usize) -> LandmarkOptions {
    LandmarkOptions::default().with_levels(levels)
}

fn body_mesh() -> BodyMesh {
    BodyMesh::from_obj_text(BUILTIN_BODY_OBJ, "builtin", 1.0).expect("builtin body")
}

fn bench_body(c: &mut Criterion) {
    let mesh = body_mesh();
    let landmarks = body::find_landmarks(&mesh, &LandmarkOptions::default()).expect("landmarks");
    let mut g = c.benchmark_group("body");
    g.bench_function("load", |b| {
        b.iter(|| BodyMesh::from_obj_text(black_box(BUILTIN_BODY_OBJ), "builtin", 1.0))
    });
    for levels in LEVELS {
        let options = landmark_options(levels);
        g.bench_with_input(BenchmarkId::new("landmarks", levels), &options, |b, o| {
            b.iter(|| body::find_landmarks(black_box(&mesh), o));
        });
    }
    g.bench_function("rings", |b| b.iter(|| body::cut_rings(black_box(&mesh), &landmarks)));
    g.bench_function("partitions", |b| {
        b.iter(|| body::build_partitions(black_box(&mesh), &landmarks, &PartitionOptions::default()));
    });
    g.finish();
}

fn bench_mannequin(c: &mut Criterion) {
    let form = DressForm::default();
    let mut g = c.benchmark_group("mannequin");
    for (layers, points) in GRIDS {
        let grid = form.measure(layers, points);
        let id = format!("{layers}x{points}");
        g.bench_with_input(BenchmarkId::new("polar", &id), &grid, |b, grid| {
            b.iter(|| refine_polar::refine(grid, 6))
        });
        g.bench_with_input(BenchmarkId::new("chord", &id), &grid, |b, grid| {
            b.iter(|| refine_chord::refine(grid, 6))
        });
    }
    g.finish();
}

const RESOLUTIONS: [usize; 4] = [3, 6, 12, 24];

/// The contour kinds, the default first.
const KINDS: [ContourKind; 2] = [ContourKind::Local, ContourKind::Natural];

fn garment_scene() -> (Body, BodyProbe, Dimensions) {
    let body = Body::analyse(body_mesh(), &LandmarkOptions::default(), &PartitionOptions::default()).expect("body");
    let probe = BodyProbe::new(&body);
    let base = build_framework(
        &body,
        &probe,
        TemplateKind::Jumpsuit,
        &Dimensions::default(),
        &FrameworkOptions::default(),
    )
    .expect("jumpsuit");
    let mut dims = Dimensions::default();
    dims.values.insert(
        "waist_girth".into(),
        base.dimension("waist_girth").expect("waist") + 0.04,
    );
    (body, probe, dims)
}

fn bench_garment(c: &mut Criterion) {
    let (body, probe, dims) = garment_scene();
    let mut g = c.benchmark_group("garment");
    for kind in KINDS {
        for k in RESOLUTIONS {
            let options = FrameworkOptions::default().with_resolution(k).with_contours(kind);
            g.bench_with_input(
                BenchmarkId::new(format!("jumpsuit-{}", kind.name()), k),
                &options,
                |b, o| b.iter(|| build_framework(black_box(&body), &probe, TemplateKind::Jumpsuit, &dims, o)),
            );
        }
    }
    g.finish();
}

/// Perimeter of M0's vertices lying in the horizontal plane `y` (on one side of x = 0 for
/// leg rings), ordered by angle about their centroid.
fn row_perimeter(positions: &[DVec3], y: f64, side: i32) -> f64 {
    let mut row: Vec<DVec3> = positions
        .iter()
        .filter(|p| (p.y - y).abs() < 1e-12 && (side == 0 || (p.x > 0.0) == (side > 0)))
        .copied()
        .collect();
    let c = row.iter().sum::<DVec3>() / row.len().max(1) as f64;
    row.sort_by(|a, b| (a.x - c.x).atan2(a.z - c.z).total_cmp(&(b.x - c.x).atan2(b.z - c.z)));
    let n = row.len();
    (0..n).map(|i| row[i].distance(row[(i + 1) % n])).sum()
}

/// Criterion's median estimate for a benchmark id, in milliseconds.
fn median_ms(id: &str) -> Option<f64> {
    let path = Path::new("target/criterion").join(id).join("new/estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    v["median"]["point_estimate"].as_f64().map(|ns| ns / 1e6)
}

fn fmt_ms(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |ms| format!("{ms:.3}"))
}

fn report() {
    let mesh = body_mesh();
    let reference = body::find_landmarks(&mesh, &landmark_options(1280)).expect("reference landmarks");
    println!(
        "\n## Body ({} vertices, {} triangles)\n",
        mesh.mesh.positions.len(),
        mesh.mesh.triangles.len()
    );
    println!("| stage | median ms | error |");
    println!("|---|---:|---|");
    println!(
        "| load (parse + validate) | {} | closed, manifold: {} repairs |",
        fmt_ms(median_ms("body/load")),
        mesh.report.notes().len()
    );
    for levels in LEVELS {
        let l = body::find_landmarks(&mesh, &landmark_options(levels)).expect("landmarks");
        let worst = LandmarkKind::ALL
            .iter()
            .map(|k| ((l.height(*k) - reference.height(*k)).abs(), k.name()))
            .fold((0.0, ""), |a, b| if b.0 > a.0 { b } else { a });
        println!(
            "| landmarks, {levels} levels | {} | max height error {:.2} mm ({}) vs 1280 levels |",
            fmt_ms(median_ms(&format!("body/landmarks/{levels}"))),
            worst.0 * 1e3,
            worst.1
        );
    }
    let rings = body::cut_rings(&mesh, &reference).expect("rings");
    println!(
        "| rings ({}) | {} | exact plane sections (walk = segment soup to 1e-9 m, tests) |",
        rings.len(),
        fmt_ms(median_ms("body/rings"))
    );
    println!("| partitions (7) | {} | - |", fmt_ms(median_ms("body/partitions")));

    println!("\n## Mannequin refinement (k = 6), error = distance to the true surface\n");
    println!("| grid | dense | polar ms | polar max mm | polar rms mm | chord ms | chord max mm | chord rms mm |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    for (layers, points) in GRIDS {
        let r = run_mannequin(&DressForm::default(), &MannequinOptions::grid(layers, points)).expect("mannequin");
        let all = |e: &[f64]| ErrorStats::of(e.iter().copied());
        let (p, c) = (all(&r.polar_error), all(&r.chord_error));
        let id = format!("{layers}x{points}");
        println!(
            "| {id} | {}x{} | {} | {:.3} | {:.3} | {} | {:.3} | {:.3} |",
            r.polar.points,
            r.polar.layers,
            fmt_ms(median_ms(&format!("mannequin/polar/{id}"))),
            p.max_m * 1e3,
            p.rms_m * 1e3,
            fmt_ms(median_ms(&format!("mannequin/chord/{id}"))),
            c.max_m * 1e3,
            c.rms_m * 1e3
        );
    }
}

fn garment_report() {
    let (body, probe, dims) = garment_scene();
    println!("\n## Garment: jumpsuit framework + M0 (waist +4 cm); girth error = M0 ring polygon vs girth dimension;");
    println!("## M0 against natural contours: each vertex's distance to the same vertex with contours=natural\n");
    println!(
        "| resolution | contours | median ms | M0 vertices | M0 faces | max girth error % | mean girth error % | waist error % | M0 against natural, max / mean mm |"
    );
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---|");
    for k in RESOLUTIONS {
        let built = KINDS.map(|kind| {
            let options = FrameworkOptions::default().with_resolution(k).with_contours(kind);
            build_framework(&body, &probe, TemplateKind::Jumpsuit, &dims, &options).expect("jumpsuit")
        });
        for (kind, fw) in KINDS.iter().zip(&built) {
            let errors: Vec<(String, f64)> = fw
                .rings
                .iter()
                .filter(|r| r.name != "neckline")
                .map(|r| {
                    let side = if r.name.starts_with("left") {
                        1
                    } else if r.name.starts_with("right") {
                        -1
                    } else {
                        0
                    };
                    let target = r.target.unwrap_or(r.girth);
                    (
                        r.name.clone(),
                        (row_perimeter(&fw.m0.mesh.positions, r.plane.offset, side) - target) / target,
                    )
                })
                .collect();
            let max = errors.iter().map(|e| e.1.abs()).fold(0.0, f64::max);
            let mean = errors.iter().map(|e| e.1.abs()).sum::<f64>() / errors.len() as f64;
            let waist = errors.iter().find(|e| e.0 == "waist").map_or(0.0, |e| e.1);
            let natural = &built[1].m0.mesh.positions;
            let moves: Vec<f64> = fw
                .m0
                .mesh
                .positions
                .iter()
                .zip(natural)
                .map(|(a, b)| a.distance(*b))
                .collect();
            let far = moves.iter().copied().fold(0.0, f64::max);
            let mean_move = moves.iter().sum::<f64>() / moves.len().max(1) as f64;
            println!(
                "| {k} | {} | {} | {} | {} | {:.3} | {:.3} | {:+.3} | {:.1} / {:.2} |",
                kind.name(),
                fmt_ms(median_ms(&format!("garment/jumpsuit-{}/{k}", kind.name()))),
                fw.m0.mesh.positions.len(),
                fw.m0.mesh.triangles.len(),
                max * 100.0,
                mean * 100.0,
                waist * 100.0,
                1e3 * far,
                1e3 * mean_move
            );
        }
    }
}

fn main() {
    let mut c = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    bench_body(&mut c);
    bench_mannequin(&mut c);
    bench_garment(&mut c);
    c.final_summary();
    report();
    garment_report();
}
