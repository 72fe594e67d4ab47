//! Names for the panels, and the hint that goes with a panel that is not a disc.

use std::collections::BTreeMap;

use glam::DVec3;

use super::labels::EdgeCurves;
use super::panels::{self, Panel};
use super::seams;
use super::types::PatternInput;

/// Panel names: the first part of the name of the patch with most faces in it (`torso`,
/// `leg`, `sleeve`, ...), then `front` or `back` by its mean normal and `left` or `right` by
/// its mean `x`; repeated names numbered.
pub(super) fn name_panels(input: &PatternInput<'_>, panel_of: &[u32], count: usize) -> Vec<String> {
    let (lo, hi) = input
        .positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let centre_x = 0.5 * (lo.x + hi.x);
    let width = (hi.x - lo.x).max(f64::MIN_POSITIVE);
    let mut faces_by_patch = vec![BTreeMap::<u32, usize>::new(); count];
    let mut normal = vec![DVec3::ZERO; count];
    let mut centroid = vec![DVec3::ZERO; count];
    let mut area = vec![0.0; count];
    for (f, t) in input.triangles.iter().enumerate() {
        let p = panel_of[f] as usize;
        *faces_by_patch[p].entry(input.face_patch[f]).or_default() += 1;
        let [a, b, c] = t.map(|i| input.positions[i as usize]);
        let n = (b - a).cross(c - a);
        normal[p] += n;
        centroid[p] += 0.5 * n.length() * (a + b + c) / 3.0;
        area[p] += 0.5 * n.length();
    }
    let mut names: Vec<String> = (0..count)
        .map(|p| {
            let patch = faces_by_patch[p]
                .iter()
                .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
                .map_or(0, |(k, _)| *k);
            let group = input.patch_names[patch as usize].split('.').next().unwrap_or("panel");
            let n = normal[p].normalize_or_zero();
            let x = centroid[p].x / area[p].max(f64::MIN_POSITIVE) - centre_x;
            let mut side = Vec::new();
            if n.z > 0.25 {
                side.push("front");
            } else if n.z < -0.25 {
                side.push("back");
            }
            if x > 0.05 * width {
                side.push("left");
            } else if x < -0.05 * width {
                side.push("right");
            }
            if side.is_empty() {
                group.to_string()
            } else {
                format!("{group}.{}", side.join("_"))
            }
        })
        .collect();
    let mut seen: BTreeMap<String, usize> = Default::default();
    let totals = names.iter().fold(BTreeMap::<String, usize>::new(), |mut m, n| {
        *m.entry(n.clone()).or_default() += 1;
        m
    });
    for n in &mut names {
        if totals[n] > 1 {
            let k = seen.entry(n.clone()).or_default();
            *k += 1;
            *n = format!("{n}.{k}");
        }
    }
    names
}

/// The curves that cross a panel that is not a disc (the template's default seams first), as
/// a hint of where to cut it.
pub(super) fn hint(
    input: &PatternInput<'_>,
    labels: &EdgeCurves,
    panel_of: &[u32],
    panel: &Panel,
    chosen: &[bool],
) -> String {
    let index = panel_of[panel.faces[0] as usize];
    let mut inside = std::collections::BTreeSet::new();
    for ((a, b), (fa, fb)) in panels::interior_edges(input.triangles) {
        if panel_of[fa as usize] == index && panel_of[fb as usize] == index {
            for &c in labels.of([a, b]) {
                if !chosen[c as usize] {
                    inside.insert(labels.names[c as usize].clone());
                }
            }
        }
    }
    if inside.is_empty() {
        return String::new();
    }
    // The template's default seams first, then the rest by name.
    let defaults = seams::default_seams(input.template, &labels.names);
    let (mut list, rest): (Vec<String>, Vec<String>) = inside.into_iter().partition(|c| defaults.contains(c));
    list.sort_by_key(|c| defaults.iter().position(|d| d == c));
    list.extend(rest);
    list.truncate(6);
    format!(" (curves across it: {})", list.join(", "))
}
