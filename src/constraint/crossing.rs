//! Curve self-intersection (\[collide\] section 2, curve layer): the segments of a planar
//! polyline tested pairwise, with a bounding-box prefilter (sort and sweep on `x`), so
//! only segments whose boxes overlap reach the exact test. Neighbouring segments share an
//! end and are never counted.

use glam::DVec2;

/// Two segments of a polyline that cross.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The first segment (from point `i` to `i + 1`).
    pub i: usize,
    /// The second segment, `j > i`.
    pub j: usize,
    /// Where they cross, in the plane's coordinates (m).
    pub at: DVec2,
    /// The length of the shorter of the two loops the crossing cuts the curve into, m:
    /// the part the crossing would have to undo.
    pub loop_length: f64,
}

fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Where segments `ab` and `cd` cross properly (each strictly separates the other's ends),
/// or touch with an end on the other segment.
fn cross(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> Option<DVec2> {
    let (d1, d2) = (orient(a, b, c), orient(a, b, d));
    let (d3, d4) = (orient(c, d, a), orient(c, d, b));
    if d1 * d2 <= 0.0 && d3 * d4 <= 0.0 && (d1 != 0.0 || d2 != 0.0) && (d3 - d4) != 0.0 {
        let t = d3 / (d3 - d4);
        return Some(a + (b - a) * t);
    }
    None
}

/// Segment count of a polyline of `n` points.
fn segments(n: usize, closed: bool) -> usize {
    if closed { n } else { n.saturating_sub(1) }
}

fn adjacent(i: usize, j: usize, m: usize, closed: bool) -> bool {
    j == i + 1 || (closed && i == 0 && j + 1 == m)
}

fn loop_length(points: &[DVec2], closed: bool, i: usize, j: usize, at: DVec2) -> f64 {
    let n = points.len();
    // From the crossing along segment i's end, to segment j's start, back to the crossing.
    let mut inner = at.distance(points[(i + 1) % n]);
    for k in i + 1..j {
        inner += points[k].distance(points[(k + 1) % n]);
    }
    inner += points[j].distance(at);
    if !closed {
        return inner;
    }
    let total: f64 = (0..n).map(|k| points[k].distance(points[(k + 1) % n])).sum();
    inner.min(total - inner)
}

/// Every crossing of the polyline, sorted by segment pair. Bounding boxes of the segments
/// are swept in order of their lowest `x`; only overlapping boxes are tested exactly.
pub fn self_crossings(points: &[DVec2], closed: bool) -> Vec<Crossing> {
    let n = points.len();
    let m = segments(n, closed);
    let seg = |k: usize| (points[k], points[(k + 1) % n]);
    let mut boxes: Vec<(f64, f64, f64, f64, usize)> = (0..m)
        .map(|k| {
            let (a, b) = seg(k);
            (a.x.min(b.x), a.x.max(b.x), a.y.min(b.y), a.y.max(b.y), k)
        })
        .collect();
    boxes.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.4.cmp(&q.4)));
    let mut out = Vec::new();
    for (s, p) in boxes.iter().enumerate() {
        for q in &boxes[s + 1..] {
            if q.0 > p.1 {
                break;
            }
            if q.2 > p.3 || p.2 > q.3 {
                continue;
            }
            let (i, j) = (p.4.min(q.4), p.4.max(q.4));
            if adjacent(i, j, m, closed) {
                continue;
            }
            let ((a, b), (c, d)) = (seg(i), seg(j));
            if let Some(at) = cross(a, b, c, d) {
                out.push(Crossing {
                    i,
                    j,
                    at,
                    loop_length: loop_length(points, closed, i, j, at),
                });
            }
        }
    }
    out.sort_by_key(|c| (c.i, c.j));
    out
}

/// The same without the prefilter: every pair of segments (the reference for tests and the
/// benchmark).
pub fn self_crossings_brute(points: &[DVec2], closed: bool) -> Vec<Crossing> {
    let n = points.len();
    let m = segments(n, closed);
    let mut out = Vec::new();
    for i in 0..m {
        for j in i + 1..m {
            if adjacent(i, j, m, closed) {
                continue;
            }
            let (a, b, c, d) = (points[i], points[(i + 1) % n], points[j], points[(j + 1) % n]);
            if let Some(at) = cross(a, b, c, d) {
                out.push(Crossing {
                    i,
                    j,
                    at,
                    loop_length: loop_length(points, closed, i, j, at),
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_eight_crosses_once_and_a_circle_never() {
        let circle: Vec<DVec2> = (0..64)
            .map(|k| {
                let t = k as f64 / 64.0 * std::f64::consts::TAU;
                DVec2::new(t.cos(), t.sin())
            })
            .collect();
        assert!(self_crossings(&circle, true).is_empty());
        let eight: Vec<DVec2> = (0..64)
            .map(|k| {
                let t = k as f64 / 64.0 * std::f64::consts::TAU + 0.01;
                DVec2::new(t.sin(), (2.0 * t).sin() / 2.0)
            })
            .collect();
        let c = self_crossings(&eight, true);
        assert_eq!(c.len(), 1, "{c:?}");
        assert!(c[0].at.length() < 1e-2);
        assert_eq!(c, self_crossings_brute(&eight, true));
    }
}
