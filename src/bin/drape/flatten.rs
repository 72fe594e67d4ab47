//! `drape flatten PANEL.obj ...`: drape's flattening of panel meshes, timed, for the
//! side-by-side with libigl (scripts/pattern_peers.py).

use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context as _;
use drape::pattern::distortion::{edge_strains, measure};
use drape::pattern::flatten::{FlattenOptions, Method, flatten as flatten_panel};

use crate::args::FlattenArgs;
use crate::failure::{Classify, Result};

pub(crate) fn flatten(args: &FlattenArgs) -> Result<ExitCode> {
    let options = FlattenOptions {
        method: Method::from_name(&args.method).unwrap_or_default(),
        ..FlattenOptions::free()
    };
    if !args.json {
        println!(
            "{:<48} {:>6} {:>6} {:>10} {:>9} {:>9} {:>7} {:>5}",
            "panel", "verts", "faces", "ms", "max %", "mean %", "flipped", "iters"
        );
    }
    for path in &args.panels {
        let obj = drape::mesh::document::read_mesh(path, 1.0, crate::max_input_bytes())
            .with_context(|| format!("reading {}", path.display()))
            .bad_input()?;
        let mesh = &obj.mesh;
        let mut best = f64::INFINITY;
        let mut result = None;
        for _ in 0..args.runs {
            let t = Instant::now();
            let flat = flatten_panel(&mesh.positions, &mesh.triangles, &[], &options)
                .with_context(|| format!("flattening {}", path.display()))
                .bad_input()?;
            best = best.min(t.elapsed().as_secs_f64() * 1e3);
            result = Some(flat);
        }
        let Some(flat) = result else { continue };
        let strains = edge_strains(&mesh.positions, &mesh.triangles, &flat.uv);
        let d = measure(&mesh.positions, &mesh.triangles, &flat.uv, &[]);
        let mean = strains.iter().map(|s| s.1).sum::<f64>() / strains.len().max(1) as f64;
        if args.json {
            println!(
                "{}",
                serde_json::json!({
                    "panel": path.display().to_string(),
                    "vertices": mesh.positions.len(),
                    "faces": mesh.triangles.len(),
                    "ms": best,
                    "max_strain": d.max_strain,
                    "mean_strain": mean,
                    "flipped": d.flipped,
                    "iterations": flat.iterations,
                })
            );
        } else {
            println!(
                "{:<48} {:>6} {:>6} {:>10.3} {:>9.3} {:>9.3} {:>7} {:>5}",
                path.file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
                mesh.positions.len(),
                mesh.triangles.len(),
                best,
                100.0 * d.max_strain,
                100.0 * mean,
                d.flipped,
                flat.iterations
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}
