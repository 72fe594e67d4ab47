//! What the speed measurements share (`drape bench` and `cargo bench --bench speed`): the
//! demo's tight jumpsuit as detection sees it, the exact signed distance of many points, a
//! median timer, and the growth of a time against a size.
//!
//! Nothing here is used by a session; it exists so that every measurement asks the same
//! question of the same garment.

use std::time::Instant;

use glam::DVec3;

use crate::body::Body;
use crate::body::index::BodyIndex;
use crate::collision::GarmentMesh;
use crate::garment::{BodyProbe, Dimensions, FrameworkError, FrameworkOptions, TemplateKind, build_framework};

/// The median wall time of `runs` calls of `f` (at least one), ms.
pub fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// The median of `values` (the mean of the middle two for an even count), NaN for none.
pub fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// The demo's tight jumpsuit at `resolution` (its waist girth 4 cm over the template's on
/// this body, ease 4 mm, as after the demo's two `set`s) as detection sees it, with its ease
/// (m).
///
/// # Errors
///
/// When the framework cannot be built on `body` (see [`build_framework`]).
pub fn demo_jumpsuit(body: &Body, probe: &BodyProbe, resolution: usize) -> Result<(GarmentMesh, f64), FrameworkError> {
    let mut dims = Dimensions::default();
    dims.values.insert("ease".into(), 0.004);
    let options = FrameworkOptions::default().with_resolution(resolution);
    let first = build_framework(body, probe, TemplateKind::Jumpsuit, &dims, &options)?;
    let waist = first.dimension("waist_girth").unwrap_or(0.0);
    dims.values.insert("waist_girth".into(), waist + 0.04);
    let fw = build_framework(body, probe, TemplateKind::Jumpsuit, &dims, &options)?;
    Ok((GarmentMesh::from_framework(&fw, probe.index().height), fw.ease()))
}

/// The exact signed distance of every point to the whole body (negative inside), on the
/// worker threads: the question the closest-point peers answer.
pub fn signed_distances(index: &BodyIndex, points: &[DVec3]) -> Vec<f64> {
    crate::par::par_map(points.len(), |k| {
        let p = points[k];
        index.nearest(p, f64::INFINITY).map_or(f64::INFINITY, |n| n.signed(p))
    })
}

/// How many signed distances of `b` differ from `a`'s: another side, or more than 1 nm apart.
pub fn answers_differing(a: &[f64], b: &[f64]) -> usize {
    a.iter()
        .zip(b)
        .filter(|(a, b)| (**a < 0.0) != (**b < 0.0) || (**a - **b).abs() > 1e-9)
        .count()
}

/// The exponent `k` of `y = c x^k` that fits the points best (least squares on their
/// logarithms): 1 for a time that grows as the size, 0 for one that does not grow. `None`
/// for fewer than two distinct positive sizes or a non-positive time.
pub fn growth_exponent(points: &[(f64, f64)]) -> Option<f64> {
    if points
        .iter()
        .any(|&(x, y)| !(x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite()))
    {
        return None;
    }
    let n = points.len() as f64;
    let logs: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    let mx = logs.iter().map(|l| l.0).sum::<f64>() / n;
    let my = logs.iter().map(|l| l.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|l| (l.0 - mx).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|l| (l.0 - mx) * (l.1 - my)).sum();
    (sxx > 1e-12).then(|| sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::growth_exponent;

    #[test]
    fn the_growth_of_a_power_law_is_its_exponent() {
        for k in [0.0, 0.5, 1.0, 1.5, 2.0] {
            let points: Vec<(f64, f64)> = [637.0, 2357.0, 9471.0, 37183.0]
                .iter()
                .map(|&x| (x, 3.7 * f64::powf(x, k)))
                .collect();
            let fit = growth_exponent(&points).expect("four sizes");
            assert!((fit - k).abs() < 1e-9, "k = {k}: fitted {fit}");
        }
        // Noise of a factor 2 either way on 4x steps moves the fit by at most log 4 / log 64.
        let noisy = [(1.0, 1.0), (4.0, 8.0), (16.0, 8.0), (64.0, 128.0)];
        let fit = growth_exponent(&noisy).expect("four sizes");
        assert!((fit - 1.0).abs() < 0.34, "{fit}");
        assert_eq!(growth_exponent(&[(5.0, 1.0), (5.0, 2.0)]), None, "one size");
        assert_eq!(growth_exponent(&[(1.0, 0.0), (2.0, 2.0)]), None, "a zero time");
    }
}
