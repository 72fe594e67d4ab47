//! check-garment benchmark: garments drape did not build, on every shipped body, counted,
//! repaired and counted again, timed on one worker thread.
//!
//! `taskset -c 0 cargo bench --bench check_garment` makes, per body, the band of its own
//! surface from 62% to 80% of its height (above the hands of a body in an A pose), offset
//! 6 mm outward, with 12 bumps pushing it up to 2 cm into the body (tests/suite/offset_garment.rs), at the body's resolution and
//! split finer until it has at least 50,000 vertices; writes it as an OBJ as a garment tool
//! would, and times what `drape check-garment` does with it once the body is loaded (read
//! and parse the file, weld and orient, count, repair, certify, write the repaired file):
//! the median of 3. Columns: the exact counts before and after (vertices inside, edges
//! crossing, faces pierced), the deepest point before, the vertices moved, the time.
//! The garment of the first split is also written as binary PLY (float), text PLY (double)
//! and GLB and checked the same way in each format (file size, read time, whole time).
//! `-- --write` puts the tables into docs/import.md; `-- --keep` keeps the garments (and
//! their repairs) and prints where.

use std::time::Instant;

use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::collision::{BodyIndex, SliceOptions};
use drape::import::{CheckOptions, Checked, ImportedGarment, check};
use drape::mesh::MeshDocument;
use drape::session::{RunOptions, parse_session, run_session};

#[path = "bodies.rs"]
mod bodies;
use bodies::shipped_bodies;
#[path = "write_figures.rs"]
mod write_figures;
use write_figures::write_block;
#[path = "../tests/suite/offset_garment.rs"]
#[allow(dead_code)]
mod offset_garment;
use offset_garment::{offset_band, to_obj};
#[path = "../tests/suite/mesh_files.rs"]
#[allow(dead_code)]
mod mesh_files;
use mesh_files::{gltf_of, write_ply};

fn main() {
    drape::par::set_threads(1);
    let bodies = shipped_bodies();
    let dir = std::env::temp_dir().join(format!("drape-bench-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let mut sessions = String::from(
        "| body | garment vertices | regions | M0 after: inside / crossing / pierced | moves | M1 vertices | regions refined | M1 after: inside / crossing / pierced | step ms |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut formats = String::from(
        "| body | garment vertices | format | file KB | read ms | whole check ms | after: inside / crossing / pierced | moved |\n|---|---|---|---|---|---|---|---|\n",
    );
    let mut out = String::from(
        "| body | garment vertices | faces | before: inside / crossing / pierced | deepest mm | after: inside / crossing / pierced | moved | status | ms |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for path in &bodies {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("?").to_string();
        let mesh = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("the body loads");
        let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("analysed");
        let index = BodyIndex::new(&body, &SliceOptions::default());
        let h = body.mesh.height();
        let base = body.mesh.mesh.bounds().map_or(0.0, |(lo, _)| lo.y);
        let band = (base + 0.62 * h, base + 0.80 * h);
        for splits in [0, 1, 2, 3] {
            let (garment, _) = offset_band(&body.mesh.mesh, band, splits, 0.006, (12, 0.02, 7));
            let file = dir.join(format!("{name}-{splits}.obj"));
            std::fs::write(&file, to_obj(&garment)).expect("written");
            let repaired = dir.join(format!("{name}-{splits}.repaired.obj"));
            let mut last: Option<Checked> = None;
            let mut times = Vec::new();
            for _ in 0..3 {
                let start = Instant::now();
                let doc = MeshDocument::read(&file, 1.0, u64::MAX).expect("the garment reads");
                let imported = ImportedGarment::new(doc, &body.mesh.mesh, &index).expect("the garment imports");
                let checked = check(&imported, &index, &CheckOptions::default());
                let text = imported
                    .doc
                    .write(&checked.positions, &checked.moved)
                    .expect("written back");
                std::fs::write(&repaired, text).expect("written");
                times.push(start.elapsed().as_secs_f64() * 1e3);
                last = Some(checked);
            }
            times.sort_by(f64::total_cmp);
            let r = last.expect("checked").report;
            let (b, a) = (&r.before, &r.after);
            let row = format!(
                "| {name} | {} | {} | {} / {} / {} | {:.1} | {} / {} / {} | {} | {:?} | {:.0} |\n",
                garment.positions.len(),
                garment.triangles.len(),
                b.inside_vertices,
                b.crossing_edges,
                b.pierced_faces,
                b.deepest_m * 1e3,
                a.inside_vertices,
                a.crossing_edges,
                a.pierced_faces,
                r.moved_vertices,
                r.status,
                times[1]
            );
            print!("{row}");
            out += &row;
            if splits <= 1 {
                sessions += &session_row(&name, path, &file, garment.positions.len());
            }
            if splits == 1 {
                formats += &format_rows(&name, &body, &index, &garment, &dir);
            }
            if garment.positions.len() >= 50_000 {
                break;
            }
        }
    }
    if std::env::args().any(|a| a == "--keep") {
        println!("the garments and their repairs: {}", dir.display());
    } else {
        std::fs::remove_dir_all(&dir).ok();
    }
    println!("\n{out}\n{sessions}\n{formats}");
    if std::env::args().any(|a| a == "--write") {
        write_block("docs/import.md", "check-garment", &out);
        write_block("docs/import.md", "garment-mesh-session", &sessions);
        write_block("docs/import.md", "check-garment-formats", &formats);
    }
}

/// The garment `file` as a session's garment (`garment mesh`, with M1) on the body at
/// `body`: the step's figures and its compute time (the median of 3), one table row.
fn session_row(name: &str, body: &std::path::Path, file: &std::path::Path, vertices: usize) -> String {
    let text = format!(
        "drape 1\nbody \"{}\"\nm1\ngarment mesh \"{}\" name=band\n",
        body.display(),
        file.display()
    );
    let session = parse_session(&text, "bench.drape", std::path::Path::new(".")).expect("the session parses");
    let mut times = Vec::new();
    let mut figures = None;
    for _ in 0..3 {
        let report = run_session(&session, &RunOptions::default(), &mut []);
        assert!(report.error.is_none(), "{:?}", report.error);
        let step = report.steps.last().expect("the garment step").clone();
        times.push(
            step.timings_ms
                .iter()
                .filter(|(k, _)| !k.starts_with("log."))
                .map(|(_, v)| v)
                .sum::<f64>(),
        );
        figures = Some(step.figures);
    }
    times.sort_by(f64::total_cmp);
    let f = figures.expect("figures");
    let n = |key: &str| f.get(key).and_then(serde_json::Value::as_u64).unwrap_or(0);
    let regions = f
        .get("regions")
        .and_then(serde_json::Value::as_array)
        .map_or(0, Vec::len);
    let refined = f
        .get("m1_patches_refined")
        .and_then(|r| r.get("total"))
        .and_then(serde_json::Value::as_u64)
        .unwrap_or(0);
    let row = format!(
        "| {name} | {vertices} | {regions} | {} / {} / {} | {} | {} | {refined} | {} / {} / {} | {:.0} |\n",
        n("penetrating_vertices"),
        n("crossing_edges"),
        n("pierced_faces"),
        n("responses") + n("edge_responses") + n("face_responses"),
        n("m1_vertices"),
        n("m1_penetrating_vertices"),
        n("m1_crossing_edges"),
        n("m1_pierced_faces"),
        times[1]
    );
    print!("session: {row}");
    row
}

/// The garment as OBJ, binary PLY (float coordinates), text PLY (double) and GLB, each
/// checked as `check-garment --repair` would (read, import, count, repair, certify, write
/// back in its format): the file's size, the read time and the whole time (medians of 3),
/// the counts after and the vertices moved.
fn format_rows(
    name: &str,
    body: &Body,
    index: &BodyIndex,
    garment: &drape::mesh::TriMesh,
    dir: &std::path::Path,
) -> String {
    let files: [(&str, &str, Vec<u8>); 4] = [
        ("OBJ", "obj", to_obj(garment).into_bytes()),
        ("PLY binary", "ply", write_ply(garment, true, false)),
        ("PLY text", "ply", write_ply(garment, false, true)),
        ("GLB", "glb", gltf_of(garment, 0.0).glb()),
    ];
    let mut rows = String::new();
    for (format, extension, bytes) in files {
        let file = dir.join(format!("{name}-formats-{}.{extension}", format.replace(' ', "-")));
        std::fs::write(&file, &bytes).expect("written");
        let mut read_ms = Vec::new();
        let mut whole_ms = Vec::new();
        let mut last = None;
        for _ in 0..3 {
            let start = Instant::now();
            let doc = MeshDocument::read(&file, 1.0, u64::MAX).expect("the garment reads");
            read_ms.push(start.elapsed().as_secs_f64() * 1e3);
            let imported = ImportedGarment::new(doc, &body.mesh.mesh, index).expect("the garment imports");
            let checked = check(&imported, index, &CheckOptions::default());
            let written = imported
                .doc
                .write(&checked.positions, &checked.moved)
                .expect("written back");
            std::fs::write(file.with_extension(format!("repaired.{extension}")), written).expect("written");
            whole_ms.push(start.elapsed().as_secs_f64() * 1e3);
            last = Some(checked.report);
        }
        read_ms.sort_by(f64::total_cmp);
        whole_ms.sort_by(f64::total_cmp);
        let r = last.expect("checked");
        let a = &r.after;
        let row = format!(
            "| {name} | {} | {format} | {:.0} | {:.1} | {:.0} | {} / {} / {} | {} |\n",
            garment.positions.len(),
            bytes.len() as f64 / 1024.0,
            read_ms[1],
            whole_ms[1],
            a.inside_vertices,
            a.crossing_edges,
            a.pierced_faces,
            r.moved_vertices
        );
        print!("formats: {row}");
        rows += &row;
    }
    rows
}
