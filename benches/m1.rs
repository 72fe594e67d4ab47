//! M1 benchmark: run time against error, measured in one run.
//!
//! `cargo bench --bench m1` prints, for the demo's tight jumpsuit (ease 4 mm, resolution 6) on each shipped body, one row per variant: M0 alone (with drape's edge
//! rounds, and with the vertex response only, the paper's M0), and M1 over selected or all
//! patches, one or two sqrt(3) steps, smoothed or not, and the body-edge and angle rules'
//! thresholds either side of their defaults, over the vertex-only M0 (the paper's flow: M1 fixes
//! what M0's vertices leave) and over drape's M0. Columns: M1's compute time (median of
//! repeated runs: selection, subdivision, collision), faces, edges crossing the body after
//! (exact), and the deviation from a reference fine surface: the same garment at resolution
//! 24, collided, its distance measured at every vertex and face centroid of the mesh
//! (max and mean, mm).

use std::path::Path;

use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::collision::{BodyIndex, CollisionOptions, DetectState, GarmentMesh, collide, quality};
use drape::garment::{BodyProbe, Dimensions, FrameworkOptions, TemplateKind, build_framework};
use drape::m1::{self, M0Collided, M1Options, SelectInput, SelectOptions, Selection, Smoothing};
use drape::mesh::TriMesh;
use glam::DVec3;

#[path = "timing.rs"]
mod timing;
use timing::median_ms;

/// The tight jumpsuit (ease 4 mm) at `resolution`, M0 as built and after its collision.
fn garment(
    body: &Body,
    probe: &BodyProbe,
    resolution: usize,
    edge_rounds: usize,
) -> (GarmentMesh, TriMesh, Vec<usize>) {
    let mut dims = Dimensions::default();
    dims.values.insert("ease".into(), 0.004);
    let options = FrameworkOptions::default().with_resolution(resolution);
    let fw = build_framework(body, probe, TemplateKind::Jumpsuit, &dims, &options).expect("the jumpsuit builds");
    let g = GarmentMesh::from_framework(&fw, probe.index().height);
    let mut collision_options = CollisionOptions::default();
    collision_options.response.edge_rounds = edge_rounds;
    let c = collide(
        probe.index(),
        &g,
        fw.ease(),
        &collision_options,
        &mut DetectState::default(),
    );
    (g, c.mesh, c.detection.partition)
}

/// Max, 95th percentile and mean distance (m) of a mesh's vertices and face centroids to
/// the reference.
fn deviation(mesh: &TriMesh, reference: &BodyIndex) -> (f64, f64, f64) {
    let mut points: Vec<DVec3> = mesh.positions.clone();
    points.extend((0..mesh.triangles.len()).map(|t| mesh.corners(t).into_iter().sum::<DVec3>() / 3.0));
    let d: Vec<f64> = drape::par::par_map(points.len(), |k| {
        reference.nearest(points[k], 1.0).map_or(1.0, |n| n.distance)
    });
    let mut sorted = d.clone();
    sorted.sort_by(f64::total_cmp);
    (
        sorted[sorted.len() - 1],
        sorted[sorted.len() * 95 / 100],
        d.iter().sum::<f64>() / d.len() as f64,
    )
}

fn edges(mesh: &TriMesh) -> Vec<[u32; 2]> {
    drape::mesh::topology::undirected_edges(mesh)
}

fn main() {
    let mut bodies: Vec<_> = std::fs::read_dir("assets/bodies")
        .expect("assets/bodies")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    bodies.sort();
    if let Some(only) = std::env::args().skip(1).find(|a| !a.starts_with('-')) {
        bodies.retain(|p| p.to_string_lossy().contains(&only));
    }
    for path in bodies {
        table(&path);
    }
}

fn table(path: &Path) {
    let mesh = BodyMesh::load(&BodySource::File(path.to_path_buf()), 1.0).expect("body");
    let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("body");
    let probe = BodyProbe::new(&body);
    let index = probe.index();
    let (_, fine, _) = garment(&body, &probe, 24, CollisionOptions::default().response.edge_rounds);
    let reference = BodyIndex::from_mesh(&fine).expect("the reference garment is manifold");
    println!(
        "\n{}: reference {} faces (resolution 24, collided)\n",
        path.file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
        fine.triangles.len()
    );
    println!("| M0 | M1 | M1 time ms | faces | crossing edges | deviation max / p95 / mean mm |");
    println!("|---|---|---:|---:|---:|---:|");
    let rounds = CollisionOptions::default().response.edge_rounds;
    for (m0_name, m0_rounds) in [("vertices only", 0), ("with edge rounds", rounds)] {
        let (g, m0, partition) = garment(&body, &probe, 6, m0_rounds);
        let m0_edges = edges(&m0);
        let q = quality(index, &m0.positions, &m0.positions, &m0_edges, &[]).with_faces(
            index,
            &m0.positions,
            &m0.triangles,
            None,
        );
        let m0_inside = q.inside.clone();
        let m0_crossing: Vec<[u32; 2]> = q.crossing.iter().map(|&e| m0_edges[e as usize]).collect();
        let (max, p95, mean) = deviation(&m0, &reference);
        println!(
            "| {m0_name} | none | 0.0 | {} | {} | {:.2} / {:.2} / {:.2} |",
            m0.triangles.len(),
            q.crossing_edges,
            max * 1e3,
            p95 * 1e3,
            mean * 1e3
        );
        let patches = g.patch_curves.len();
        // (all patches, steps, smoothing, rule thresholds: body edge ratio, angle in degrees)
        let (k, a) = (SelectOptions::default().body_edge, SelectOptions::default().angle_deg);
        for (all, steps, smoothing, body_edge, angle) in [
            (false, 1, Smoothing::None, k, a),
            (false, 2, Smoothing::None, k, a),
            (true, 1, Smoothing::None, k, a),
            (true, 2, Smoothing::None, k, a),
            (false, 1, Smoothing::Kobbelt, k, a),
            (false, 2, Smoothing::Kobbelt, k, a),
            (false, 1, Smoothing::None, 1.5, a),
            (false, 1, Smoothing::None, 3.0, a),
            (false, 1, Smoothing::None, k, 15.0),
            (false, 1, Smoothing::None, k, 45.0),
        ] {
            let mut options = M1Options::default();
            options.all_patches = all;
            options.steps = steps;
            options.smoothing = smoothing;
            options.select.body_edge = body_edge;
            options.select.angle_deg = angle;
            let thresholds = if (body_edge, angle) == (k, a) {
                String::new()
            } else {
                format!(", body {body_edge}, angle {angle}")
            };
            let run = || {
                let selection = if all {
                    Selection::all(patches)
                } else {
                    let input = SelectInput {
                        mesh: &m0,
                        face_patch: &g.face_patch,
                        patches,
                        standard: Some(&g.mesh.positions),
                        measured: None,
                        edges: None,
                    };
                    m1::select(&input, index, &options.select)
                };
                let built = m1::build(&m0, &g.face_patch, selection, &options);
                let collided = M0Collided {
                    measured: None,
                    inside: &m0_inside,
                    crossing: &m0_crossing,
                    triangles: &m0.triangles,
                    pierced: &q.pierced,
                    partition: &partition,
                    ring_normal: &g.ring_normal,
                };
                let c = m1::collide_m1(index, &built, &collided, 0.004, &CollisionOptions::default());
                (built, c)
            };
            let (built, c) = run();
            let ms = median_ms(3, || {
                std::hint::black_box(run());
            });
            let out = TriMesh {
                positions: c.positions.clone(),
                triangles: built.mesh.triangles.clone(),
            };
            let (max, p95, mean) = deviation(&out, &reference);
            println!(
                "| {m0_name} | {} patches ({}), {steps} step{}{}{thresholds} | {ms:.1} | {} | {} -> {} | {:.2} / {:.2} / {:.2} |",
                if all { "all" } else { "selected" },
                built.selection.count(),
                if steps == 2 { "s" } else { "" },
                if smoothing == Smoothing::Kobbelt {
                    ", smoothed"
                } else {
                    ""
                },
                built.mesh.triangles.len(),
                c.crossing_before,
                c.quality.crossing_edges,
                max * 1e3,
                p95 * 1e3,
                mean * 1e3
            );
        }
    }
}
