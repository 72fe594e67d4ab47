//! Turning each flattened piece so that its grain line runs along the body's up direction,
//! and laying the pieces out side by side without overlap (bottom-left skyline packing on a
//! table of a given width, tallest pieces first).

use glam::{DMat2, DVec2, DVec3};

/// The 2D direction the body's up direction (`+y`) maps to on a flattened panel: the sum of
/// each triangle's map of up (projected on its plane), weighted by the triangle's area.
pub fn grain_direction(positions: &[DVec3], triangles: &[[u32; 3]], uv: &[DVec2]) -> DVec2 {
    let mut g = DVec2::ZERO;
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let [p, q, r] = t.map(|i| uv[i as usize]);
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        let double = n.length();
        if double == 0.0 || double.is_nan() {
            continue;
        }
        let x = e1 / e1.length();
        let y = n.cross(x) / double;
        // Local 2D edges and their images.
        let local = DMat2::from_cols(DVec2::new(e1.length(), 0.0), DVec2::new(e2.dot(x), e2.dot(y)));
        let image = DMat2::from_cols(q - p, r - p);
        if local.determinant().abs() <= 0.0 {
            continue;
        }
        let jacobian = image * local.inverse();
        let up = DVec2::new(DVec3::Y.dot(x), DVec3::Y.dot(y));
        g += 0.5 * double * (jacobian * up);
    }
    g
}

/// The rotation that turns `grain` to `+y` (none when it is zero).
pub fn grain_rotation(grain: DVec2) -> DMat2 {
    if grain.length_squared() > 0.0 {
        DMat2::from_angle(std::f64::consts::FRAC_PI_2 - grain.y.atan2(grain.x))
    } else {
        DMat2::IDENTITY
    }
}

/// Where each piece goes: given each piece's bounds `(min, max)` after its rotation, the
/// translation that places it on a table `width` wide (or as wide as the widest piece),
/// `gap` between pieces. Bottom-left skyline packing: the tallest pieces first, each where
/// it rests lowest on the pieces already placed (then leftmost), at one of the skyline's
/// steps.
pub fn shelves(bounds: &[(DVec2, DVec2)], width: f64, gap: f64) -> Vec<DVec2> {
    let size = |k: usize| bounds[k].1 - bounds[k].0 + DVec2::splat(gap);
    let widest = (0..bounds.len()).map(|k| size(k).x).fold(0.0, f64::max);
    let width = width.max(widest + gap);
    let mut order: Vec<usize> = (0..bounds.len()).collect();
    order.sort_by(|&a, &b| size(b).y.total_cmp(&size(a).y).then(a.cmp(&b)));
    // The skyline: steps `(x from, x to, top)`, covering [gap, width] left to right.
    let mut sky: Vec<(f64, f64, f64)> = vec![(gap, width, gap)];
    let mut out = vec![DVec2::ZERO; bounds.len()];
    for k in order {
        let s = size(k);
        let mut best: Option<(f64, f64)> = None;
        for &(x, _, _) in &sky {
            if x + s.x > width + 1e-12 {
                continue;
            }
            let top = sky
                .iter()
                .filter(|&&(a, b, _)| b > x && a < x + s.x)
                .map(|&(_, _, t)| t)
                .fold(f64::NEG_INFINITY, f64::max);
            if best.is_none_or(|(bx, by)| top < by || (top == by && x < bx)) {
                best = Some((x, top));
            }
        }
        let (x, y) = best.unwrap_or((gap, sky.iter().map(|s| s.2).fold(gap, f64::max)));
        out[k] = DVec2::new(x, y) - bounds[k].0;
        // Raise the skyline over [x, x + s.x] to y + s.y.
        let (from, to, top) = (x, x + s.x, y + s.y);
        let mut next = Vec::with_capacity(sky.len() + 2);
        for &(a, b, t) in &sky {
            if b <= from || a >= to {
                next.push((a, b, t));
                continue;
            }
            if a < from {
                next.push((a, from, t));
            }
            if b > to {
                next.push((to, b, t));
            }
        }
        next.push((from, to, top));
        next.sort_by(|p, q| p.0.total_cmp(&q.0));
        sky = next;
    }
    out
}
