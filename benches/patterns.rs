//! Pattern benchmark: the pattern's compute time against its error, measured in one run.
//!
//! `cargo bench --bench patterns` cuts the demo's jumpsuit (its last step: waist +4 cm, ease
//! 4 mm, the drags, and the yoke cut) on every shipped body at resolution 6, and prints one
//! row per flattening setting: LSCM alone; ARAP with springs of weight 1 on the boundary
//! edges besides the held seam lengths, stopped at relative energy changes of 1e-3 to 1e-6
//! (the default 1e-4); no springs; springs of weight 10. Then the default at resolutions 6, 12 and 24 on the built-in body.
//! Columns: the whole pattern's compute time (cut, flatten every piece, seams, layout; median
//! of 3), ARAP iterations over all pieces, the largest and mean edge strain (%), the worst seam
//! mismatch (mm) and the seams over their tolerance, and the flipped triangles. One worker
//! thread (`taskset -c 0 cargo bench --bench patterns` for one core); `-- --write` puts the
//! tables into docs/patterns.md.

use std::path::Path;

use drape::pattern::{self, CutLine, CutShape, FlattenOptions, Method, Pattern, PatternOptions};
use glam::DVec3;

#[path = "bodies.rs"]
mod bodies;
#[path = "../tests/suite/capture.rs"]
mod capture;
use bodies::shipped_bodies;
#[path = "write_figures.rs"]
mod write_figures;
use write_figures::write_block;
#[path = "timing.rs"]
mod timing;
use capture::{Collect, run};
use timing::median_ms;

/// The demo session (its `garment` line at `resolution`) run on `body`.
fn demo(body: Option<&Path>, resolution: usize) -> Collect {
    let text = std::fs::read_to_string("assets/sessions/demo.drape")
        .expect("the demo session")
        .replace("resolution=6", &format!("resolution={resolution}"));
    run(&text, body)
}

/// One row's figures.
struct Row {
    ms: f64,
    iterations: usize,
    max_strain: f64,
    mean_strain: f64,
    worst_mm: f64,
    over: usize,
    flipped: usize,
}

fn measure(last: &Collect, flatten: FlattenOptions) -> Row {
    let step = last.meshes.last().expect("a collided mesh").0;
    let curves = last.framework(step).curve_polylines();
    // The demo's yoke cut.
    let cuts = [CutLine {
        name: "yoke".into(),
        shape: CutShape::Plane {
            point: DVec3::new(0.0, 1.0, 0.0),
            normal: DVec3::new(0.0, 1.0, 0.25),
        },
    }];
    let input = last.input(step, &curves, &cuts);
    let options = PatternOptions {
        flatten,
        ..PatternOptions::default()
    };
    let mut pattern: Option<Pattern> = None;
    let ms = median_ms(3, || {
        pattern = Some(pattern::build(&input, &options, None).expect("the pattern"));
    });
    let p = pattern.expect("built");
    Row {
        ms,
        iterations: p.pieces.iter().map(|q| q.flat.iterations).sum(),
        max_strain: 100.0 * p.pieces.iter().map(|q| q.distortion.max_strain).fold(0.0, f64::max),
        mean_strain: 100.0 * p.pieces.iter().map(|q| q.distortion.mean_strain).sum::<f64>() / p.pieces.len() as f64,
        worst_mm: 1e3 * p.seams.iter().map(|s| s.mismatch).fold(0.0, f64::max),
        over: p.seams.iter().filter(|s| !s.sews()).count(),
        flipped: p.pieces.iter().map(|q| q.distortion.flipped).sum(),
    }
}

/// One table row, with its line end.
fn row(body: &str, setting: &str, r: &Row) -> String {
    format!(
        "| {body} | {setting} | {:.1} | {} | {:.1} | {:.2} | {:.4} | {} | {} |\n",
        r.ms, r.iterations, r.max_strain, r.mean_strain, r.worst_mm, r.over, r.flipped
    )
}

fn main() {
    drape::par::set_threads(1);
    let bodies = shipped_bodies();
    let defaults = FlattenOptions::default();
    let settings: Vec<(String, FlattenOptions)> = [
        (
            "LSCM alone".to_string(),
            FlattenOptions {
                method: Method::Lscm,
                ..defaults
            },
        ),
        ("default: springs 1, tolerance 1e-4".into(), defaults),
        (
            "springs 1, tolerance 1e-5".into(),
            FlattenOptions {
                tolerance: 1e-5,
                ..defaults
            },
        ),
        (
            "springs 1, tolerance 1e-6".into(),
            FlattenOptions {
                tolerance: 1e-6,
                ..defaults
            },
        ),
        (
            "springs 1, tolerance 1e-3".into(),
            FlattenOptions {
                tolerance: 1e-3,
                ..defaults
            },
        ),
        (
            "no springs, tolerance 1e-4".into(),
            FlattenOptions {
                boundary_weight: 0.0,
                ..defaults
            },
        ),
        (
            "no springs, tolerance 1e-6".into(),
            FlattenOptions {
                boundary_weight: 0.0,
                tolerance: 1e-6,
                ..defaults
            },
        ),
        (
            "springs 10, tolerance 1e-4".into(),
            FlattenOptions {
                boundary_weight: 10.0,
                ..defaults
            },
        ),
    ]
    .into_iter()
    .collect();
    let mut out = String::new();
    let header = "| ms | ARAP iterations | strain max % | strain mean % | worst mismatch mm | seams over tolerance | flipped |\n|---|---|---|---|---|---|---|---|---|\n";
    out += "Demo jumpsuit pattern (last step, yoke cut), resolution 6, per flattening setting:\n\n";
    out += &format!("| body | setting {header}");
    for body in &bodies {
        let name = body.file_stem().and_then(|s| s.to_str()).unwrap_or("?").to_string();
        let last = demo(Some(body), 6);
        for (setting, options) in &settings {
            out += &row(&name, setting, &measure(&last, *options));
            print!("{}", out.lines().last().map(|l| format!("{l}\n")).unwrap_or_default());
        }
    }
    out += "\nThe default setting on the built-in body by resolution:\n\n";
    out += &format!("| body | resolution {header}");
    for resolution in [6, 12, 24] {
        let last = demo(None, resolution);
        out += &row("built-in", &resolution.to_string(), &measure(&last, defaults));
    }
    println!("\n{out}");
    if std::env::args().any(|a| a == "--write") {
        write_block("docs/patterns.md", "pattern-settings", &out);
    }
}
