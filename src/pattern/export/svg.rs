//! The laid-out pieces as SVG at 1:1: user units are millimetres (`width` and `height` in
//! `mm`, the `viewBox` in the same numbers), `y` turned to point down. Each piece is a group
//! `<g id="piece:NAME">` with its cut line (`<path class="cut">`, closed), its grain line,
//! its notches and its name.

use std::fmt::Write;

use glam::DVec2;

use crate::pattern::Pattern;

/// Length of a notch mark, mm.
const NOTCH_MM: f64 = 6.0;

/// The pattern as SVG text.
pub fn to_svg(pattern: &Pattern) -> String {
    let (lo, hi) = pattern
        .pieces
        .iter()
        .flat_map(|p| p.uv.iter())
        .fold((DVec2::ZERO, DVec2::ZERO), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let margin = 0.02;
    // The size as written (to the micrometre), so that `y` turned down reads back exactly.
    let round = |v: f64| (v * 1e3).round() / 1e3;
    let (w, h) = (round(1e3 * (hi.x + margin)), round(1e3 * (hi.y + margin)));
    let _ = lo;
    let at = |p: DVec2| (1e3 * p.x, h - 1e3 * p.y);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.3}mm" height="{h:.3}mm" viewBox="0 0 {w:.3} {h:.3}">"#
    );
    let _ = writeln!(
        out,
        "<style>.cut{{fill:#f4efe6;stroke:#222;stroke-width:0.6}} .grain{{stroke:#1a5fb4;stroke-width:0.5}} .notch{{stroke:#c01c28;stroke-width:0.8}} text{{font:14px sans-serif;fill:#333}}</style>"
    );
    for piece in &pattern.pieces {
        let _ = writeln!(out, r#"<g id="piece:{}">"#, escape(&piece.panel.name));
        let mut d = String::new();
        for (k, &v) in piece.panel.boundary.iter().enumerate() {
            let (x, y) = at(piece.uv[v as usize]);
            let _ = write!(d, "{}{x:.4} {y:.4} ", if k == 0 { "M" } else { "L" });
        }
        d.push('Z');
        let _ = writeln!(out, r#"<path class="cut" d="{d}"/>"#);
        let [(x1, y1), (x2, y2)] = piece.grain.map(at);
        let _ = writeln!(
            out,
            r#"<line class="grain" x1="{x1:.4}" y1="{y1:.4}" x2="{x2:.4}" y2="{y2:.4}"/>"#
        );
        for &(p, inward) in &piece.notches {
            let (x1, y1) = at(p);
            let (x2, y2) = at(p + inward * (NOTCH_MM * 1e-3));
            let _ = writeln!(
                out,
                r#"<line class="notch" x1="{x1:.4}" y1="{y1:.4}" x2="{x2:.4}" y2="{y2:.4}"/>"#
            );
        }
        let centre = 0.5 * (piece.grain[0] + piece.grain[1]);
        let (x, y) = at(centre);
        let _ = writeln!(
            out,
            r#"<text x="{x:.1}" y="{y:.1}" text-anchor="middle">{}</text>"#,
            escape(&piece.panel.name)
        );
        let _ = writeln!(out, "</g>");
    }
    out.push_str("</svg>\n");
    out
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
