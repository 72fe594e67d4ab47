//! A garment mesh from another tool made ready for the collision layers: its faces fanned
//! into triangles, coincident vertices welded, faces that repeat a vertex dropped, every
//! part oriented consistently and then away from the body, its size and place checked
//! against the body. Each repair is counted and reported; what cannot be repaired is an
//! error that names the element and the line of the file.

use std::collections::BTreeMap;

use glam::DVec3;
use serde::Serialize;

use crate::collision::BodyIndex;
use crate::collision::GarmentMesh;
use crate::mesh::topology::{boundary_vertices, face_labels_by_vertex, undirected_edges};
use crate::mesh::validate::consistent_parts;
use crate::mesh::{Adjacency, MeshDocument, MeshError, MeshFileError, TriMesh};

/// What reading the garment found and repaired.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ImportNotes {
    /// Vertices and faces in the file.
    pub vertices: usize,
    /// Faces in the file.
    pub faces: usize,
    /// Faces with more than three corners, fanned into triangles.
    pub polygons_triangulated: usize,
    /// Triangles the collision uses.
    pub triangles: usize,
    /// Vertices at exactly the position of an earlier one (a seam written twice), welded
    /// for the collision; both keep their place in the file and move together.
    pub duplicate_vertices_welded: usize,
    /// Triangles dropped because two of their corners are one vertex (after welding).
    pub degenerate_triangles_dropped: usize,
    /// Where the first of those are in the file: their lines (OBJ) or face numbers
    /// (1-based).
    pub degenerate_lines: Vec<usize>,
    /// "line" or "face": what [`Self::degenerate_lines`] count.
    pub place_word: &'static str,
    /// Triangles of zero area (kept).
    pub zero_area_triangles: usize,
    /// Vertices no face uses (left as they are).
    pub unused_vertices: usize,
    /// Triangles turned to agree with their neighbours.
    pub turned_to_agree: usize,
    /// Parts that faced the body (inside out), turned to face away from it, and their
    /// triangles. The file's faces are written back as they were.
    pub inside_out_parts: usize,
    /// Triangles in those.
    pub inside_out_triangles: usize,
    /// Edge-connected parts.
    pub parts: usize,
    /// Edges with one face (the garment's openings).
    pub boundary_edges: usize,
}

impl ImportNotes {
    /// The repairs and warnings, one line each.
    pub fn lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        let mut note = |n: usize, text: String| {
            if n > 0 {
                out.push(format!("{n} {text}"));
            }
        };
        note(self.polygons_triangulated, "polygon(s) fanned into triangles".into());
        note(
            self.duplicate_vertices_welded,
            "duplicate vertex(es) welded for the collision (each moves with its twin)".into(),
        );
        let lines: Vec<String> = self.degenerate_lines.iter().map(ToString::to_string).collect();
        note(
            self.degenerate_triangles_dropped,
            format!(
                "triangle(s) repeating a vertex left out ({}s {})",
                self.place_word,
                lines.join(", ")
            ),
        );
        note(self.zero_area_triangles, "zero-area triangle(s) kept".into());
        note(self.unused_vertices, "vertex(es) no face uses, left as they are".into());
        note(
            self.turned_to_agree,
            "triangle(s) turned to agree with their neighbours (for the collision; the file keeps its faces)".into(),
        );
        note(
            self.inside_out_parts,
            format!(
                "part(s) inside out ({} triangles facing the body), turned for the collision; the file keeps its faces",
                self.inside_out_triangles
            ),
        );
        out
    }
}

/// Why a garment file cannot be collided.
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    /// The file could not be read or parsed.
    #[error(transparent)]
    File(#[from] MeshFileError),
    /// An edge shared by three or more faces, an unorientable part, or nothing left.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The garment's size is far from the body's: other units.
    #[error("{file}: the garment is {garment:.3} m across and the body {body:.3} m tall ({ratio:.3} times): {hint}")]
    Scale {
        /// File.
        file: String,
        /// Garment bounding-box diagonal, m (as read with the units given).
        garment: f64,
        /// Body height, m.
        body: f64,
        /// Their ratio.
        ratio: f64,
        /// Which units would fit.
        hint: String,
    },
    /// The garment's box does not meet the body's: another frame.
    #[error(
        "{file}: the garment (from {lo:?} to {hi:?} m) does not overlap the body (from {body_lo:?} to {body_hi:?} m): is it in the body's frame (metres, y up, facing +z)?"
    )]
    Apart {
        /// File.
        file: String,
        /// Garment box.
        lo: [f64; 3],
        /// Garment box.
        hi: [f64; 3],
        /// Body box.
        body_lo: [f64; 3],
        /// Body box.
        body_hi: [f64; 3],
    },
}

/// A garment from a file, ready to collide.
#[derive(Clone, Debug)]
pub struct ImportedGarment {
    /// The file as read.
    pub doc: MeshDocument,
    /// The mesh the collision layers see: one vertex per distinct position used by a face,
    /// its triangles oriented away from the body, one patch per group of the file.
    pub mesh: GarmentMesh,
    /// Per file vertex, its vertex in [`Self::mesh`] (`u32::MAX` for a vertex no face uses).
    pub to_mesh: Vec<u32>,
    /// What was found and repaired.
    pub notes: ImportNotes,
}

/// The garment may be at most this many times the body's height across, and at least
/// `1 / SIZE_RATIO` of it (a sock is a tenth): beyond, its units are not the body's.
const SIZE_RATIO: f64 = 20.0;

impl ImportedGarment {
    /// Prepares `doc` against a body (its mesh and index).
    ///
    /// # Failures
    /// [`ImportError`]: a non-manifold edge or an unorientable part (named by vertex and
    /// line), no usable triangle, a size that fits other units, or a garment apart from
    /// the body.
    pub fn new(doc: MeshDocument, body: &TriMesh, index: &BodyIndex) -> Result<Self, ImportError> {
        let place = format!("{}: ", doc.name);
        check_size_and_place(&doc, body)?;
        let mut notes = ImportNotes {
            vertices: doc.contents.positions.len(),
            faces: doc.contents.faces.len(),
            polygons_triangulated: doc.contents.faces.iter().filter(|f| f.corners.len() > 3).count(),
            place_word: doc.format.place_word(),
            ..ImportNotes::default()
        };
        let (file_triangles, face_of) = doc.triangles();
        let (positions, to_mesh) = weld(&doc, &file_triangles, &mut notes);
        // Triangles over the welded vertices, those repeating one left out.
        let mut triangles = Vec::with_capacity(file_triangles.len());
        let mut lines = Vec::with_capacity(file_triangles.len());
        let mut groups = Vec::with_capacity(file_triangles.len());
        for (t, f) in file_triangles.iter().zip(&face_of) {
            let m = t.map(|v| to_mesh[v as usize]);
            let face = &doc.contents.faces[*f as usize];
            if m[0] == m[1] || m[1] == m[2] || m[0] == m[2] {
                notes.degenerate_triangles_dropped += 1;
                if notes.degenerate_lines.len() < 10 && notes.degenerate_lines.last() != Some(&face.at) {
                    notes.degenerate_lines.push(face.at);
                }
                continue;
            }
            triangles.push(m);
            lines.push(face.at);
            groups.push(face.group);
        }
        if triangles.is_empty() {
            return Err(MeshError::NoTriangles {
                place,
                count: file_triangles.len(),
            }
            .into());
        }
        let mut mesh = TriMesh { positions, triangles };
        let adjacency = Adjacency::try_new(&mesh).map_err(|e| {
            let shown: Vec<String> = e
                .triangles
                .iter()
                .filter_map(|&t| lines.get(t as usize))
                .map(ToString::to_string)
                .collect();
            // Name the edge by the file's vertex numbers.
            let file_vertex = |m: u32| to_mesh.iter().position(|&x| x == m).map_or(m + 1, |v| v as u32 + 1);
            MeshError::NonManifold {
                place: place.clone(),
                a: file_vertex(e.vertices[0]),
                b: file_vertex(e.vertices[1]),
                count: e.triangles.len(),
                lines: format!(" ({}s {})", doc.format.place_word(), shown.join(", ")),
            }
        })?;
        notes.boundary_edges = adjacency.boundary_edges;
        let (flipped, parts) = consistent_parts(&mesh, &adjacency, (&lines, doc.format.place_word()), &place)?;
        notes.turned_to_agree = flipped.iter().filter(|f| **f).count();
        notes.parts = parts.len();
        for (t, &flip) in mesh.triangles.iter_mut().zip(&flipped) {
            if flip {
                t.swap(1, 2);
            }
        }
        face_away(&mut mesh, &parts, index, &mut notes);
        let diagonal_sq = mesh.bounds().map_or(0.0, |(lo, hi)| (hi - lo).length_squared());
        notes.zero_area_triangles = (0..mesh.triangles.len())
            .filter(|&t| mesh.scaled_normal(t).length() * 0.5 <= 1e-12 * diagonal_sq)
            .count();
        notes.triangles = mesh.triangles.len();
        let garment = garment_mesh(mesh, &groups, doc.contents.groups.len());
        Ok(Self {
            doc,
            mesh: garment,
            to_mesh,
            notes,
        })
    }

    /// The same garment with its faces in other patches (`face_patch`, one per triangle,
    /// below `patches`): the collision's roles (each vertex's patches) made again.
    pub fn with_face_patches(self, face_patch: &[u32], patches: usize) -> Self {
        Self {
            mesh: garment_mesh(self.mesh.mesh, face_patch, patches),
            doc: self.doc,
            to_mesh: self.to_mesh,
            notes: self.notes,
        }
    }

    /// The file's vertices at the collision mesh's `positions`, and which of them moved
    /// (bit for bit): what [`MeshDocument::write`] takes.
    pub fn file_positions(&self, positions: &[DVec3]) -> (Vec<DVec3>, Vec<bool>) {
        self.doc
            .contents
            .positions
            .iter()
            .zip(&self.to_mesh)
            .map(|(p, &m)| match positions.get(m as usize) {
                Some(q) if q != p => (*q, true),
                _ => (*p, false),
            })
            .unzip()
    }
}

/// One vertex per distinct position among those the faces use (exact duplicates, a seam
/// written twice, welded): the positions and, per file vertex, its welded vertex
/// (`u32::MAX` for a vertex no face uses).
fn weld(doc: &MeshDocument, file_triangles: &[[u32; 3]], notes: &mut ImportNotes) -> (Vec<DVec3>, Vec<u32>) {
    let mut used = vec![false; doc.contents.positions.len()];
    for t in file_triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    notes.unused_vertices = used.iter().filter(|u| !**u).count();
    let mut first_at: BTreeMap<[u64; 3], u32> = BTreeMap::new();
    let mut to_mesh = vec![u32::MAX; doc.contents.positions.len()];
    let mut positions = Vec::new();
    for (v, p) in doc.contents.positions.iter().enumerate() {
        if !used[v] {
            continue;
        }
        // `+ 0.0` makes -0 and 0 one key.
        let key = [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits());
        let next = positions.len() as u32;
        let id = *first_at.entry(key).or_insert(next);
        if id == next {
            positions.push(*p);
        } else {
            notes.duplicate_vertices_welded += 1;
        }
        to_mesh[v] = id;
    }
    (positions, to_mesh)
}

/// Turns each part (consistently oriented) to face away from the body: its area-weighted
/// normals agree, on the whole, with the body's outward normal at the nearest skin (also
/// where the garment dips inside).
fn face_away(mesh: &mut TriMesh, parts: &[Vec<usize>], index: &BodyIndex, notes: &mut ImportNotes) {
    for members in parts {
        if crate::layers::facing(mesh, members.iter().copied(), index) < 0.0 {
            notes.inside_out_parts += 1;
            notes.inside_out_triangles += members.len();
            for &t in members {
                mesh.triangles[t].swap(1, 2);
            }
        }
    }
}

/// The garment's size against the body's height, and its box against the body's.
fn check_size_and_place(doc: &MeshDocument, body: &TriMesh) -> Result<(), ImportError> {
    let (lo, hi) = doc
        .contents
        .positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let Some((body_lo, body_hi)) = body.bounds() else {
        return Ok(());
    };
    let (garment, height) = ((hi - lo).length(), (body_hi - body_lo).y);
    let ratio = garment / height;
    if !(1.0 / SIZE_RATIO..=SIZE_RATIO).contains(&ratio) {
        let file_units = garment / doc.scale;
        let hint = [("mm", 1e-3), ("cm", 1e-2), ("m", 1.0), ("inches", 0.0254)]
            .into_iter()
            .map(|(name, s)| (name, (file_units * s / height).ln().abs()))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(String::new(), |(name, _)| {
                format!("the file is likely in {name} (give its units: units={name})")
            });
        return Err(ImportError::Scale {
            file: doc.name.clone(),
            garment,
            body: height,
            ratio,
            hint,
        });
    }
    let apart = (0..3).any(|k| hi[k] < body_lo[k] || lo[k] > body_hi[k]);
    if apart {
        return Err(ImportError::Apart {
            file: doc.name.clone(),
            lo: lo.to_array(),
            hi: hi.to_array(),
            body_lo: body_lo.to_array(),
            body_hi: body_hi.to_array(),
        });
    }
    Ok(())
}

/// The collision's view of a garment mesh: one patch per group of the file, no rings, no
/// curves (nothing is skipped as an unchanged patch).
fn garment_mesh(mesh: TriMesh, groups: &[u32], group_count: usize) -> GarmentMesh {
    let n = mesh.positions.len();
    let boundary = boundary_vertices(&mesh);
    let vertex_patches = std::sync::Arc::new(face_labels_by_vertex(n, &mesh.triangles, groups));
    GarmentMesh {
        normals: mesh.vertex_normals(),
        edges: std::sync::Arc::new(undirected_edges(&mesh)),
        face_patch: std::sync::Arc::new(groups.to_vec()),
        boundary: std::sync::Arc::new(boundary),
        ring_normal: vec![None; n],
        vertex_patches,
        patch_curves: vec![Vec::new(); group_count],
        controls: BTreeMap::new(),
        mesh,
    }
}
