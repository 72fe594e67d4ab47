//! The whole pattern: cut, flatten (or keep), match the seams, lay out.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};

use super::names::{hint, name_panels};
use super::panels::Panel;
use super::seams::{Seam, seam_tolerance};
use super::types::{Pattern, PatternError, PatternInput, PatternOptions, Piece};
use super::{cut_lines, distortion, flatten, labels, layout, panels, seams};

/// A chain of seam edges with its two sides: curve, panels, mesh vertices, each side's
/// own vertices.
type Sided = (u32, [u32; 2], Vec<u32>, [Vec<u32>; 2]);

/// Per piece, its notches: a seam side (its own vertices) and a fraction of its length.
type NotchesAt = Vec<Vec<(Vec<u32>, f64)>>;

/// Every curve's name, the seam curves chosen, and whether each name is a seam.
type SeamChoice = (Vec<String>, Vec<String>, Vec<bool>);

/// Cuts, flattens, matches and lays out a garment's pattern. A panel equal (positions and
/// triangles, bit for bit, and its seam sides) to one of `previous`'s keeps its flattening.
pub fn build(
    input: &PatternInput<'_>,
    options: &PatternOptions,
    previous: Option<&Pattern>,
) -> Result<Pattern, PatternError> {
    // The mesh split along the cut lines, and each cut's seam edges.
    let mut split = cut_lines::SplitMesh {
        positions: input.positions.to_vec(),
        surfaced: match input.surfaced {
            Some(s) if s.len() == input.positions.len() => s.to_vec(),
            _ => input.positions.to_vec(),
        },
        triangles: input.triangles.to_vec(),
        face_patch: input.face_patch.to_vec(),
    };
    let cut_edges: Vec<Vec<[u32; 2]>> = input.cuts.iter().map(|c| split.split(&c.shape)).collect();
    let input = &PatternInput {
        positions: &split.positions,
        triangles: &split.triangles,
        face_patch: &split.face_patch,
        surfaced: Some(&split.surfaced),
        ..*input
    };
    let (names, seam_curves, chosen) = seam_choice(input, options)?;
    let labels = labels::label_edges(&split.surfaced, input.triangles, input.face_patch, input.curves);
    // Cut lines are seams, each under its own name after the curves'.
    let mut cut_of: BTreeMap<[u32; 2], u32> = BTreeMap::new();
    for (k, edges) in cut_edges.iter().enumerate() {
        for &e in edges {
            cut_of.entry(e).or_insert((input.curves.len() + k) as u32);
        }
    }
    let seam_of = |e: [u32; 2]| {
        cut_of
            .get(&[e[0].min(e[1]), e[0].max(e[1])])
            .copied()
            .or_else(|| labels.of(e).iter().copied().find(|&c| chosen[c as usize]))
    };
    let is_seam = |e: [u32; 2]| seam_of(e).is_some();
    let (panel_of, count) = panels::components(input.triangles, is_seam);
    let panel_names = name_panels(input, &panel_of, count);
    let mut panels = panels::split(input.positions, input.triangles, &panel_of, &panel_names, is_seam);
    for p in &mut panels {
        match panels::disc_boundary(p) {
            Ok(b) => p.boundary = b,
            Err(mut e) => {
                e.hint = hint(input, &labels, &panel_of, p, &chosen);
                return Err(e.into());
            }
        }
    }
    let (chains, runs) = seam_chains(input, &panels, &panel_of, seam_of);
    let mut pieces = Vec::with_capacity(panels.len());
    for (panel, runs) in panels.into_iter().zip(runs) {
        pieces.push(piece(input, panel, runs, options, previous)?);
    }
    let (seam_list, notch_at) = measure_seams(input, chains, &pieces, &names, options);
    lay_out(&mut pieces, &notch_at, options);
    Ok(Pattern {
        source: options.source,
        seam_curves,
        pieces,
        seams: seam_list,
        panel_of,
    })
}

/// Every curve's name (the cut lines' after the curves'), the seam curves chosen, and
/// whether each name is a seam.
fn seam_choice(input: &PatternInput<'_>, options: &PatternOptions) -> Result<SeamChoice, PatternError> {
    let mut names: Vec<String> = input.curves.iter().map(|(n, _)| n.clone()).collect();
    let seam_curves = match &options.seams {
        Some(list) => {
            if let Some(s) = list.iter().find(|s| !names.contains(s)) {
                return Err(PatternError::UnknownSeam {
                    name: s.clone(),
                    known: names.join(", "),
                });
            }
            list.clone()
        }
        None => seams::default_seams(input.template, &names),
    };
    let mut chosen: Vec<bool> = names.iter().map(|n| seam_curves.contains(n)).collect();
    for cut in input.cuts {
        names.push(cut.name.clone());
        chosen.push(true);
    }
    Ok((names, seam_curves, chosen))
}

/// The chains of seam edges with each side's own vertices, and per panel its sides (the
/// runs whose lengths the flattening holds).
fn seam_chains(
    input: &PatternInput<'_>,
    panels: &[Panel],
    panel_of: &[u32],
    seam_of: impl Fn([u32; 2]) -> Option<u32>,
) -> (Vec<Sided>, Vec<Vec<Vec<u32>>>) {
    let mut edges = Vec::new();
    for ((a, b), faces) in panels::interior_edges(input.triangles) {
        if let Some(c) = seam_of([a, b]) {
            edges.push(seams::SeamEdge {
                a,
                b,
                faces: [faces.0, faces.1],
                curve: c,
            });
        }
    }
    let mut chains = Vec::new();
    let mut runs: Vec<Vec<Vec<u32>>> = vec![Vec::new(); panels.len()];
    for (curve, pair, vertices, faces) in seams::chains(&edges, panel_of) {
        // Each edge's ends on each side, taken in the face on that side; the chain broken
        // where a side does not go on from the vertex it reached (another seam opened the
        // panel there, so that one mesh vertex is two of the panel's).
        let at = |k: usize, f: [u32; 2]| -> [[u32; 2]; 2] {
            [0, 1].map(|s| {
                let piece = &panels[pair[s] as usize];
                [vertices[k], vertices[k + 1]].map(|v| seams::local_vertex(piece, input.triangles, f[s], v))
            })
        };
        let mut ends: Vec<[[u32; 2]; 2]> = Vec::with_capacity(faces.len());
        for (k, f) in faces.iter().enumerate() {
            let mut e = at(k, *f);
            // Both sides in one panel (a slit): which face is which side follows the side
            // the chain is on, not the faces' order.
            if pair[0] == pair[1]
                && let Some(last) = ends.last()
                && (0..2).any(|s| e[s][0] != last[s][1])
            {
                let swapped = at(k, [f[1], f[0]]);
                if (0..2).all(|s| swapped[s][0] == last[s][1]) {
                    e = swapped;
                }
            }
            ends.push(e);
        }
        // An edge whose two sides are the same edge of one panel did not open it.
        let closed = |k: usize| pair[0] == pair[1] && ends[k][0] == ends[k][1];
        let mut start = 0;
        for k in 1..=ends.len() {
            let breaks =
                k == ends.len() || (0..2).any(|s| ends[k][s][0] != ends[k - 1][s][1]) || closed(k) != closed(k - 1);
            if !breaks {
                continue;
            }
            let part = &ends[start..k];
            let sides = [0, 1].map(|s| {
                let mut side: Vec<u32> = part.iter().map(|e| e[s][0]).collect();
                side.push(part[part.len() - 1][s][1]);
                side
            });
            let mesh_vertices = vertices[start..=k].to_vec();
            let start_of = start;
            start = k;
            // A stretch of seam that runs into a panel without opening it (its two sides the
            // same edges: a stray stretch of a curve inside) cuts nothing.
            if closed(start_of) {
                continue;
            }
            for s in 0..2 {
                let run = &mut runs[pair[s] as usize];
                if !run.contains(&sides[s]) {
                    run.push(sides[s].clone());
                }
            }
            chains.push((curve, pair, mesh_vertices, sides));
        }
    }
    (chains, runs)
}

/// One panel flattened (or its flattening kept from `previous`) and measured.
fn piece(
    input: &PatternInput<'_>,
    panel: Panel,
    runs: Vec<Vec<u32>>,
    options: &PatternOptions,
    previous: Option<&Pattern>,
) -> Result<Piece, PatternError> {
    let kept = previous.and_then(|prev| {
        prev.pieces
            .iter()
            .find(|q| {
                q.panel.triangles == panel.triangles
                    && q.runs == runs
                    && same_bits(&q.panel.positions, &panel.positions)
            })
            .map(|q| q.flat.clone())
    });
    let reused = kept.is_some();
    let flat = match kept {
        Some(f) => f,
        None => flatten::flatten(&panel.positions, &panel.triangles, &runs, &options.flatten).map_err(|source| {
            PatternError::Flatten {
                panel: panel.name.clone(),
                source,
            }
        })?,
    };
    let distortion = distortion::measure(&panel.positions, &panel.triangles, &flat.uv, &panel.boundary);
    let mut vertex_strain = vec![0.0_f64; panel.positions.len()];
    for ([a, b], s) in distortion::edge_strains(&panel.positions, &panel.triangles, &flat.uv) {
        vertex_strain[a as usize] = vertex_strain[a as usize].max(s);
        vertex_strain[b as usize] = vertex_strain[b as usize].max(s);
    }
    let mut patches: Vec<String> = panel
        .faces
        .iter()
        .map(|&f| input.patch_names[input.face_patch[f as usize] as usize].clone())
        .collect();
    patches.sort();
    patches.dedup();
    let area_3d: f64 = panel
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| panel.positions[i as usize]);
            0.5 * (b - a).cross(c - a).length()
        })
        .sum();
    let area_2d: f64 = panel
        .triangles
        .iter()
        .map(|t| flatten::signed_area(flat.uv[t[0] as usize], flat.uv[t[1] as usize], flat.uv[t[2] as usize]))
        .sum();
    Ok(Piece {
        uv: flat.uv.clone(),
        panel,
        patches,
        flat,
        distortion,
        vertex_strain,
        grain: [DVec2::ZERO; 2],
        notches: Vec::new(),
        area_3d,
        area_2d,
        reused,
        runs,
    })
}

/// The seams measured on the flattenings (lengths do not change with the layout), named,
/// and per piece its notches (a side and a fraction of its length).
fn measure_seams(
    input: &PatternInput<'_>,
    chains: Vec<Sided>,
    pieces: &[Piece],
    names: &[String],
    options: &PatternOptions,
) -> (Vec<Seam>, NotchesAt) {
    let mut seam_list = Vec::new();
    let mut notch_at: NotchesAt = vec![Vec::new(); pieces.len()];
    for (curve, pair, vertices, sides) in chains {
        let length_3d = seams::length_3d(input.positions, &vertices);
        let length_2d = [0, 1].map(|s| seams::length_2d(&pieces[pair[s] as usize].flat.uv, &sides[s]));
        let notches = seams::notch_fractions(length_3d, options.notch_spacing);
        for s in 0..2 {
            for &t in &notches {
                notch_at[pair[s] as usize].push((sides[s].clone(), t));
            }
        }
        let (a, b) = (
            &pieces[pair[0] as usize].panel.name,
            &pieces[pair[1] as usize].panel.name,
        );
        seam_list.push(Seam {
            name: format!("{a}|{b}"),
            curve: names[curve as usize].clone(),
            panels: [pair[0] as usize, pair[1] as usize],
            sides,
            length_3d,
            length_2d,
            mismatch: (length_2d[0] - length_2d[1]).abs(),
            tolerance: seam_tolerance(length_3d),
            notches,
        });
    }
    // Names of seams between the same two panels on several curves get their curve.
    let mut counts: BTreeMap<String, usize> = Default::default();
    for s in &seam_list {
        *counts.entry(s.name.clone()).or_default() += 1;
    }
    let mut seen: BTreeMap<String, usize> = Default::default();
    for s in &mut seam_list {
        if counts[&s.name] > 1 {
            let k = seen.entry(format!("{}#{}", s.name, s.curve)).or_default();
            *k += 1;
            s.name = if *k > 1 {
                format!("{}#{}.{k}", s.name, s.curve)
            } else {
                format!("{}#{}", s.name, s.curve)
            };
        }
    }
    (seam_list, notch_at)
}

/// Turns each piece to its grain, lays them out, and places the grain lines and notches.
fn lay_out(pieces: &mut [Piece], notch_at: &NotchesAt, options: &PatternOptions) {
    let mut bounds = Vec::with_capacity(pieces.len());
    for piece in pieces.iter_mut() {
        let grain = layout::grain_direction(&piece.panel.positions, &piece.panel.triangles, &piece.flat.uv);
        let turn = layout::grain_rotation(grain);
        piece.uv = piece.flat.uv.iter().map(|&p| turn * p).collect();
        let (lo, hi) = piece
            .uv
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        bounds.push((lo, hi));
    }
    let places = layout::shelves(&bounds, options.table_width, options.gap);
    for (k, piece) in pieces.iter_mut().enumerate() {
        let shift = places[k];
        for p in &mut piece.uv {
            *p += shift;
        }
        let (lo, hi) = (bounds[k].0 + shift, bounds[k].1 + shift);
        let x = 0.5 * (lo.x + hi.x);
        piece.grain = [
            DVec2::new(x, lo.y + 0.15 * (hi.y - lo.y)),
            DVec2::new(x, lo.y + 0.85 * (hi.y - lo.y)),
        ];
        for (side, t) in &notch_at[k] {
            let (at, along) = seams::point_at(&piece.panel.positions, &piece.uv, side, *t);
            // The boundary runs counter-clockwise with the piece on its left; a seam side may
            // run either way, so the inward direction is whichever side the piece's
            // centroid lies on.
            let left = along.perp();
            let centre = piece.uv.iter().copied().sum::<DVec2>() / piece.uv.len() as f64;
            let inward = if (centre - at).dot(left) >= 0.0 { left } else { -left };
            piece.notches.push((at, inward));
        }
    }
}

/// Two position lists equal bit for bit.
fn same_bits(a: &[DVec3], b: &[DVec3]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits))
}
