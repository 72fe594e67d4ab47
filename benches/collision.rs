//! Collision benchmark: run time beside what was found and missed, measured in one run.
//!
//! `cargo bench --bench collision` prints two tables (medians of repeated runs timed here,
//! so that every row comes from the same process and machine state):
//!
//! 1. Detection on the real body for the demo's tight jumpsuit M0 (waist +4 cm, ease 4 mm):
//!    brute force (every vertex against every triangle, point-face) against partitions,
//!    partitions with their BVH, the partitions' own tests (line-line on legs and abdomen),
//!    and the next step (waist +2 mm more) with inert points and patch skipping. Found,
//!    missed and false hits are counted against the winding-number ground truth.
//! 2. Point-face against line-line on the legs' and abdomen's vertices of a garment pushed
//!    in and out at random, for several slice spacings: time per vertex beside the
//!    misclassified vertices and the depth error against the exact depth (in mm and in
//!    ring edges: the paper bounds it by a quarter of a ring edge).

use std::collections::BTreeMap;
use std::hint::black_box;
use std::time::Instant;

use drape::body::{Body, BodyMesh, DetectionMethod, LandmarkOptions, PartitionOptions};
use drape::collision::{
    Acceleration, BodyIndex, DetectOptions, DetectState, Detection, GarmentMesh, SliceOptions, detect, ground_truth,
};
use drape::garment::{BodyProbe, Dimensions, FrameworkOptions, TemplateKind, build_framework};
use glam::DVec3;

#[path = "timing.rs"]
mod timing;
use timing::median_ms;

fn jumpsuit(body: &Body, probe: &BodyProbe, waist: f64, height: f64) -> GarmentMesh {
    let mut dims = Dimensions::default();
    dims.values.insert("waist_girth".into(), waist);
    dims.values.insert("ease".into(), 0.004);
    let fw = build_framework(body, probe, TemplateKind::Jumpsuit, &dims, &FrameworkOptions::default())
        .expect("the jumpsuit builds");
    GarmentMesh::from_framework(&fw, height)
}

fn score(d: &Detection, truth: &[bool]) -> (usize, usize, usize) {
    let mut said = vec![false; truth.len()];
    for h in &d.hits {
        said[h.vertex as usize] = true;
    }
    let found = said.iter().zip(truth).filter(|(s, t)| **s && **t).count();
    let missed = said.iter().zip(truth).filter(|(s, t)| !**s && **t).count();
    let false_hits = said.iter().zip(truth).filter(|(s, t)| **s && !**t).count();
    (found, missed, false_hits)
}

fn detection_table(body: &Body, probe: &BodyProbe, index: &BodyIndex) {
    let g = jumpsuit(body, probe, 0.8096, index.height);
    let truth = ground_truth(&body.mesh.mesh, &g.mesh.positions, &[]).inside;
    println!(
        "\n## Detection: tight jumpsuit M0 ({} vertices) on the real body ({} triangles); {} vertices truly inside\n",
        g.mesh.positions.len(),
        index.triangles.len(),
        truth.iter().filter(|t| **t).count()
    );
    println!("| mode | vertices tested | median ms | speed-up | found | missed | false hits |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let pf = Some(DetectionMethod::PointFace);
    let cases: [(&str, DetectOptions, usize); 4] = [
        (
            "brute force (all triangles, point-face)",
            DetectOptions::default()
                .with_acceleration(Acceleration::BruteForce)
                .with_method(pf),
            3,
        ),
        (
            "partitioned (point-face)",
            DetectOptions::default()
                .with_acceleration(Acceleration::Partitioned)
                .with_method(pf),
            5,
        ),
        (
            "partitioned + BVH (point-face)",
            DetectOptions::default().with_method(pf),
            30,
        ),
        (
            "partitioned + BVH, line-line on A and D (default)",
            DetectOptions::default(),
            30,
        ),
    ];
    let mut brute = None;
    for (name, options, runs) in cases {
        let mut d = None;
        let ms = median_ms(runs, || {
            d = Some(detect(index, &g.input(), &options, &mut DetectState::default()));
        });
        let d = d.expect("ran");
        let base = *brute.get_or_insert(ms);
        let (found, missed, false_hits) = score(&d, &truth);
        println!(
            "| {name} | {} | {ms:.2} | {:.0}x | {found} | {missed} | {false_hits} |",
            d.tested,
            base / ms
        );
    }
    // The next step: 2 mm more at the waist, with the state of the step before.
    let next = jumpsuit(body, probe, 0.8116, index.height);
    let truth_next = ground_truth(&body.mesh.mesh, &next.mesh.positions, &[]).inside;
    for (name, skipping) in [
        ("next step (waist +2 mm), no skipping", false),
        ("next step, + inert points and patch skipping", true),
    ] {
        let options = DetectOptions::default().with_skipping(skipping);
        let mut state0 = DetectState::default();
        detect(index, &g.input(), &options, &mut state0);
        let mut d = None;
        // Each run starts from the first step's state (its clone is timed too).
        let second = median_ms(30, || {
            let mut state = state0.clone();
            d = Some(detect(index, &next.input(), &options, &mut state));
        });
        let d = d.expect("ran");
        let (found, missed, false_hits) = score(&d, &truth_next);
        println!(
            "| {name} | {} (inert {}, patch {}) | {:.2} | {:.0}x | {found} | {missed} | {false_hits} |",
            d.tested,
            d.skipped_inert,
            d.skipped_patch,
            second,
            brute.unwrap_or(1.0) / second
        );
    }
}

/// The jumpsuit M0 with every vertex pushed along its normal by a random amount in
/// `[-2 cm, +2 cm]`.
fn perturbed(body: &Body, probe: &BodyProbe, height: f64) -> GarmentMesh {
    let fw = build_framework(
        body,
        probe,
        TemplateKind::Jumpsuit,
        &Dimensions::default(),
        &FrameworkOptions::default(),
    )
    .expect("the jumpsuit builds");
    let mut g = GarmentMesh::from_framework(&fw, height);
    let mut seed = 99u64;
    for (p, n) in g.mesh.positions.iter_mut().zip(&g.normals) {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
        *p += *n * (0.04 * u - 0.02);
    }
    g.normals = g.mesh.vertex_normals();
    g
}

fn methods_table(body: &Body, probe: &BodyProbe) {
    let base_index = BodyIndex::new(body, &SliceOptions::default());
    let g = perturbed(body, probe, base_index.height);
    // The vertices of the line-line partitions (legs and abdomen).
    let picked: Vec<usize> = (0..g.mesh.positions.len())
        .filter(|&v| {
            base_index
                .partition_at(g.mesh.positions[v].y)
                .is_some_and(|k| base_index.partitions[k].method == DetectionMethod::LineLine)
        })
        .collect();
    let positions: Vec<DVec3> = picked.iter().map(|&v| g.mesh.positions[v]).collect();
    let normals: Vec<DVec3> = picked.iter().map(|&v| g.normals[v]).collect();
    let controls = BTreeMap::new();
    let input = drape::collision::GarmentInput {
        positions: &positions,
        normals: &normals,
        edges: &[],
        vertex_patches: &[],
        patch_curves: &[],
        controls: &controls,
    };
    let truth = ground_truth(&body.mesh.mesh, &positions, &[]).inside;
    let exact = detect(
        &base_index,
        &input,
        &DetectOptions::default().with_method(Some(DetectionMethod::PointFace)),
        &mut DetectState::default(),
    );
    let exact_depth: BTreeMap<u32, f64> = exact.hits.iter().map(|h| (h.vertex, h.depth)).collect();
    println!(
        "\n## Point-face vs line-line: {} vertices of legs A and abdomen D, pushed in and out by up to 2 cm ({} inside)\n",
        positions.len(),
        truth.iter().filter(|t| **t).count()
    );
    println!(
        "| test | slice spacing mm | slices | µs per vertex | wrong (missed + false) | max depth error mm | mean depth error mm | max error / ring edge |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    let pf_ms = median_ms(20, || {
        black_box(detect(
            &base_index,
            &input,
            &DetectOptions::default().with_method(Some(DetectionMethod::PointFace)),
            &mut DetectState::default(),
        ));
    });
    let (_, m, f) = score(&exact, &truth);
    println!(
        "| point-face (BVH) | - | - | {:.2} | {} | 0 | 0 | - |",
        pf_ms * 1e3 / positions.len() as f64,
        m + f
    );
    for divisions in [100.0, 200.0, 400.0, 800.0] {
        let mut options = SliceOptions::default();
        options.spacing_fraction = 1.0 / divisions;
        let index = BodyIndex::new(body, &options);
        let ll = DetectOptions::default().with_method(Some(DetectionMethod::LineLine));
        let mut d = None;
        let ms = median_ms(20, || {
            d = Some(detect(&index, &input, &ll, &mut DetectState::default()))
        });
        let d = d.expect("ran");
        let (_, missed, false_hits) = score(&d, &truth);
        let errors: Vec<f64> = d
            .hits
            .iter()
            .filter_map(|h| exact_depth.get(&h.vertex).map(|e| (h.depth - e).abs()))
            .collect();
        let max = errors.iter().copied().fold(0.0, f64::max);
        let mean = errors.iter().sum::<f64>() / errors.len().max(1) as f64;
        // Mean ring edge over the slices used.
        let (sum, count) = index
            .slices
            .slices
            .iter()
            .flat_map(|s| s.loops.iter())
            .flat_map(|l| {
                let points = l.points();
                let n = points.len();
                (0..n).map(move |i| points[i].distance(points[(i + 1) % n]))
            })
            .fold((0.0, 0usize), |(s, c), e| (s + e, c + 1));
        let edge = sum / count.max(1) as f64;
        println!(
            "| line-line | {:.1} | {} | {:.2} | {} | {:.2} | {:.3} | {:.2} |",
            index.height / divisions * 1e3,
            index.slices.len(),
            ms * 1e3 / positions.len() as f64,
            missed + false_hits,
            max * 1e3,
            mean * 1e3,
            max / edge
        );
    }
}

fn main() {
    let mesh = BodyMesh::from_obj_text(drape::body::BUILTIN_BODY_OBJ, "builtin", 1.0).expect("builtin body");
    let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("body");
    let start = Instant::now();
    let probe = BodyProbe::new(&body);
    let index = probe.index();
    println!(
        "body index (pseudo-normals, 8 BVHs, {} slices): {:.1} ms, once per body",
        index.slices.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    detection_table(&body, &probe, index);
    methods_table(&body, &probe);
}
