//! `drape sculpt-compare`: one drag with no, uniform and adaptive Loop subdivision, printed
//! as a table or JSON and logged side by side.

use std::process::ExitCode;

use anyhow::{Context as _, anyhow};
use drape::mesh::TriMesh;
use drape::sculpt::{Comparison, Drag, Falloff, SculptOptions, Variant, compare};
use drape::session::{
    CollisionPart, CollisionStage, GarmentStage, RunOptions, SinkError, Stage, StageInfo, StageSink, parse_session,
    run_session,
};
use drape::viz::{LogOptions, sculpt_blueprint};
use glam::DVec3;

use crate::args::SculptCompareArgs;
use crate::failure::{Classify, Result};
use crate::files::save_study;

/// Runs of the comparison whose median time is reported.
const RUNS: usize = 5;

/// The collided M0 and the control points of the garment a session built.
#[derive(Default)]
struct Garment {
    mesh: Option<TriMesh>,
    controls: Vec<(String, DVec3)>,
}

impl StageSink for Garment {
    fn collision(&mut self, _info: &StageInfo, stage: CollisionStage<'_>) -> std::result::Result<(), SinkError> {
        if stage.part == CollisionPart::Respond {
            self.mesh = Some(stage.outcome.collision.mesh.clone());
        }
        Ok(())
    }

    fn garment(&mut self, _info: &StageInfo, stage: GarmentStage<'_>) -> std::result::Result<(), SinkError> {
        if let GarmentStage::Part(fw, _) = stage {
            self.controls = fw.control_points();
        }
        Ok(())
    }
}

fn point(text: &str) -> Option<DVec3> {
    let xyz: Vec<f64> = text.split(',').map(|t| t.trim().parse().ok()).collect::<Option<_>>()?;
    match xyz.as_slice() {
        [x, y, z] if xyz.iter().all(|v| v.is_finite()) => Some(DVec3::new(*x, *y, *z)),
        _ => None,
    }
}

/// The mesh to sculpt and the pick point.
fn input(args: &SculptCompareArgs) -> Result<(TriMesh, DVec3)> {
    if let Some(path) = &args.mesh {
        let at = point(&args.at)
            .ok_or_else(|| anyhow!("--at must be x,y,z (m) with --mesh, got '{}'", args.at))
            .bad_input()?;
        let obj = drape::mesh::document::read_mesh(path, 1.0, crate::max_input_bytes())
            .with_context(|| path.display().to_string())
            .bad_input()?;
        return Ok((obj.mesh, at));
    }
    let body = match &args.body {
        Some(p) if p.to_string_lossy().contains('"') => {
            return Err(anyhow!("the body path {} holds a '\"'", p.display())).bad_input();
        }
        Some(p) => format!("\"{}\"", std::path::absolute(p).unwrap_or_else(|_| p.clone()).display()),
        None => "builtin".into(),
    };
    let text = format!(
        "drape 1\nbody {body}\ngarment jumpsuit fit=tight resolution={}\n",
        args.resolution
    );
    let session = parse_session(&text, "sculpt-compare", std::path::Path::new(".")).bad_input()?;
    let mut garment = Garment::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut garment]);
    if let Some(e) = report.error {
        return Err(anyhow!("{}", e.message()))
            .context("building the garment")
            .bad_input();
    }
    let mesh = garment
        .mesh
        .ok_or_else(|| anyhow!("the session built no garment"))
        .internal()?;
    let at = match point(&args.at) {
        Some(p) => p,
        None => garment
            .controls
            .iter()
            .find(|(n, _)| *n == args.at)
            .map(|(_, p)| *p)
            .ok_or_else(|| {
                let names: Vec<&str> = garment.controls.iter().map(|(n, _)| n.as_str()).collect();
                anyhow!(
                    "--at: no control point '{}': expected x,y,z or one of {}",
                    args.at,
                    names.join(", ")
                )
            })
            .bad_input()?,
    };
    Ok((mesh, at))
}

fn json(v: &Variant, epsilon: f64) -> serde_json::Value {
    let m = &v.measures;
    serde_json::json!({
        "faces": m.faces,
        "max_edge_m": m.max_edge_m,
        "min_angle_deg": m.min_angle_deg,
        "smoothness": m.smoothness,
        "time_ms": v.time_ms,
        "region_faces": m.region_faces,
        "max_turn_deg": m.max_turn_deg,
        "levels": v.levels,
        "level_limit_reached": v.limited,
        "epsilon_m": epsilon,
    })
}

pub(crate) fn compare_command(args: &SculptCompareArgs) -> Result<ExitCode> {
    let falloff = Falloff::from_name(&args.falloff)
        .ok_or_else(|| {
            anyhow!(
                "--falloff: unknown '{}': expected biweight, wendland or smoothstep",
                args.falloff
            )
        })
        .bad_input()?;
    let (mesh, at) = input(args)?;
    let drag = Drag {
        at,
        radius: args.radius,
        peak: args.peak,
        direction: None,
        falloff,
    };
    let options = SculptOptions {
        epsilon: args.eps,
        max_levels: usize::from(args.levels),
        weight: args.weight,
    };
    let mut runs: Vec<Comparison> = Vec::with_capacity(RUNS);
    for _ in 0..RUNS {
        runs.push(compare(&mesh, &drag, &options).bad_input()?);
    }
    let median = |f: fn(&Comparison) -> f64| {
        let mut t: Vec<f64> = runs.iter().map(f).collect();
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    };
    let times = [
        median(|c| c.none.time_ms),
        median(|c| c.uniform.time_ms),
        median(|c| c.adaptive.time_ms),
        median(|c| c.adaptive_matched.time_ms),
    ];
    let mut result = runs.swap_remove(0);
    result.none.time_ms = times[0];
    result.uniform.time_ms = times[1];
    result.adaptive.time_ms = times[2];
    result.adaptive_matched.time_ms = times[3];
    let variants = [
        ("none", &result.none, result.epsilon),
        ("uniform", &result.uniform, result.epsilon),
        ("adaptive", &result.adaptive, result.epsilon),
        (
            "adaptive at uniform's max edge",
            &result.adaptive_matched,
            result.uniform.measures.max_edge_m,
        ),
    ];
    if args.json {
        let mut out: serde_json::Map<String, serde_json::Value> = variants[..3]
            .iter()
            .map(|(name, v, eps)| ((*name).to_string(), json(v, *eps)))
            .collect();
        if let Some(serde_json::Value::Object(adaptive)) = out.get_mut("adaptive") {
            adaptive.insert(
                "at_uniform_max_edge".into(),
                json(&result.adaptive_matched, result.uniform.measures.max_edge_m),
            );
        }
        println!("{}", serde_json::to_string_pretty(&out).internal()?);
    } else {
        let p = result.displacement.pick.point;
        println!(
            "drag at {:.3},{:.3},{:.3}: radius {} m, peak {} m, {}; {} vertices moved, {} region faces of {}; epsilon {:.4} m",
            p.x,
            p.y,
            p.z,
            drag.radius,
            drag.peak,
            falloff.name(),
            result.displacement.offsets.len(),
            result.displacement.region.len(),
            mesh.triangles.len(),
            result.epsilon
        );
        println!(
            "{:<31} {:>7} {:>7} {:>12} {:>14} {:>11} {:>13} {:>7} {:>9}",
            "", "faces", "region", "max edge mm", "min angle deg", "smoothness", "max turn deg", "levels", "time ms"
        );
        for (name, v, _) in variants {
            let m = &v.measures;
            println!(
                "{:<31} {:>7} {:>7} {:>12.2} {:>14.2} {:>11.3} {:>13.2} {:>7} {:>9.2}{}",
                name,
                m.faces,
                m.region_faces,
                m.max_edge_m * 1e3,
                m.min_angle_deg,
                m.smoothness,
                m.max_turn_deg,
                v.levels,
                v.time_ms,
                if v.limited { "  (level limit)" } else { "" }
            );
        }
        println!("smoothness: mean angle between the normals of adjacent region faces, degrees (lower is smoother)");
    }
    save_study(
        &args.save,
        ("sculpt-compare", "sculpt.compare"),
        sculpt_blueprint(),
        LogOptions::default(),
        Stage::SculptCompare(&result),
    )
    .internal()?;
    Ok(ExitCode::SUCCESS)
}
