//! The seams a template is cut along by default, and the seams of a cut mesh: chains of
//! seam edges between two panels, each side's 2D length, and the notches that match them.

use glam::{DVec2, DVec3};
use serde::Serialize;

use super::panels::Panel;

/// The curves a template is cut along unless the session names others: side seams, centre
/// front and back, inseams and the crotch, the waist (a jumpsuit's), the chest ring (the
/// yoke), the shoulder seams, the armholes, the sleeves' underarm seams, the neckline (under
/// a collar) and the collar's back. Only the curves the garment has are used.
pub const DEFAULT_SEAMS: &[&str] = &[
    "side_left",
    "side_right",
    "centre_front",
    "centre_back",
    "inner_left",
    "inner_right",
    "crotch",
    "waist",
    "chest",
    "seam_left",
    "seam_right",
    "left_armhole",
    "right_armhole",
    "left_sleeve_inner",
    "right_sleeve_inner",
    "left_cap_inner",
    "right_cap_inner",
    "neckline",
    "collar_back",
];

/// Which default seams a garment skips: a dress has no waist seam of its own kind, a shirt
/// none at the waist, and a neckline is a seam only under a collar.
pub fn default_seams(template: &str, curves: &[String]) -> Vec<String> {
    let has = |c: &str| curves.iter().any(|n| n == c);
    DEFAULT_SEAMS
        .iter()
        .filter(|&&c| has(c))
        .filter(|&&c| !(c == "waist" && template != "jumpsuit"))
        .filter(|&&c| c != "neckline" || has("collar"))
        .filter(|&&c| !(c == "centre_front" && template == "dress"))
        .map(|c| c.to_string())
        .collect()
}

/// The tolerance a seam's two sides must meet: 0.5 mm or 0.1% of its length, whichever is
/// larger.
pub fn seam_tolerance(length: f64) -> f64 {
    (0.5e-3_f64).max(1e-3 * length)
}

/// A seam: a chain of seam edges on one curve between two panels (or between two sides of
/// one panel, a slit), with each side's vertices in the same order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Seam {
    /// Name: the two panels it joins (`torso.front_left|torso.back_left`), with the curve
    /// after a `#` when the same two panels meet on several.
    pub name: String,
    /// The feature curve it runs along.
    pub curve: String,
    /// The two panels (indices into the pattern's pieces).
    pub panels: [usize; 2],
    /// Each side's own vertices along the seam, in the same order.
    #[serde(skip)]
    pub sides: [Vec<u32>; 2],
    /// Its 3D length, m.
    pub length_3d: f64,
    /// Each side's 2D length, m.
    pub length_2d: [f64; 2],
    /// `|length_2d[0] - length_2d[1]|`, m.
    pub mismatch: f64,
    /// The tolerance ([`seam_tolerance`]), m.
    pub tolerance: f64,
    /// Fractions of the 3D length where notches match the two sides (both ends, and every
    /// notch spacing along a long seam).
    pub notches: Vec<f64>,
}

impl Seam {
    /// Whether the two sides sew within the tolerance.
    pub fn sews(&self) -> bool {
        self.mismatch <= self.tolerance
    }
}

/// A chain of seam edges: its curve, its two panels, its mesh vertices in order and the
/// faces on its two sides along each edge.
pub(crate) type Chain = (u32, [u32; 2], Vec<u32>, Vec<[u32; 2]>);

/// One seam edge with the face on each side.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SeamEdge {
    pub(crate) a: u32,
    pub(crate) b: u32,
    pub(crate) faces: [u32; 2],
    pub(crate) curve: u32,
}

/// The chains of seam edges: grouped by curve and the pair of panels on their sides, then
/// split into connected runs, each ordered from an end (its smallest end vertex; a closed
/// run from its smallest vertex).
pub(crate) fn chains(edges: &[SeamEdge], panel_of: &[u32]) -> Vec<Chain> {
    let mut groups: std::collections::BTreeMap<(u32, [u32; 2]), Vec<SeamEdge>> = Default::default();
    for e in edges {
        let (pa, pb) = (panel_of[e.faces[0] as usize], panel_of[e.faces[1] as usize]);
        let (key, e) = if pa <= pb {
            ([pa, pb], *e)
        } else {
            (
                [pb, pa],
                SeamEdge {
                    faces: [e.faces[1], e.faces[0]],
                    ..*e
                },
            )
        };
        groups.entry((e.curve, key)).or_default().push(e);
    }
    let mut out = Vec::new();
    for ((curve, pair), group) in groups {
        let mut unused: Vec<bool> = vec![true; group.len()];
        loop {
            // Vertex degrees among the unused edges, to start at an end.
            let mut degree: std::collections::BTreeMap<u32, usize> = Default::default();
            for (e, _) in group.iter().zip(&unused).filter(|(_, u)| **u) {
                *degree.entry(e.a).or_default() += 1;
                *degree.entry(e.b).or_default() += 1;
            }
            let Some(start) = degree
                .iter()
                .find(|(_, d)| **d == 1)
                .or_else(|| degree.iter().next())
                .map(|(v, _)| *v)
            else {
                break;
            };
            let mut vertices = vec![start];
            let mut faces = Vec::new();
            let mut v = start;
            while let Some(k) = (0..group.len()).find(|&k| unused[k] && (group[k].a == v || group[k].b == v)) {
                unused[k] = false;
                v = if group[k].a == v { group[k].b } else { group[k].a };
                vertices.push(v);
                faces.push(group[k].faces);
            }
            out.push((curve, pair, vertices, faces));
        }
    }
    out
}

/// The local vertex of mesh vertex `v` in the panel holding mesh face `face`.
pub(crate) fn local_vertex(panel: &Panel, triangles: &[[u32; 3]], face: u32, v: u32) -> u32 {
    let idx = panel.faces.binary_search(&face).unwrap_or(0);
    let k = triangles[face as usize].iter().position(|&x| x == v).unwrap_or(0);
    panel.triangles[idx][k]
}

/// Length of a polyline through `points` (indices into `at`).
pub(crate) fn length_2d(at: &[DVec2], points: &[u32]) -> f64 {
    points
        .windows(2)
        .map(|w| at[w[0] as usize].distance(at[w[1] as usize]))
        .sum()
}

/// Length of a 3D polyline through `points` (indices into `at`).
pub(crate) fn length_3d(at: &[DVec3], points: &[u32]) -> f64 {
    points
        .windows(2)
        .map(|w| at[w[0] as usize].distance(at[w[1] as usize]))
        .sum()
}

/// The notch fractions of a seam `length` long: both ends, and evenly between them no
/// farther apart than `spacing`.
pub(crate) fn notch_fractions(length: f64, spacing: f64) -> Vec<f64> {
    let parts = if spacing > 0.0 {
        (length / spacing).ceil().max(1.0) as usize
    } else {
        1
    };
    (0..=parts).map(|k| k as f64 / parts as f64).collect()
}

/// The point at fraction `t` of the 3D length along a side (`points` local vertices,
/// `xyz` their 3D positions, `uv` their 2D ones), in 2D, with the boundary's direction there.
pub(crate) fn point_at(xyz: &[DVec3], uv: &[DVec2], points: &[u32], t: f64) -> (DVec2, DVec2) {
    let total = length_3d(xyz, points);
    let target = t * total;
    let mut run = 0.0;
    let last = points.len().saturating_sub(2);
    for (k, w) in points.windows(2).enumerate() {
        let (a, b) = (w[0] as usize, w[1] as usize);
        let l = xyz[a].distance(xyz[b]);
        if run + l >= target || k == last {
            let s = if l > 0.0 {
                ((target - run) / l).clamp(0.0, 1.0)
            } else {
                0.0
            };
            return (uv[a].lerp(uv[b], s), (uv[b] - uv[a]).normalize_or_zero());
        }
        run += l;
    }
    (points.first().map_or(DVec2::ZERO, |&p| uv[p as usize]), DVec2::ZERO)
}
