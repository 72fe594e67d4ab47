//! The constraint network and the solver on the real body.

use drape::constraint::{ConstraintNet, Edit, NetworkOptions, SolverOptions, Target, solve};
use glam::DVec3;

use super::common::{real_jumpsuit, real_probe};

#[test]
fn scratch_network() {
    let fw = real_jumpsuit();
    let net = ConstraintNet::for_framework(fw, real_probe(), &NetworkOptions::default());
    println!("{}", net.describe(fw, 1e-9));
    let probe = real_probe();
    for (name, by) in [
        ("waist.front", DVec3::new(0.0, 0.0, -0.05)),
        ("waist.front_left", DVec3::new(0.0, 0.0, 0.02)),
        ("chest.front_left", DVec3::new(0.0, 0.0, -0.04)),
        ("crotch.point", DVec3::new(0.0, -0.03, 0.0)),
        ("left_knee.outer", DVec3::new(0.03, 0.0, 0.0)),
    ] {
        for chains in [drape::constraint::Chains::Iterate, drape::constraint::Chains::Split] {
            let opts = SolverOptions {
                chains,
                ..SolverOptions::default()
            };
            let t = std::time::Instant::now();
            let r = solve(
                fw,
                &net,
                &Edit::Point {
                    name: name.into(),
                    target: Target::By(by),
                },
                probe,
                &opts,
            );
            match r {
                Ok(s) => {
                    println!(
                        "{name} {:?}: {:.1} ms, {} iterations, {} passes, converged {}, violations {:?}, deficit {:.2e}, path {:?}",
                        chains,
                        t.elapsed().as_secs_f64() * 1e3,
                        s.iterations.len(),
                        s.passes,
                        s.converged,
                        s.violations
                            .iter()
                            .map(|(k, r)| (
                                net.constraints[*k].kind.name(),
                                net.curves[net.constraints[*k].i].name.clone(),
                                *r
                            ))
                            .collect::<Vec<_>>(),
                        s.clearance_deficit,
                        s.path
                    );
                    for it in &s.iterations {
                        println!(
                            "   pass {} {} driven {:?} node {} curve short {} ({:.2e} -> {:.2e}) moved {:?} broken {:?}",
                            it.pass,
                            net.curves[it.curve].name,
                            it.driven_by
                                .iter()
                                .map(|k| net.constraints[*k].kind.name())
                                .collect::<Vec<_>>(),
                            it.node.len(),
                            it.curve_layer.short_before,
                            it.curve_layer.deficit_before,
                            it.curve_layer.deficit_after,
                            it.curve_layer.moved,
                            it.broken
                                .iter()
                                .map(|k| (
                                    net.constraints[*k].kind.name(),
                                    net.curves[net.constraints[*k].i].name.clone(),
                                    net.curves[net.constraints[*k].j].name.clone()
                                ))
                                .collect::<Vec<_>>()
                        );
                    }
                }
                Err(e) => println!("{name}: {e}"),
            }
        }
    }
}

#[test]
fn scratch_clearance() {
    let fw = real_jumpsuit();
    let probe = real_probe();
    println!("ease {}", fw.ease());
    for r in &fw.rings {
        let d: Vec<String> = r
            .stages
            .control
            .iter()
            .map(|p| format!("{:.1}", probe.signed_distance(*p) * 1e3))
            .collect();
        let min_s = r
            .spline
            .subdivide(6, true)
            .iter()
            .map(|p| probe.signed_distance(*p))
            .fold(f64::INFINITY, f64::min);
        println!(
            "{:<12} control mm [{}] min sample {:.1} mm ease {:?}",
            r.name,
            d.join(" "),
            min_s * 1e3,
            r.ease
        );
    }
    for c in &fw.open_curves {
        let d: Vec<String> = c
            .stages
            .control
            .iter()
            .map(|p| format!("{:.1}", probe.signed_distance(*p) * 1e3))
            .collect();
        println!("{:<12} control mm [{}]", c.name, d.join(" "));
    }
}
