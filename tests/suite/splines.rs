//! Cubic splines against scipy's CubicSpline (tests/fixtures/spline_reference.json, made
//! by tests/fixtures/make_spline_reference.py).

use drape::geom::{CubicSpline, EndCondition};
use serde_json::Value;

const TOLERANCE: f64 = 1e-12;

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

#[test]
fn values_and_derivatives_match_scipy_to_1e_12_relative() {
    let text = std::fs::read_to_string("tests/fixtures/spline_reference.json").expect("fixture");
    let fixture: Value = serde_json::from_str(&text).expect("json");
    let cases = fixture["cases"].as_array().expect("cases");
    assert!(cases.len() >= 16);
    let mut worst = 0.0_f64;
    for case in cases {
        let (x, y, t) = (floats(&case["x"]), floats(&case["y"]), floats(&case["t"]));
        let end = match case["end"]["kind"].as_str() {
            Some("natural") => EndCondition::Natural,
            Some("periodic") => EndCondition::Periodic,
            Some("clamped") => EndCondition::Clamped {
                start_slope: case["end"]["start_slope"].as_f64().expect("slope"),
                end_slope: case["end"]["end_slope"].as_f64().expect("slope"),
            },
            other => panic!("unknown end {other:?}"),
        };
        let spline = CubicSpline::try_new(&x, &y, end).expect("spline");
        for (key, order) in [("value", 0), ("d1", 1), ("d2", 2)] {
            let want = floats(&case[key]);
            // Relative to the magnitude of that quantity over the case.
            let scale = want.iter().fold(1e-300_f64, |m, v| m.max(v.abs()));
            for (ti, wi) in t.iter().zip(&want) {
                let (v, d1, d2) = spline.eval(*ti);
                let got = [v, d1, d2][order];
                let rel = (got - wi).abs() / scale;
                worst = worst.max(rel);
                assert!(
                    rel <= TOLERANCE,
                    "{} {key} at t={ti}: drape {got}, scipy {wi}, rel {rel:e}",
                    case["name"]
                );
            }
        }
    }
    eprintln!("worst relative difference to scipy: {worst:e}");
}
