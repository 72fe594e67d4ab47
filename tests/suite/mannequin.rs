//! The [spline] mannequin: the deviation measure itself, and what it says of both methods.

use drape::mannequin::{DressForm, MannequinOptions, Region, TrueSurface, run_mannequin};

#[test]
fn the_deviation_of_points_on_and_off_the_true_surface_is_exact() {
    let form = DressForm::default();
    let truth = TrueSurface::new(&form);
    for (s, t) in [
        (0.03, 0.4),
        (0.3, 2.0),
        (0.55, -1.2),
        (0.78, 0.1),
        (0.83, 3.0),
        (0.95, 1.57),
    ] {
        let p = form.point(s, t);
        let (on, region) = truth.distance(p);
        assert!(on < 1e-9, "on the surface at s={s}: {on}");
        assert_eq!(region, Region::of(s));
        let (ps, pt) = form.tangents(s, t);
        let normal = ps.cross(pt).normalize();
        for delta in [1e-4, 2e-3] {
            let (off, _) = truth.distance(p + normal * delta);
            assert!((off - delta).abs() < 1e-8, "s={s} t={t} delta={delta}: {off}");
        }
    }
}

#[test]
fn chord_length_beats_polar_at_neck_and_shoulder() {
    let result = run_mannequin(&DressForm::default(), &MannequinOptions::default()).unwrap();
    assert_eq!((result.polar.points, result.polar.layers), (72, 103));
    for region in ["neck", "shoulder"] {
        let r = result.regions.iter().find(|r| r.region == region).unwrap();
        assert!(
            r.chord.max_m < r.polar.max_m && r.chord.rms_m < r.polar.rms_m,
            "{region}: {r:?}"
        );
        assert!(r.polar.count > 0 && r.chord.count > 0);
    }
}

#[test]
fn both_methods_reproduce_the_measured_points() {
    // Refined points at the measured nodes are the measured points themselves.
    let result = run_mannequin(&DressForm::default(), &MannequinOptions::grid(10, 8)).unwrap();
    let k = result.options.subdivisions;
    for grid in [&result.polar, &result.chord] {
        for i in 0..result.measured.layers {
            for j in 0..result.measured.points {
                let d = grid.at(i * k, j * k).distance(result.measured.at(i, j));
                assert!(d < 1e-12, "node ({i}, {j}): {d}");
            }
        }
    }
}

#[test]
fn the_chord_method_converges_as_the_grid_gets_denser() {
    let coarse = run_mannequin(&DressForm::default(), &MannequinOptions::grid(18, 12)).unwrap();
    let fine = run_mannequin(&DressForm::default(), &MannequinOptions::grid(54, 36)).unwrap();
    for (c, f) in coarse.regions.iter().zip(&fine.regions) {
        assert!(
            f.chord.max_m < 0.5 * c.chord.max_m,
            "{}: {} -> {}",
            c.region,
            c.chord.max_m,
            f.chord.max_m
        );
    }
}
