//! NURBS surfaces: evaluation against independent references (the Bernstein form of a
//! rational Bezier patch, and the Cox-de Boor recursion written here), knot insertion that
//! leaves the surface unchanged, subdivision whose four parts reproduce the original, and
//! validation that names what is wrong.

use drape::nurbs::{Direction, NurbsError, NurbsSurface, insert_knot, quarter};
use glam::DVec3;

use super::common::Lcg;

/// Cox-de Boor: the B-spline basis function `N_{i,p}(t)` on `knots` (the last span closed).
pub(super) fn basis(i: usize, p: usize, knots: &[f64], t: f64) -> f64 {
    if p == 0 {
        let last = knots[knots.len() - 1];
        let (a, b) = (knots[i], knots[i + 1]);
        return if (a <= t && t < b) || (t == last && b == last && a < b) {
            1.0
        } else {
            0.0
        };
    }
    let mut out = 0.0;
    if knots[i + p] > knots[i] {
        out += (t - knots[i]) / (knots[i + p] - knots[i]) * basis(i, p - 1, knots, t);
    }
    if knots[i + p + 1] > knots[i + 1] {
        out += (knots[i + p + 1] - t) / (knots[i + p + 1] - knots[i + 1]) * basis(i + 1, p - 1, knots, t);
    }
    out
}

/// The rational surface by its definition: sum of N_i(u) N_j(v) w_ij P_ij over the same
/// sum without P.
pub(super) fn reference(
    degree: [usize; 2],
    knots: &[Vec<f64>; 2],
    count: [usize; 2],
    pts: &[DVec3],
    w: &[f64],
    u: f64,
    v: f64,
) -> DVec3 {
    let (mut num, mut den) = (DVec3::ZERO, 0.0);
    for i in 0..count[0] {
        let bu = basis(i, degree[0], &knots[0], u);
        for j in 0..count[1] {
            let b = bu * basis(j, degree[1], &knots[1], v) * w[i * count[1] + j];
            num += pts[i * count[1] + j] * b;
            den += b;
        }
    }
    num / den
}

/// A clamped knot vector for `count` points of degree `p` with random interior knots
/// (one of them doubled when there are two or more).
pub(super) fn knots(rng: &mut Lcg, count: usize, p: usize) -> Vec<f64> {
    let interior = count - p - 1;
    let mut inner: Vec<f64> = (0..interior).map(|_| 0.05 + 0.9 * rng.next()).collect();
    inner.sort_by(f64::total_cmp);
    if interior >= 2 && p >= 2 {
        inner[1] = inner[0];
    }
    let mut k = vec![0.0; p + 1];
    k.extend(inner);
    k.extend(vec![1.0; p + 1]);
    k
}

/// A random surface of degrees `degree` with `count` points and weights in [0.5, 2].
pub(super) fn random_surface(
    rng: &mut Lcg,
    degree: [usize; 2],
    count: [usize; 2],
) -> (NurbsSurface, [Vec<f64>; 2], Vec<DVec3>, Vec<f64>) {
    let kn = [knots(rng, count[0], degree[0]), knots(rng, count[1], degree[1])];
    let n = count[0] * count[1];
    let pts: Vec<DVec3> = (0..n)
        .map(|k| {
            let (i, j) = (k / count[1], k % count[1]);
            DVec3::new(i as f64 * 0.1, (rng.next() - 0.5) * 0.05, j as f64 * 0.1)
        })
        .collect();
    let w: Vec<f64> = (0..n).map(|_| 0.5 + 1.5 * rng.next()).collect();
    let s = NurbsSurface::new(degree, kn.clone(), count, &pts, &w).expect("valid");
    (s, kn, pts, w)
}

fn samples(rng: &mut Lcg, n: usize) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = (0..n).map(|_| (rng.next(), rng.next())).collect();
    out.extend([(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.5)]);
    out
}

#[test]
fn evaluation_agrees_with_the_bernstein_form_of_a_rational_bezier_patch() {
    // Bicubic by biquadratic, one span each: the basis functions are Bernstein polynomials.
    let mut rng = Lcg(3);
    let (s, _, pts, w) = random_surface(&mut rng, [3, 2], [4, 3]);
    let bern = |n: usize, i: usize, t: f64| {
        let c = [
            [1.0, 0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0, 0.0],
            [1.0, 2.0, 1.0, 0.0],
            [1.0, 3.0, 3.0, 1.0],
        ][n][i];
        c * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32)
    };
    for (u, v) in samples(&mut rng, 200) {
        let (mut num, mut den) = (DVec3::ZERO, 0.0);
        for i in 0..4 {
            for j in 0..3 {
                let b = bern(3, i, u) * bern(2, j, v) * w[i * 3 + j];
                num += pts[i * 3 + j] * b;
                den += b;
            }
        }
        let d = s.point(u, v).distance(num / den);
        assert!(d <= 1e-12, "({u}, {v}): {d}");
    }
}

#[test]
fn evaluation_agrees_with_the_cox_de_boor_definition_with_interior_and_double_knots() {
    let mut rng = Lcg(11);
    for (degree, count) in [([2, 3], [6, 7]), ([3, 3], [9, 8]), ([1, 2], [4, 5]), ([4, 2], [7, 5])] {
        let (s, kn, pts, w) = random_surface(&mut rng, degree, count);
        for (u, v) in samples(&mut rng, 200) {
            let d = s.point(u, v).distance(reference(degree, &kn, count, &pts, &w, u, v));
            assert!(d <= 1e-12, "degree {degree:?} at ({u}, {v}): {d}");
        }
    }
}

#[test]
fn knot_insertion_leaves_the_surface_unchanged() {
    let mut rng = Lcg(21);
    for (degree, count) in [([2, 3], [6, 7]), ([3, 3], [9, 8]), ([3, 1], [5, 4])] {
        let (s, ..) = random_surface(&mut rng, degree, count);
        let mut t = s.clone();
        for k in 0..6 {
            let dir = if k % 2 == 0 { Direction::U } else { Direction::V };
            t = insert_knot(&t, dir, 0.1 + 0.8 * rng.next());
        }
        assert_eq!(t.count(), [count[0] + 3, count[1] + 3], "three knots each way");
        for (u, v) in samples(&mut rng, 300) {
            let d = t.point(u, v).distance(s.point(u, v));
            assert!(d <= 1e-12, "({u}, {v}): {d}");
        }
    }
}

#[test]
fn the_four_sub_surfaces_of_a_quartering_reproduce_the_original_on_their_ranges() {
    let mut rng = Lcg(31);
    for (degree, count) in [([3, 3], [9, 9]), ([2, 3], [5, 7]), ([3, 2], [4, 3])] {
        let (s, ..) = random_surface(&mut rng, degree, count);
        let parts = quarter(&s).expect("splits");
        let mut area = 0.0;
        for part in &parts {
            let (u0, u1) = part.range(Direction::U);
            let (v0, v1) = part.range(Direction::V);
            area += (u1 - u0) * (v1 - v0);
            for (a, b) in samples(&mut rng, 100) {
                let (u, v) = (u0 + a * (u1 - u0), v0 + b * (v1 - v0));
                let d = part.point(u, v).distance(s.point(u, v));
                assert!(d <= 1e-12, "degree {degree:?} ({u}, {v}): {d}");
            }
        }
        assert!((area - 1.0).abs() < 1e-15, "the parts tile the range: {area}");
        // Recursing works on the parts too.
        for part in &parts {
            let sub = quarter(part).expect("splits again");
            let (u0, u1) = sub[3].range(Direction::U);
            let (v0, v1) = sub[3].range(Direction::V);
            let (u, v) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
            assert!(sub[3].point(u, v).distance(s.point(u, v)) <= 1e-12);
        }
    }
}

#[test]
fn invalid_surfaces_are_refused_with_what_is_wrong() {
    let pts = vec![DVec3::ZERO; 9];
    let w = vec![1.0; 9];
    let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let ok = NurbsSurface::new([2, 2], [k.clone(), k.clone()], [3, 3], &pts, &w);
    assert!(ok.is_ok());
    let not_clamped = vec![0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
    let e = NurbsSurface::new([2, 2], [k.clone(), not_clamped], [3, 3], &pts, &w).unwrap_err();
    assert_eq!(
        e,
        NurbsError::NotClamped {
            dir: Direction::V,
            need: 3
        }
    );
    assert!(e.to_string().contains("knot vector in v must be clamped"), "{e}");
    let e = NurbsSurface::new([2, 2], [k[..5].to_vec(), k.clone()], [3, 3], &pts, &w).unwrap_err();
    assert!(e.to_string().contains("in u has 5 knots, expected 6"), "{e}");
    let mut bad_w = w.clone();
    bad_w[4] = 0.0;
    let e = NurbsSurface::new([2, 2], [k.clone(), k.clone()], [3, 3], &pts, &bad_w).unwrap_err();
    assert!(e.to_string().contains("control point (1, 1): weight 0"), "{e}");
    let mut nan = pts.clone();
    nan[7] = DVec3::new(f64::NAN, 0.0, 0.0);
    let e = NurbsSurface::new([2, 2], [k.clone(), k.clone()], [3, 3], &nan, &w).unwrap_err();
    assert!(e.to_string().contains("control point (2, 1)"), "{e}");
    let e = NurbsSurface::new([2, 2], [k.clone(), k.clone()], [3, 3], &pts[..8], &w).unwrap_err();
    assert!(
        e.to_string().contains("the net has 8 points, expected 3 x 3 = 9"),
        "{e}"
    );
    let decreasing = vec![0.0, 0.0, 0.0, 0.7, 0.6, 1.0, 1.0, 1.0];
    let e = NurbsSurface::new([2, 2], [decreasing, k], [5, 3], &[DVec3::ZERO; 15], &[1.0; 15]).unwrap_err();
    assert!(e.to_string().contains("knot 4 = 0.6"), "{e}");
}
