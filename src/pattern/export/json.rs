//! The pattern's figures as JSON: per piece its name, areas, strain and flipped
//! triangles; per seam its panels, the two sides' lengths and their mismatch.

use serde::Serialize;

use crate::pattern::Pattern;

#[derive(Serialize)]
struct PieceJson<'a> {
    name: &'a str,
    patches: &'a [String],
    vertices: usize,
    triangles: usize,
    area_3d_m2: f64,
    area_2d_m2: f64,
    /// Largest edge strain, a fraction (0.01 is 1%).
    max_strain: f64,
    mean_strain: f64,
    area_ratio_min: f64,
    area_ratio_max: f64,
    max_angle_deg: f64,
    mean_angle_deg: f64,
    flipped: usize,
    overlaps: usize,
    grain_mm: [[f64; 2]; 2],
    notches: usize,
    /// ARAP iterations its flattening took (when it was made).
    iterations: usize,
    reused: bool,
}

#[derive(Serialize)]
struct SeamJson<'a> {
    name: &'a str,
    curve: &'a str,
    panels: [&'a str; 2],
    length_3d_m: f64,
    length_a_m: f64,
    length_b_m: f64,
    mismatch_m: f64,
    tolerance_m: f64,
    sews: bool,
    notches: usize,
}

#[derive(Serialize)]
struct PatternJson<'a> {
    source: &'static str,
    seam_curves: &'a [String],
    panels: Vec<PieceJson<'a>>,
    seams: Vec<SeamJson<'a>>,
}

/// The pattern as pretty JSON.
pub fn to_json(pattern: &Pattern) -> String {
    let panels = pattern
        .pieces
        .iter()
        .map(|p| PieceJson {
            name: &p.panel.name,
            patches: &p.patches,
            vertices: p.panel.positions.len(),
            triangles: p.panel.triangles.len(),
            area_3d_m2: p.area_3d,
            area_2d_m2: p.area_2d,
            max_strain: p.distortion.max_strain,
            mean_strain: p.distortion.mean_strain,
            area_ratio_min: p.distortion.area_ratio[0],
            area_ratio_max: p.distortion.area_ratio[1],
            max_angle_deg: p.distortion.max_angle_deg,
            mean_angle_deg: p.distortion.mean_angle_deg,
            flipped: p.distortion.flipped,
            overlaps: p.distortion.overlaps,
            grain_mm: p.grain.map(|g| [1e3 * g.x, 1e3 * g.y]),
            notches: p.notches.len(),
            iterations: p.flat.iterations,
            reused: p.reused,
        })
        .collect();
    let seams = pattern
        .seams
        .iter()
        .map(|s| SeamJson {
            name: &s.name,
            curve: &s.curve,
            panels: s.panels.map(|k| pattern.pieces[k].panel.name.as_str()),
            length_3d_m: s.length_3d,
            length_a_m: s.length_2d[0],
            length_b_m: s.length_2d[1],
            mismatch_m: s.mismatch,
            tolerance_m: s.tolerance,
            sews: s.sews(),
            notches: s.notches.len(),
        })
        .collect();
    let doc = PatternJson {
        source: pattern.source.name(),
        seam_curves: &pattern.seam_curves,
        panels,
        seams,
    };
    serde_json::to_string_pretty(&doc).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}
