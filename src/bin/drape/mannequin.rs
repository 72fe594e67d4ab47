//! `drape mannequin`: the \[spline\] study, printed as a table or JSON and logged.

use std::process::ExitCode;

use drape::mannequin::{DressForm, MannequinOptions, Region, run_mannequin};
use drape::session::Stage;
use drape::viz::{LogOptions, default_blueprint};

use crate::args::MannequinArgs;
use crate::failure::{Classify, Result};
use crate::files::save_study;

pub(crate) fn mannequin(args: &MannequinArgs) -> Result<ExitCode> {
    let options = MannequinOptions::grid(usize::from(args.layers), usize::from(args.points))
        .with_subdivisions(usize::from(args.subdivisions));
    let result = run_mannequin(&DressForm::default(), &options).bad_input()?;
    let ordered: Vec<_> = Region::REPORT_ORDER
        .iter()
        .filter_map(|r| result.regions.iter().find(|e| e.region == r.name()))
        .collect();
    if args.json {
        let regions: Vec<_> = ordered
            .iter()
            .map(|e| {
                serde_json::json!({"region": e.region, "polar": {"max_m": e.polar.max_m, "rms_m": e.polar.rms_m},
                                        "chord": {"max_m": e.chord.max_m, "rms_m": e.chord.rms_m}})
            })
            .collect();
        let out = serde_json::json!({"layers": options.layers, "points": options.points, "regions": regions});
        println!("{}", serde_json::to_string_pretty(&out).internal()?);
    } else {
        println!(
            "dress form {} layers x {} points, refined to {} x {} (k = {}); deviation from the true surface, mm",
            options.layers, options.points, result.polar.points, result.polar.layers, options.subdivisions
        );
        println!(
            "{:<9} {:>10} {:>10} {:>10} {:>10}   better",
            "region", "polar max", "polar rms", "chord max", "chord rms"
        );
        for e in &ordered {
            let better = if e.chord.max_m < e.polar.max_m {
                "chord"
            } else {
                "polar"
            };
            let [pm, pr, cm, cr] = e.millimetres();
            println!("{:<9} {pm:>10.3} {pr:>10.3} {cm:>10.3} {cr:>10.3}   {better}", e.region);
        }
    }
    save_study(
        &args.save,
        ("mannequin", "mannequin.refine"),
        default_blueprint(),
        LogOptions::default().with_mannequin_offset_x(-0.3),
        Stage::Mannequin(&result),
    )
    .internal()?;
    Ok(ExitCode::SUCCESS)
}
