//! Property tests of the spline core: interpolation, C2 continuity at every knot, and the
//! end conditions, on random data.

use drape::geom::{CubicSpline, EndCondition};
use proptest::prelude::*;

fn knots_and_values() -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
    (3usize..25).prop_flat_map(|n| {
        (
            prop::collection::vec(0.01f64..2.0, n),
            prop::collection::vec(-5.0f64..5.0, n),
        )
            .prop_map(|(steps, ys)| {
                let mut x = Vec::with_capacity(steps.len());
                let mut acc = -1.0;
                for s in steps {
                    acc += s;
                    x.push(acc);
                }
                (x, ys)
            })
    })
}

fn check_c2(s: &CubicSpline, x: &[f64], y: &[f64]) -> Result<(), TestCaseError> {
    let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    for (i, (&xi, &yi)) in x.iter().zip(y).enumerate() {
        prop_assert!((s.sample(xi) - yi).abs() <= 1e-12 * scale, "value at knot {}", i);
        if i > 0 && i + 1 < x.len() {
            // Left and right limits of S' and S'' agree at interior knots: the change across
            // the knot over 2h is no more than the change over h on each side (smooth pieces),
            // while a break would show a jump of the order of the values themselves.
            let h = 1e-6 * (x[i + 1] - x[i - 1]);
            let at = |t: f64| s.eval(t);
            let (l2, l1, r1, r2) = (at(xi - 2.0 * h), at(xi - h), at(xi + h), at(xi + 2.0 * h));
            for (order, pick) in [
                (1, (|e: (f64, f64, f64)| e.1) as fn((f64, f64, f64)) -> f64),
                (2, |e| e.2),
            ] {
                let across = (pick(r1) - pick(l1)).abs();
                let steps = (pick(l1) - pick(l2)).abs() + (pick(r2) - pick(r1)).abs();
                let floor = 1e-9 * pick(l1).abs().max(pick(r1).abs()).max(1.0);
                prop_assert!(
                    across <= 1.5 * steps + floor,
                    "derivative {} jumps at knot {}: {} vs {}",
                    order,
                    i,
                    pick(l1),
                    pick(r1)
                );
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(super::common::proptest_cases(200)))]

    #[test]
    fn natural_splines_interpolate_with_zero_end_curvature((x, y) in knots_and_values()) {
        let s = CubicSpline::try_new(&x, &y, EndCondition::Natural).unwrap();
        check_c2(&s, &x, &y)?;
        prop_assert!(s.second_derivative(x[0]) == 0.0 && s.second_derivative(*x.last().unwrap()) == 0.0);
    }

    #[test]
    fn clamped_splines_take_their_end_slopes((x, y) in knots_and_values(), s0 in -4.0f64..4.0, sn in -4.0f64..4.0) {
        let s = CubicSpline::try_new(&x, &y, EndCondition::Clamped { start_slope: s0, end_slope: sn }).unwrap();
        check_c2(&s, &x, &y)?;
        prop_assert!((s.derivative(x[0]) - s0).abs() <= 1e-9 * (1.0 + s0.abs()));
        prop_assert!((s.derivative(*x.last().unwrap()) - sn).abs() <= 1e-9 * (1.0 + sn.abs()));
    }

    #[test]
    fn periodic_splines_close_smoothly((x, mut y) in knots_and_values()) {
        let n = y.len() - 1;
        y[n] = y[0];
        let s = CubicSpline::try_new(&x, &y, EndCondition::Periodic).unwrap();
        check_c2(&s, &x, &y)?;
        // Across the seam the derivatives change no more than over one more step back
        // (a smooth piece), where a break would jump by the order of the values.
        let d = 1e-7 * (x[n] - x[0]);
        let (a, b, c) = (s.eval(x[0]), s.eval(x[n] - d), s.eval(x[n] - 2.0 * d));
        let floor = 1e-7 * a.1.abs().max(a.2.abs()).max(1.0);
        prop_assert!((a.1 - b.1).abs() <= 1.5 * (b.1 - c.1).abs() + floor, "S' at the seam");
        prop_assert!((a.2 - b.2).abs() <= 1.5 * (b.2 - c.2).abs() + floor, "S'' at the seam");
    }
}
