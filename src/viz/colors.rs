//! Colours: one per partition, one per collision response rule, one per plotted series,
//! and an error colour map.

use crate::body::PartitionId;
use crate::collision::AppliedRule;

/// Display colour of a partition (RGB).
pub fn partition_color(id: PartitionId) -> [u8; 3] {
    match id {
        PartitionId::A => [66, 133, 244],
        PartitionId::B => [0, 172, 193],
        PartitionId::C => [52, 168, 83],
        PartitionId::D => [251, 188, 5],
        PartitionId::E => [255, 112, 67],
        PartitionId::F => [234, 67, 53],
        PartitionId::G => [171, 71, 188],
    }
}

/// A pale tint of a partition colour for the body surface.
pub fn partition_tint(id: PartitionId) -> [u8; 3] {
    let c = partition_color(id);
    c.map(|v| ((u16::from(v) + 3 * 225) / 4) as u8)
}

/// Error colour map (blue, cyan, green, yellow, red) for `value / max` clamped to `[0, 1]`.
pub fn error_color(value: f64, max: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 5] = [
        [48.0, 18.0, 160.0],
        [30.0, 150.0, 230.0],
        [60.0, 200.0, 90.0],
        [250.0, 210.0, 40.0],
        [220.0, 30.0, 30.0],
    ];
    let x = if max > 0.0 { (value / max).clamp(0.0, 1.0) } else { 0.0 } * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    [0, 1, 2].map(|k| (a[k] + (b[k] - a[k]) * f).round() as u8)
}

/// Colour of a response rule (its arrows in `collision/response/<rule>`).
pub fn rule_color(rule: AppliedRule) -> [u8; 3] {
    match rule {
        AppliedRule::VertexNormal => [90, 90, 255],
        AppliedRule::ViewDirection => [0, 200, 200],
        AppliedRule::BodyNormal => [255, 170, 0],
        AppliedRule::GlobalCentre => [30, 160, 60],
        AppliedRule::LocalCentre => [150, 220, 60],
        AppliedRule::Guard => [230, 30, 200],
        AppliedRule::EdgeLift => [255, 230, 90],
        AppliedRule::FaceLift => [255, 150, 40],
        AppliedRule::Fallback => [140, 140, 140],
    }
}

/// Colour of the M1 selection rule that first selected a patch.
pub fn m1_rule_color(rule: crate::m1::Rule) -> [u8; 3] {
    match rule {
        crate::m1::Rule::Stretch => [230, 120, 40],
        crate::m1::Rule::Angle => [60, 140, 230],
        crate::m1::Rule::Edges => [170, 90, 210],
        crate::m1::Rule::Body => [60, 180, 120],
    }
}

/// The clearance bands of the fit map: upper bound (mm; the last is unbounded), colour and
/// label. Below 0 the garment is inside the body.
pub const CLEARANCE_BANDS: [(f64, [u8; 3], &str); 7] = [
    (0.0, [200, 0, 150], "inside the body"),
    (2.0, [225, 35, 35], "0-2 mm: on the skin"),
    (5.0, [245, 140, 30], "2-5 mm: tight"),
    (10.0, [235, 215, 50], "5-10 mm: close"),
    (20.0, [70, 185, 80], "10-20 mm: fitted"),
    (40.0, [50, 175, 210], "20-40 mm: loose"),
    (f64::INFINITY, [60, 90, 210], "over 40 mm: free"),
];

/// The fit-map band (index into [`CLEARANCE_BANDS`]) of a clearance `d` (m).
pub fn clearance_band(d: f64) -> usize {
    let mm = d * 1e3;
    CLEARANCE_BANDS
        .iter()
        .position(|(upper, _, _)| mm < *upper)
        .unwrap_or(CLEARANCE_BANDS.len() - 1)
}

/// Colour of the plotted series met `k`-th in a recording: hues a golden-ratio turn apart,
/// so that series met together (those of one plot) are far apart on the colour wheel.
pub fn series_color(k: usize) -> [u8; 3] {
    let hue = (k as f64 * 0.618_033_988_749_895).fract() * 6.0;
    // HSV to RGB at saturation 0.75 and value 0.95.
    let (s, v) = (0.75, 0.95);
    let f = hue.fract();
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    let rgb = match hue as u32 {
        0 => [v, t, p],
        1 => [q, v, p],
        2 => [p, v, t],
        3 => [p, q, v],
        4 => [t, p, v],
        _ => [v, p, q],
    };
    rgb.map(|c| (c * 255.0).round() as u8)
}
