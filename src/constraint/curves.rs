//! One view of the framework's feature curves for the constraint layer: rings, open curves
//! and contours by a single index, their control points, planes, samples and refitting.

use glam::DVec3;

use crate::garment::adjust::combined_adjustment;
use crate::garment::{Framework, RingOptions};
use crate::geom::Plane;

/// What a curve is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
pub enum CurveKind {
    /// A closed planar ring (`waist`, `left_knee`, ...).
    Ring,
    /// An open planar curve with an apex (`crotch`, `left_strap`).
    Open,
    /// A contour through ring anchors (`centre_front`, ...).
    Contour,
}

impl CurveKind {
    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ring => "ring",
            Self::Open => "open",
            Self::Contour => "contour",
        }
    }
}

/// A curve of the network: which framework list it lives in and where.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct CurveNode {
    /// Curve name.
    pub name: String,
    /// Kind.
    pub kind: CurveKind,
    /// Index in the framework's list of that kind.
    pub index: usize,
}

/// The curves of a framework in network order: rings, then open curves, then contours.
pub fn curve_nodes(fw: &Framework) -> Vec<CurveNode> {
    let mut out = Vec::new();
    for (index, r) in fw.rings.iter().enumerate() {
        out.push(CurveNode {
            name: r.name.clone(),
            kind: CurveKind::Ring,
            index,
        });
    }
    for (index, c) in fw.open_curves.iter().enumerate() {
        out.push(CurveNode {
            name: c.name.clone(),
            kind: CurveKind::Open,
            index,
        });
    }
    for (index, c) in fw.contours.iter().enumerate() {
        out.push(CurveNode {
            name: c.name.clone(),
            kind: CurveKind::Contour,
            index,
        });
    }
    out
}

/// The control points of a curve.
pub fn points<'f>(fw: &'f Framework, c: &CurveNode) -> &'f [DVec3] {
    match c.kind {
        CurveKind::Ring => &fw.rings[c.index].stages.control,
        CurveKind::Open => &fw.open_curves[c.index].stages.control,
        CurveKind::Contour => &fw.contours[c.index].points,
    }
}

/// The plane of a planar curve.
pub fn plane(fw: &Framework, c: &CurveNode) -> Option<Plane> {
    match c.kind {
        CurveKind::Ring => Some(fw.rings[c.index].plane),
        CurveKind::Open => Some(fw.open_curves[c.index].plane),
        CurveKind::Contour => None,
    }
}

/// Moves a planar curve's plane by `d` (a whole-curve drag).
pub fn shift_plane(fw: &mut Framework, c: &CurveNode, d: DVec3) {
    let p = match c.kind {
        CurveKind::Ring => &mut fw.rings[c.index].plane,
        CurveKind::Open => &mut fw.open_curves[c.index].plane,
        CurveKind::Contour => return,
    };
    p.offset += p.normal.dot(d);
}

/// Whether the curve is closed.
pub fn closed(c: &CurveNode) -> bool {
    c.kind == CurveKind::Ring
}

/// The control points that carry a name and drive their neighbours: a ring's anchors, an
/// open curve's ends and apex, every point of a contour.
pub fn key_points(fw: &Framework, c: &CurveNode) -> Vec<usize> {
    match c.kind {
        CurveKind::Ring => fw.rings[c.index].anchors.iter().map(|a| a.control).collect(),
        CurveKind::Open => {
            let n = fw.open_curves[c.index].stages.control.len();
            vec![0, n / 2, n - 1]
        }
        CurveKind::Contour => (0..fw.contours[c.index].points.len()).collect(),
    }
}

/// The control points after moving key points `moved` (index, displacement): the others
/// between two key points follow in proportion (\[frame\] section 2.5's combined adjustment
/// for rings, a linear fade along an open curve), so a drag bends the curve smoothly.
pub fn spread(fw: &Framework, c: &CurveNode, moved: &[(usize, DVec3)]) -> Vec<DVec3> {
    let control = points(fw, c);
    let keys = key_points(fw, c);
    let d_at = |k: usize| moved.iter().find(|(i, _)| *i == k).map_or(DVec3::ZERO, |m| m.1);
    let mut out = match c.kind {
        CurveKind::Ring => {
            let r = &fw.rings[c.index];
            let moves: Vec<DVec3> = keys.iter().map(|&k| d_at(k)).collect();
            combined_adjustment(control, &keys, &moves, &r.plane)
        }
        CurveKind::Open | CurveKind::Contour => {
            let mut out = control.to_vec();
            for w in keys.windows(2) {
                let (a, b) = (w[0], w[1]);
                let (da, db) = (d_at(a), d_at(b));
                for (i, p) in out.iter_mut().enumerate().take(b + 1).skip(a) {
                    let t = (i - a) as f64 / (b - a).max(1) as f64;
                    *p = control[i] + da * (1.0 - t) + db * t;
                }
            }
            out
        }
    };
    // Moved points land exactly where asked.
    for &(i, d) in moved {
        out[i] = control[i] + d;
    }
    out
}

/// Why a curve's new control points cannot be fitted.
#[derive(Clone, Debug, PartialEq)]
pub enum RefitFailure {
    /// Two consecutive control points meet (closer than the curve's length can tell apart:
    /// the chord-length parameter would not increase between them): the edit folds the
    /// curve onto itself there.
    Meet {
        /// The two control points (the second follows the first along the curve).
        points: [usize; 2],
        /// Where they meet, m.
        at: DVec3,
    },
    /// The fit failed otherwise (the fitting error, as text).
    Fit(String),
}

/// Two consecutive points of `control` (and the last and the first, `closed`) that the
/// chord-length parameter cannot tell apart: the running sum of the chords, summed as the
/// spline sums them, does not increase between them.
pub fn meeting_points(control: &[DVec3], closed: bool) -> Option<[usize; 2]> {
    let n = control.len();
    let ends = if closed { n } else { n.saturating_sub(1) };
    let mut length = 0.0;
    for i in 0..ends {
        let j = (i + 1) % n;
        let next = length + control[i].distance(control[j]);
        // Written so that a NaN sum is caught too.
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(next > length) {
            return Some([i, j]);
        }
        length = next;
    }
    None
}

/// Replaces a curve's control points and refits it (anchors and apex follow).
///
/// # Failures
/// [`RefitFailure::Meet`] where two consecutive control points meet, else
/// [`RefitFailure::Fit`] with the fitting error.
pub fn set_points(
    fw: &mut Framework,
    c: &CurveNode,
    control: Vec<DVec3>,
    options: &RingOptions,
) -> Result<(), RefitFailure> {
    if let Some(points) = meeting_points(&control, c.kind == CurveKind::Ring) {
        return Err(RefitFailure::Meet {
            points,
            at: control[points[0]],
        });
    }
    let fitted = match c.kind {
        CurveKind::Ring => fw.rings[c.index].refit(control, options).map_err(|e| e.to_string()),
        CurveKind::Open => fw.open_curves[c.index].refit(control).map_err(|e| e.to_string()),
        CurveKind::Contour => {
            let t = fw.contours[c.index].tangents;
            fw.contours[c.index].refit(control, t).map_err(|e| e.to_string())
        }
    };
    fitted.map_err(RefitFailure::Fit)
}

/// Dense samples of the fitted curve with their spline parameters (`per_span` per
/// control span), for the curve-layer collision and the self-crossing check.
pub fn samples(fw: &Framework, c: &CurveNode, per_span: usize) -> Vec<(f64, DVec3)> {
    let sample = |l: f64| match c.kind {
        CurveKind::Ring => fw.rings[c.index].spline.sample(l),
        CurveKind::Open => fw.open_curves[c.index].spline.sample(l),
        CurveKind::Contour => fw.contours[c.index].spline.sample(l),
    };
    let knots = knots(fw, c);
    let per = per_span.max(1);
    let mut out = Vec::new();
    for w in knots.windows(2) {
        for s in 0..per {
            let l = w[0] + (w[1] - w[0]) * s as f64 / per as f64;
            out.push((l, sample(l)));
        }
    }
    if !closed(c)
        && let Some(&l) = knots.last()
    {
        out.push((l, sample(l)));
    }
    out
}

/// The spline knots (one per control point; a closed curve's last knot closes the loop).
pub fn knots<'f>(fw: &'f Framework, c: &CurveNode) -> &'f [f64] {
    match c.kind {
        CurveKind::Ring => fw.rings[c.index].spline.knots(),
        CurveKind::Open => fw.open_curves[c.index].spline.knots(),
        CurveKind::Contour => fw.contours[c.index].spline.knots(),
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::meeting_points;

    #[test]
    fn points_that_meet_are_found_where_the_chord_sum_stalls() {
        let square = [DVec3::ZERO, DVec3::X, DVec3::ONE.with_z(0.0), DVec3::Y];
        assert_eq!(meeting_points(&square, true), None);
        let mut twice = square.to_vec();
        twice.insert(2, twice[1]);
        assert_eq!(meeting_points(&twice, true), Some([1, 2]));
        // The last and the first meet only on a closed curve.
        let mut closing = square.to_vec();
        closing.push(DVec3::ZERO);
        assert_eq!(meeting_points(&closing, false), None);
        assert_eq!(meeting_points(&closing, true), Some([4, 0]));
        // Apart by less than the running length can tell: 1e-17 m after 3 m of chords.
        let mut tiny = square.to_vec();
        tiny.push(DVec3::new(1e-17, 1.0, 0.0));
        assert_eq!(meeting_points(&tiny, false), Some([3, 4]));
        assert_eq!(meeting_points(&[DVec3::ZERO, DVec3::NAN], false), Some([0, 1]));
    }
}
