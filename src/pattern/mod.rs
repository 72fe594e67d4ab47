//! Pattern pieces: the garment cut into panels along its seams, each panel flattened with
//! its distortion measured, the two sides of every seam matched, the pieces laid out for
//! cutting (`docs/design.md` section 9; \[frame\] section 6, the paper's last stage).
//!
//! The data flow: the mesh's edges between patches are labelled with the feature curves
//! they lie on ([`labels`]); the edges on the chosen seam curves cut the faces into panels
//! ([`panels`]), each checked to be a disc; each panel is flattened ([`flatten`]: LSCM,
//! then ARAP with the boundary held at its 3D lengths) and measured ([`distortion`]); the
//! seams are chained and their sides' 2D lengths compared ([`seams`]); each piece is
//! turned to its grain and the pieces are laid out ([`layout`]). A panel whose triangles
//! and positions are the previous pattern's, bit for bit, keeps its flattening.
//! [`export`] writes DXF, SVG, JSON and OBJ. Nothing here knows Rerun.

pub mod cut_lines;
pub mod distortion;
pub mod export;
pub mod flatten;
pub mod labels;
pub mod layout;
pub mod panels;
pub mod seams;

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use serde::Serialize;

pub use cut_lines::{CutLine, CutShape};
pub use distortion::Distortion;
pub use flatten::{FlattenError, FlattenOptions, Flattening, Method};
pub use labels::EdgeCurves;
pub use panels::{NotADisc, Panel};
pub use seams::{DEFAULT_SEAMS, Seam, seam_tolerance};

/// Which mesh the pattern is cut from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Source {
    /// M0 after its collision response (default).
    #[default]
    M0,
    /// M1, the refined mesh after its collision (its faces keep their patch).
    M1,
}

impl Source {
    /// The name in sessions.
    pub fn name(self) -> &'static str {
        match self {
            Self::M0 => "m0",
            Self::M1 => "m1",
        }
    }
}

/// Pattern settings (the session's `patterns` statement).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatternOptions {
    /// The seam curves; `None` is the template's default set ([`seams::default_seams`]).
    pub seams: Option<Vec<String>>,
    /// The mesh cut (default M0).
    pub source: Source,
    /// The flattening.
    pub flatten: FlattenOptions,
    /// Notches along a seam at most this far apart, m (default 0.1).
    pub notch_spacing: f64,
    /// The width of the table the pieces are laid out on, m (default 1.5, a cutting table).
    pub table_width: f64,
    /// Space between pieces on the table, m (default 0.02).
    pub gap: f64,
}

impl Default for PatternOptions {
    fn default() -> Self {
        Self {
            seams: None,
            source: Source::M0,
            flatten: FlattenOptions::default(),
            notch_spacing: 0.1,
            table_width: 1.5,
            gap: 0.02,
        }
    }
}

/// What a pattern is cut from.
#[derive(Clone, Copy, Debug)]
pub struct PatternInput<'a> {
    /// Template name (for the default seams).
    pub template: &'a str,
    /// Mesh positions, m.
    pub positions: &'a [DVec3],
    /// Mesh triangles, counter-clockwise seen from outside.
    pub triangles: &'a [[u32; 3]],
    /// The patch of each triangle.
    pub face_patch: &'a [u32],
    /// Patch names, by index.
    pub patch_names: &'a [String],
    /// The feature curves as polylines, by name.
    pub curves: &'a [(String, Vec<DVec3>)],
    /// The user's cut lines: seams too, the mesh split along them first.
    pub cuts: &'a [CutLine],
}

/// Why a pattern cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PatternError {
    /// A named seam is not a curve of the garment.
    #[error("seam {name:?} is not a curve of this garment; its curves: {known}")]
    UnknownSeam {
        /// The name.
        name: String,
        /// The garment's curves, comma-separated.
        known: String,
    },
    /// A panel is not a disc.
    #[error(transparent)]
    NotADisc(#[from] NotADisc),
    /// A panel could not be flattened.
    #[error("panel {panel}: {source}")]
    Flatten {
        /// The panel.
        panel: String,
        /// Why.
        source: FlattenError,
    },
}

/// One pattern piece.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// The panel it comes from.
    pub panel: Panel,
    /// Its patches' names.
    pub patches: Vec<String>,
    /// The flattening, as solved (before the layout).
    pub flat: Flattening,
    /// 2D position of every vertex on the table, m (turned to the grain, laid out).
    pub uv: Vec<DVec2>,
    /// Its distortion.
    pub distortion: Distortion,
    /// Per vertex, the largest strain of its edges (for colouring).
    pub vertex_strain: Vec<f64>,
    /// The grain line on the table (both ends), m.
    pub grain: [DVec2; 2],
    /// Notches on the table: the point on the cut line and the unit direction into the
    /// piece.
    pub notches: Vec<(DVec2, DVec2)>,
    /// 3D area and 2D area, m2.
    pub area_3d: f64,
    /// 2D area, m2.
    pub area_2d: f64,
    /// Whether its flattening was kept from the previous pattern.
    pub reused: bool,
    /// Its sides of seams (own vertices along each), held at their 3D lengths.
    pub runs: Vec<Vec<u32>>,
}

/// A garment's pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct Pattern {
    /// The mesh it was cut from.
    pub source: Source,
    /// The seam curves used.
    pub seam_curves: Vec<String>,
    /// The pieces, in the order of their first face in the mesh.
    pub pieces: Vec<Piece>,
    /// The seams, by curve and panels.
    pub seams: Vec<Seam>,
    /// The panel of each mesh face.
    pub panel_of: Vec<u32>,
}

impl Pattern {
    /// Pieces flattened again (not kept from the previous pattern).
    pub fn flattened(&self) -> usize {
        self.pieces.iter().filter(|p| !p.reused).count()
    }

    /// Every seam within its tolerance.
    pub fn sews(&self) -> bool {
        self.seams.iter().all(Seam::sews)
    }
}

/// Cuts, flattens, matches and lays out a garment's pattern. A panel equal (positions and
/// triangles, bit for bit) to one of `previous`'s keeps its flattening.
pub fn build(
    input: &PatternInput<'_>,
    options: &PatternOptions,
    previous: Option<&Pattern>,
) -> Result<Pattern, PatternError> {
    // The mesh split along the cut lines, and each cut's seam edges.
    let mut split = cut_lines::SplitMesh {
        positions: input.positions.to_vec(),
        triangles: input.triangles.to_vec(),
        face_patch: input.face_patch.to_vec(),
    };
    let cut_edges: Vec<Vec<[u32; 2]>> = input.cuts.iter().map(|c| split.split(&c.shape)).collect();
    let input = &PatternInput {
        positions: &split.positions,
        triangles: &split.triangles,
        face_patch: &split.face_patch,
        ..*input
    };
    let mut names: Vec<String> = input.curves.iter().map(|(n, _)| n.clone()).collect();
    let seam_curves = match &options.seams {
        Some(list) => {
            for s in list {
                if !names.contains(s) {
                    return Err(PatternError::UnknownSeam {
                        name: s.clone(),
                        known: names.join(", "),
                    });
                }
            }
            list.clone()
        }
        None => seams::default_seams(input.template, &names),
    };
    let mut chosen: Vec<bool> = names.iter().map(|n| seam_curves.contains(n)).collect();
    let labels = labels::label_edges(input.positions, input.triangles, input.face_patch, input.curves);
    // Cut lines are seams, each under its own name after the curves'.
    let mut cut_of: BTreeMap<[u32; 2], u32> = BTreeMap::new();
    for (cut, edges) in input.cuts.iter().zip(&cut_edges) {
        let index = names.len() as u32;
        names.push(cut.name.clone());
        chosen.push(true);
        for &e in edges {
            cut_of.entry(e).or_insert(index);
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
    // Seams: chains of seam edges, each side's own vertices.
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
    for (curve, pair, vertices, faces) in seams::chains(&edges, &panel_of) {
        let side = |s: usize| -> Vec<u32> {
            let piece = &panels[pair[s] as usize];
            vertices
                .iter()
                .enumerate()
                .map(|(k, &v)| {
                    let f = faces[k.min(faces.len() - 1)][s];
                    seams::local_vertex(piece, input.triangles, f, v)
                })
                .collect()
        };
        let sides = [side(0), side(1)];
        for s in 0..2 {
            runs[pair[s] as usize].push(sides[s].clone());
        }
        chains.push((curve, pair, vertices, sides));
    }
    // Flatten (or keep) every panel.
    let mut pieces = Vec::with_capacity(panels.len());
    for (panel, runs) in panels.into_iter().zip(runs) {
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
            None => {
                flatten::flatten(&panel.positions, &panel.triangles, &runs, &options.flatten).map_err(|source| {
                    PatternError::Flatten {
                        panel: panel.name.clone(),
                        source,
                    }
                })?
            }
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
        pieces.push(Piece {
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
        });
    }
    // Seams, measured on the flattenings (lengths do not change with the layout).
    let mut seam_list = Vec::new();
    let mut notch_at: Vec<Vec<(Vec<u32>, f64)>> = vec![Vec::new(); pieces.len()];
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
    // Turn each piece to its grain, then lay them out.
    let mut bounds = Vec::with_capacity(pieces.len());
    for piece in &mut pieces {
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
    Ok(Pattern {
        source: options.source,
        seam_curves,
        pieces,
        seams: seam_list,
        panel_of,
    })
}

/// Two position lists equal bit for bit.
fn same_bits(a: &[DVec3], b: &[DVec3]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits))
}

/// Panel names: the first part of the name of the patch with most faces in it (`torso`,
/// `leg`, `sleeve`, ...), then `front` or `back` by its mean normal and `left` or `right` by
/// its mean `x`; repeated names numbered.
fn name_panels(input: &PatternInput<'_>, panel_of: &[u32], count: usize) -> Vec<String> {
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
fn hint(input: &PatternInput<'_>, labels: &EdgeCurves, panel_of: &[u32], panel: &Panel, chosen: &[bool]) -> String {
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
