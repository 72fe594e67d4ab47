//! Units and scale: the shipped body written in millimetres (read with `units mm`) and in
//! kilometres (`units km`) gives the same landmarks, girths, M0 and collision figures as in
//! metres, to a relative 1e-9.

use drape::session::{
    CollisionPart, CollisionStage, RunOptions, SinkError, StageInfo, StageSink, parse_session, run_session,
};
use glam::DVec3;

/// Keeps each step's M0 after response.
#[derive(Default)]
struct Responded(Vec<Vec<DVec3>>);

impl StageSink for Responded {
    fn collision(&mut self, _: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        if stage.part == CollisionPart::Respond {
            self.0.push(stage.outcome.collision.mesh.positions.clone());
        }
        Ok(())
    }
}

/// The builtin body's OBJ with every coordinate multiplied by `factor`.
fn scaled_obj(factor: f64) -> String {
    drape::body::BUILTIN_BODY_OBJ
        .lines()
        .map(|l| match l.strip_prefix("v ") {
            Some(rest) => {
                let xyz: Vec<String> = rest
                    .split_whitespace()
                    .map(|t| format!("{}", t.parse::<f64>().expect("a coordinate") * factor))
                    .collect();
                format!("v {}", xyz.join(" "))
            }
            None => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Runs the session on a body file in `units`; returns the metrics and the M0s.
fn run(dir: &std::path::Path, units: &str, factor: f64) -> (Vec<serde_json::Value>, Vec<Vec<DVec3>>) {
    let body = dir.join(format!("body_{units}.obj"));
    std::fs::write(&body, scaled_obj(factor)).unwrap();
    let text = format!(
        "drape 1\nbody \"{}\"\nunits {units}\ngarment jumpsuit resolution=4\nset ease 0.004\ndrag waist.front_left by=0,0,0.02\n",
        body.display()
    );
    let session = parse_session(&text, "units.drape", dir).expect("parses");
    let mut sink = Responded::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{units}: {:?}", report.error);
    let metrics = report.steps.iter().map(drape::session::StepMetrics::to_json).collect();
    (metrics, sink.0)
}

/// Compares two JSON values: numbers to a relative 1e-9 (of the larger, or absolutely
/// below 1e-12), strings and the rest exactly; timings and the body's name left out.
fn same(a: &serde_json::Value, b: &serde_json::Value, path: &str) {
    use serde_json::Value;
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            for (k, v) in x {
                if k == "timings_ms" || k == "body" {
                    continue;
                }
                same(v, &y[k], &format!("{path}.{k}"));
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{path}");
            for (k, (u, v)) in x.iter().zip(y).enumerate() {
                same(u, v, &format!("{path}[{k}]"));
            }
        }
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            let scale = x.abs().max(y.abs());
            assert!(
                (x - y).abs() <= 1e-9 * scale || (x - y).abs() < 1e-12,
                "{path}: {x} vs {y}"
            );
        }
        _ => assert_eq!(a, b, "{path}"),
    }
}

#[test]
fn millimetres_and_kilometres_give_the_figures_of_metres() {
    let dir = std::env::temp_dir().join(format!("drape-units-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (metres, m0) = run(&dir, "m", 1.0);
    for (units, factor) in [("mm", 1000.0), ("km", 1e-3)] {
        let (metrics, meshes) = run(&dir, units, factor);
        for (a, b) in metres.iter().zip(&metrics) {
            same(a, b, &format!("{units} step {}", a["step"]));
        }
        assert_eq!(m0.len(), meshes.len());
        for (step, (a, b)) in m0.iter().zip(&meshes).enumerate() {
            let worst = a.iter().zip(b).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max);
            assert!(
                worst <= 1e-9 * 1.6,
                "{units}: M0 of collision {step} differs by {worst:e} m"
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
