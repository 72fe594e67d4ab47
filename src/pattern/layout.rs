//! Turning each flattened piece so that its grain line runs along the body's up direction,
//! and laying the pieces out side by side without overlap (rows on a table of a given
//! width, tallest pieces first).

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
/// translation that places it. Rows of at most `width` (or the widest piece), `gap` between
/// pieces and rows, the tallest pieces first; the first row at `y = 0`, rows going up.
pub fn shelves(bounds: &[(DVec2, DVec2)], width: f64, gap: f64) -> Vec<DVec2> {
    let size = |k: usize| bounds[k].1 - bounds[k].0;
    let widest = (0..bounds.len()).map(|k| size(k).x).fold(0.0, f64::max);
    let width = width.max(widest + 2.0 * gap);
    let mut order: Vec<usize> = (0..bounds.len()).collect();
    order.sort_by(|&a, &b| size(b).y.total_cmp(&size(a).y).then(a.cmp(&b)));
    let mut out = vec![DVec2::ZERO; bounds.len()];
    let (mut x, mut y, mut row) = (gap, gap, 0.0_f64);
    for k in order {
        let s = size(k);
        if x > gap && x + s.x + gap > width {
            x = gap;
            y += row + gap;
            row = 0.0;
        }
        out[k] = DVec2::new(x, y) - bounds[k].0;
        x += s.x + gap;
        row = row.max(s.y);
    }
    out
}
