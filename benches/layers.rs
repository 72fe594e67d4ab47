//! Layers benchmark: on every shipped body, a band 6 mm out (the inner garment) and a
//! narrower one 12 mm out with ten dents up to 15 mm into the inner (the outer), both made
//! clear of the body first (tests/suite/offset_garment.rs); timed on one worker thread,
//! medians of 3: the outer band's own collision with the body (`check`, what a single
//! garment's step does) beside the layer push of it out of the inner band (building the
//! inner surface, the certificate before, the push, the certificate after).
//!
//! `taskset -c 0 cargo bench --bench layers` prints the table; `-- --write` puts it into
//! docs/layers.md.

use std::time::Instant;

use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::collision::{BodyIndex, SliceOptions};
use drape::import::{CheckOptions, ImportedGarment, check};
use drape::layers::{LayerSurface, PushOptions, push_outside};
use drape::mesh::MeshDocument;

#[path = "bodies.rs"]
mod bodies;
use bodies::shipped_bodies;
#[path = "write_figures.rs"]
mod write_figures;
use write_figures::write_block;
#[path = "../tests/suite/offset_garment.rs"]
mod offset_garment;
use offset_garment::{band_clear_of, to_obj};

fn main() {
    drape::par::set_threads(1);
    let mut table = String::from(
        "| body | inner vertices | outer vertices | outer on the body ms | before: behind / through / pierced | after | moved | rounds | push ms |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for path in shipped_bodies() {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("?").to_string();
        let mesh = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("the body loads");
        let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("analysed");
        let index = BodyIndex::new(&body, &SliceOptions::default());
        let inner = band_clear_of(&body, &index, (0.62, 0.80), 0.006, (0, 0.0));
        let outer = band_clear_of(&body, &index, (0.64, 0.78), 0.012, (10, 0.015));
        let mut single = Vec::new();
        let mut layered = Vec::new();
        let mut last = None;
        for _ in 0..3 {
            let start = Instant::now();
            let doc = MeshDocument::parse_obj(&to_obj(&outer), "outer.obj", 1.0).expect("the band reads");
            let imported = ImportedGarment::new(doc, &body.mesh.mesh, &index).expect("the band imports");
            let _ = check(&imported, &index, &CheckOptions::default());
            single.push(start.elapsed().as_secs_f64() * 1e3);
            let start = Instant::now();
            let surface = LayerSurface::new(&inner, "inner").expect("the inner band");
            let mut pushed = outer.clone();
            let report = push_outside(&surface, &mut pushed, &PushOptions::default()).expect("pushed");
            layered.push(start.elapsed().as_secs_f64() * 1e3);
            last = Some(report);
        }
        single.sort_by(f64::total_cmp);
        layered.sort_by(f64::total_cmp);
        let r = last.expect("pushed");
        let (b, a) = (&r.before, &r.after);
        let row = format!(
            "| {name} | {} | {} | {:.0} | {} / {} / {} | {} / {} / {} | {} | {} | {:.0} |\n",
            inner.positions.len(),
            outer.positions.len(),
            single[1],
            b.behind,
            b.outer_edges_through_inner,
            b.outer_faces_pierced,
            a.behind,
            a.outer_edges_through_inner,
            a.outer_faces_pierced,
            r.moved,
            r.rounds,
            layered[1]
        );
        print!("{row}");
        table += &row;
    }
    println!("\n{table}");
    if std::env::args().any(|a| a == "--write") {
        write_block("docs/layers.md", "layer-push", &table);
    }
}
