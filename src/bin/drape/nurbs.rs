//! `drape nurbs-experiment`: the [nurbs] L/T experiment, printed as a table or JSON and
//! logged.

use std::path::Path;
use std::process::ExitCode;

use anyhow::Context as _;
use drape::nurbs::{Experiment, ExperimentOptions, NurbsSurface, experiment, file::parse, run_experiment};
use drape::session::Stage;
use drape::viz::{LogOptions, nurbs_blueprint};

use crate::args::NurbsExperimentArgs;
use crate::failure::{Classify, Result};
use crate::files::save_study;

fn load(path: Option<&Path>, shipped: &str) -> Result<NurbsSurface> {
    let Some(path) = path else {
        return parse(shipped).internal().map(|n| n.surface);
    };
    let text = drape::input::read_text(path, crate::max_input_bytes()).bad_input()?;
    parse(&text)
        .with_context(|| format!("{}", path.display()))
        .bad_input()
        .map(|n| n.surface)
}

pub(crate) fn experiment(args: &NurbsExperimentArgs) -> Result<ExitCode> {
    if args.min_level > args.max_level {
        return Err(anyhow::anyhow!(
            "--min-level {} is above --max-level {}",
            args.min_level,
            args.max_level
        ))
        .bad_input();
    }
    if !(args.accuracy.is_finite() && args.accuracy > 0.0) {
        return Err(anyhow::anyhow!(
            "--accuracy must be a positive length in m, got {}",
            args.accuracy
        ))
        .bad_input();
    }
    if !(args.distance.is_finite() && args.distance > 0.0) {
        return Err(anyhow::anyhow!(
            "--distance must be a positive length in m, got {}",
            args.distance
        ))
        .bad_input();
    }
    let butterfly = load(args.butterfly.as_deref(), experiment::BUTTERFLY)?;
    let leaf = load(args.leaf.as_deref(), experiment::CORN_LEAF)?;
    let options = ExperimentOptions {
        levels: args.min_level..=args.max_level,
        accuracy_m: args.accuracy,
        timing_ms: args.timing_ms.max(0.0),
        pose: drape::nurbs::Placement {
            at: [args.at[0], args.at[1]],
            gap: 0.0,
            yaw_deg: args.yaw,
            roll_deg: args.roll,
        },
        near_distance_m: args.distance,
        ..ExperimentOptions::default()
    };
    if !args.json {
        eprintln!(
            "butterfly {} control points, leaf {}; levels {}..{} ...",
            butterfly.net().len(),
            leaf.net().len(),
            args.min_level,
            args.max_level
        );
    }
    let result = run_experiment(&butterfly, &leaf, &options);
    if args.json {
        let out = serde_json::json!({
            "levels": result.levels,
            "crossing": result.crossing,
            "recommended": result.recommended,
            "near_pose": result.near_pose,
            "crossing_pose": result.crossing_pose,
        });
        println!("{}", serde_json::to_string_pretty(&out).internal()?);
    } else {
        print_table(&result);
    }
    save_study(
        &args.save,
        ("nurbs-experiment", "nurbs.experiment"),
        nurbs_blueprint(),
        LogOptions::default(),
        Stage::NurbsExperiment(&result),
    )
    .internal()?;
    Ok(ExitCode::SUCCESS)
}

fn print_table(result: &Experiment) {
    println!("near pose: control-point distance (the paper's mind) against the true surface distance, mm");
    println!(
        "{:>2} {:>10} {:>9} {:>9} {:>8} {:>10} {:>10} {:>9} {:>15} {:>15}",
        "L", "time ms", "query ms", "pairs", "leaves", "cp min", "true", "error", "net dev b/l", "coverage b/l"
    );
    for r in &result.levels {
        println!(
            "{:>2} {:>10.3} {:>9.3} {:>9} {:>8} {:>10.4} {:>10.4} {:>9.4} {:>7.4}/{:<7.4} {:>7.3}/{:<7.3}",
            r.level,
            r.time_ms,
            r.query_ms,
            r.pairs_tested,
            r.leaf_pairs,
            r.cp_min_distance_m * 1e3,
            r.true_distance_m * 1e3,
            r.error_m * 1e3,
            r.net_deviation_m[0] * 1e3,
            r.net_deviation_m[1] * 1e3,
            r.coverage_m[0] * 1e3,
            r.coverage_m[1] * 1e3,
        );
    }
    let rec = &result.recommended;
    println!(
        "recommended: L = {}, T = {:.4} mm (accuracy {:.3} mm{})",
        rec.level,
        rec.threshold_m * 1e3,
        rec.accuracy_m * 1e3,
        if rec.met { "" } else { ", not met at any level run" }
    );
    println!("crossing pose (the butterfly pushed through the leaf), threshold T:");
    println!(
        "{:>2} {:>9} {:>11} {:>11} {:>10} {:>10}",
        "L", "detected", "paper rule", "candidates", "cp min", "refined"
    );
    for c in &result.crossing {
        println!(
            "{:>2} {:>9} {:>11} {:>11} {:>10.4} {:>10.4}",
            c.level,
            if c.detected { "yes" } else { "NO" },
            if c.paper_rule { "yes" } else { "no" },
            c.candidate_pairs,
            c.cp_min_distance_m * 1e3,
            c.true_distance_m * 1e3
        );
    }
}
