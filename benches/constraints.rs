//! Constraint-solver benchmark: solver time per edit beside the final residuals, measured
//! in one run.
//!
//! `cargo bench --bench constraints` prints one table for the tight jumpsuit on the real
//! body: a small and a large drag of a point into the body, a drag whose collision closes
//! a chain (chest -> strap -> chest), and a whole-curve drag, each solved with closed
//! chains iterated and with the chains split. Columns: median solve time (the solve alone,
//! then with the re-surfacing of the changed patches), passes and curve solves, the largest
//! constraint residual left, the number of violated constraints, and the largest shortfall
//! of the collision gap left on a solved curve's samples.

use std::time::Instant;

use drape::body::{Body, BodyMesh, LandmarkOptions, PartitionOptions};
use drape::constraint::{Chains, ConstraintNet, Edit, NetworkOptions, SolverOptions, Target, solve};
use drape::garment::assemble::assemble;
use drape::garment::{BodyProbe, Dimensions, FrameworkOptions, TemplateKind, build_framework};
use glam::DVec3;

#[path = "timing.rs"]
mod timing;
use timing::median_ms;

fn main() {
    let mesh = BodyMesh::from_obj_text(drape::body::BUILTIN_BODY_OBJ, "builtin", 1.0).expect("builtin body");
    let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("body");
    let probe = BodyProbe::new(&body);
    let fw = build_framework(
        &body,
        &probe,
        TemplateKind::Jumpsuit,
        &Dimensions::default(),
        &FrameworkOptions::default(),
    )
    .expect("jumpsuit");
    let start = Instant::now();
    let net = ConstraintNet::for_framework(&fw, &probe, &NetworkOptions::default());
    println!(
        "network: {} curves, {} constraints, built in {:.2} ms",
        net.curves.len(),
        net.constraints.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    let point = |name: &str, d: DVec3| Edit::Point {
        name: name.into(),
        target: Target::By(d),
    };
    let edits = [
        (
            "small drag in (waist.front 5 mm)",
            point("waist.front", DVec3::new(0.0, 0.0, -0.005)),
        ),
        (
            "large drag in (waist.front 6 cm)",
            point("waist.front", DVec3::new(0.0, 0.0, -0.06)),
        ),
        (
            "small chain (chest.front_left 1 cm in)",
            point("chest.front_left", DVec3::new(0.0, 0.0, -0.01)),
        ),
        (
            "large chain (chest.front_left 4 cm in)",
            point("chest.front_left", DVec3::new(0.0, 0.0, -0.04)),
        ),
        (
            "whole curve (left_knee 3 cm up)",
            Edit::Curve {
                name: "left_knee".into(),
                by: DVec3::new(0.0, 0.03, 0.0),
            },
        ),
    ];
    println!(
        "\n| edit | chains | solve ms | + re-surface ms | passes | curve solves | max residual | violated | gap shortfall mm |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for (label, edit) in &edits {
        for chains in [Chains::Iterate, Chains::Split] {
            let options = SolverOptions {
                chains,
                ..SolverOptions::default()
            };
            let s = solve(&fw, &net, edit, &probe, &options).expect("solves");
            let ms = median_ms(15, || {
                std::hint::black_box(solve(&fw, &net, edit, &probe, &options).expect("solves"));
            });
            let with = median_ms(9, || {
                let s = solve(&fw, &net, edit, &probe, &options).expect("solves");
                std::hint::black_box(assemble(&s.framework, &probe, Some(&fw)).expect("assembles"));
            });
            let worst = s.residuals.iter().copied().fold(0.0, f64::max);
            println!(
                "| {label} | {} | {ms:.2} | {with:.2} | {} | {} | {worst:.1e} | {} | {:.3} |",
                chains.name(),
                s.passes,
                s.iterations.len(),
                s.violations.len(),
                s.clearance_deficit * 1e3
            );
        }
    }
}
