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

/// The limits of S' and S'' at `at` from one side (`side` -1 or +1), from samples inside
/// the piece on that side alone: on a cubic piece S' is a quadratic and S'' a line, so
/// extrapolating S' from three samples and S'' from two is exact (up to rounding), however
/// sharply the piece bends. The samples are `h`, `2h` and `3h` away.
fn one_sided(s: &CubicSpline, at: f64, h: f64, side: f64) -> (f64, f64) {
    let [f1, f2, f3] = [1.0, 2.0, 3.0].map(|k| s.eval(at + side * k * h));
    (3.0 * f1.1 - 3.0 * f2.1 + f3.1, 2.0 * f1.2 - f2.2)
}

/// Whether two limits agree up to rounding (relative to the larger, or 1).
fn agree(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-8 * a.abs().max(b.abs()).max(1.0)
}

fn check_c2(s: &CubicSpline, x: &[f64], y: &[f64]) -> Result<(), TestCaseError> {
    let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    for (i, (&xi, &yi)) in x.iter().zip(y).enumerate() {
        prop_assert!((s.sample(xi) - yi).abs() <= 1e-12 * scale, "value at knot {}", i);
        if i > 0 && i + 1 < x.len() {
            // Left and right limits of S' and S'' agree at interior knots. The samples stay
            // inside the neighbouring pieces (3h is far below the shortest, 0.01).
            let h = 1e-6 * (x[i + 1] - x[i - 1]);
            let (left, right) = (one_sided(s, xi, h, -1.0), one_sided(s, xi, h, 1.0));
            prop_assert!(
                agree(left.0, right.0),
                "S' jumps at knot {}: {} vs {}",
                i,
                left.0,
                right.0
            );
            prop_assert!(
                agree(left.1, right.1),
                "S'' jumps at knot {}: {} vs {}",
                i,
                left.1,
                right.1
            );
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
        // Across the seam: the first piece's limits at its start equal the last piece's at
        // its end.
        let h = 1e-7 * (x[n] - x[0]);
        let (start, end) = (one_sided(&s, x[0], h, 1.0), one_sided(&s, x[n], h, -1.0));
        prop_assert!(agree(start.0, end.0), "S' at the seam: {} vs {}", start.0, end.0);
        prop_assert!(agree(start.1, end.1), "S'' at the seam: {} vs {}", start.1, end.1);
    }
}

#[test]
fn a_clamped_spline_that_bends_sharply_just_past_a_knot_is_still_c2_there() {
    // Found by a long random run: S'' falls from 10 to -3 within 2e-6 past knot 1 (the
    // next knot is 0.012 away and the values swing by 5), so a finite-difference comparison
    // of S' across the knot with S' beside it misreads the bend as a jump.
    let x = [
        -0.99,
        0.6369813229560732,
        0.649194590975213,
        0.6599998323802778,
        2.333522194172029,
        2.343522194172029,
    ];
    let y = [
        -3.2730405436865757,
        2.8125745831304556,
        1.6996375676049185,
        -3.343777909399207,
        0.0,
        0.0,
    ];
    let clamped = EndCondition::Clamped {
        start_slope: 1.13274766987402,
        end_slope: 0.0,
    };
    let s = CubicSpline::try_new(&x, &y, clamped).unwrap();
    check_c2(&s, &x, &y).unwrap();
}
