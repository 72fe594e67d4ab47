//! A whole mesh file kept as read (OBJ, PLY, glTF or GLB), to be written back in its own
//! format with only some vertices moved.
//!
//! [`super::read_obj`] reads what drape needs of a body (positions and triangles). A garment
//! from another tool comes with texture coordinates, normals, groups, materials and
//! comments that the tool it goes back to needs, in an order it expects. [`MeshDocument`]
//! keeps the file: its vertices in the file's order, its faces as polygons with their
//! groups, and whatever the format needs to write the file again
//! ([`MeshDocument::write`]): the positions of the moved vertices and the normals they use
//! written anew, everything else as read, so an unmoved vertex keeps its exact coordinates.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use glam::{DMat3, DVec3};

use super::gltf_doc::GltfKeep;
use super::obj::ObjMesh;
use super::obj_doc::ObjText;
use super::ply_doc::PlyKeep;
use super::{MeshFileError, TriMesh};

/// The file formats drape reads and writes garments in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (text).
    Obj,
    /// Stanford PLY (text or binary).
    Ply,
    /// glTF 2.0 as JSON, its buffers embedded or beside it.
    Gltf,
    /// glTF 2.0 binary.
    Glb,
}

impl MeshFormat {
    /// The format a file name's extension names (any case), if one drape reads.
    pub fn of_path(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "obj" => Some(Self::Obj),
            "ply" => Some(Self::Ply),
            "gltf" => Some(Self::Gltf),
            "glb" => Some(Self::Glb),
            _ => None,
        }
    }

    /// The format of a file's first bytes, where they tell: PLY and GLB have magic numbers.
    pub fn sniff(bytes: &[u8]) -> Option<Self> {
        if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") {
            Some(Self::Ply)
        } else if bytes.starts_with(b"glTF") {
            Some(Self::Glb)
        } else {
            None
        }
    }

    /// The format's name, for messages.
    pub fn name(self) -> &'static str {
        match self {
            Self::Obj => "OBJ",
            Self::Ply => "PLY",
            Self::Gltf => "glTF",
            Self::Glb => "GLB",
        }
    }

    /// The file name extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Self::Obj => "obj",
            Self::Ply => "ply",
            Self::Gltf => "gltf",
            Self::Glb => "glb",
        }
    }

    /// How a face is pointed at in messages: by its line in an OBJ file, by its number
    /// (1-based, in file order) in the others.
    pub fn place_word(self) -> &'static str {
        match self {
            Self::Obj => "line",
            Self::Ply | Self::Gltf | Self::Glb => "face",
        }
    }
}

/// What drape reads: OBJ, PLY, glTF or GLB, by extension.
pub const READABLE: &str = "drape reads meshes as OBJ, PLY, glTF or GLB (.obj, .ply, .gltf, .glb)";

/// Reads a body's mesh (positions and triangles) of at most `max_bytes` from an OBJ, PLY,
/// glTF or GLB file (as [`MeshDocument::read`] tells them apart); coordinates times `scale`
/// are metres.
///
/// # Failures
/// As [`MeshDocument::read`].
pub fn read_mesh(path: &Path, scale: f64, max_bytes: u64) -> Result<ObjMesh, MeshFileError> {
    let name = path.display().to_string();
    let bytes = crate::input::read_bytes(path, max_bytes)?;
    match detect(path, &bytes)? {
        MeshFormat::Obj => super::obj::parse_obj(&text(bytes, &name)?, &name, scale),
        _ => Ok(MeshDocument::read(path, scale, max_bytes)?.into_mesh()),
    }
}

/// The format of a file: from its first bytes where they tell (PLY, GLB), else from its
/// extension; a file without one is OBJ.
fn detect(path: &Path, bytes: &[u8]) -> Result<MeshFormat, MeshFileError> {
    match (MeshFormat::sniff(bytes), MeshFormat::of_path(path)) {
        (Some(format), _) | (None, Some(format)) => Ok(format),
        (None, None) if path.extension().is_none() => Ok(MeshFormat::Obj),
        (None, None) => Err(MeshFileError::Unsupported {
            path: path.display().to_string(),
            message: format!("not a file drape reads: {READABLE}"),
        }),
    }
}

/// A file's bytes as text.
fn text(bytes: Vec<u8>, name: &str) -> Result<String, MeshFileError> {
    String::from_utf8(bytes).map_err(|e| {
        crate::input::InputError::NotText {
            path: name.to_string(),
            at: e.utf8_error().valid_up_to(),
        }
        .into()
    })
}

/// One corner of a face: its vertex, texture coordinate and normal (0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Corner {
    /// Vertex.
    pub v: u32,
    /// Texture coordinate, if given (OBJ).
    pub vt: Option<u32>,
    /// Normal, if given (OBJ).
    pub vn: Option<u32>,
}

/// One polygon face as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Face {
    /// Where it is: its 1-based line in an OBJ file, its 1-based number among the file's
    /// faces in the others ([`MeshFormat::place_word`]).
    pub at: usize,
    /// Its corners, in order.
    pub corners: Vec<Corner>,
    /// Its group (an OBJ `g` or `o`, a glTF mesh primitive, a PLY file's one group): an
    /// index into [`MeshDocument::groups`].
    pub group: u32,
}

/// The format's own record of the file, to write it again.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Source {
    /// Every line.
    Obj(ObjText),
    /// The header and every element.
    Ply(PlyKeep),
    /// The JSON and the buffers.
    Gltf(GltfKeep),
}

/// A mesh file: its vertices, faces and groups, and the rest kept to write it back.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshDocument {
    /// The file's name, for messages.
    pub name: String,
    /// The format it was read in.
    pub format: MeshFormat,
    /// Metres per file unit.
    pub scale: f64,
    /// The rotation from the file's axes to the frame [`Self::positions`] are in
    /// (identity unless [`Self::reorient`]ed).
    pub frame: DMat3,
    /// Vertex positions, m, in the file's order (glTF: each position accessor's in turn,
    /// placed by its node).
    pub positions: Vec<DVec3>,
    /// The faces.
    pub faces: Vec<Face>,
    /// Group names in the order met; index 0 is the faces before any OBJ `g` or `o`.
    pub groups: Vec<String>,
    /// Texture coordinates (OBJ `vt` lines; PLY and glTF: vertices that carry one).
    pub texcoords: usize,
    /// Normals (OBJ `vn` lines; PLY and glTF: vertices that carry one).
    pub normals: usize,
    /// Material statements (OBJ `usemtl` and `mtllib`), materials (glTF), 0 (PLY).
    pub materials: usize,
    pub(super) source: Source,
}

impl MeshDocument {
    /// Reads a mesh file of at most `max_bytes`; coordinates times `scale` are metres. The
    /// format comes from the first bytes where they tell (PLY, GLB), else from the
    /// extension; a file without one is read as OBJ.
    ///
    /// # Failures
    /// [`MeshFileError`]: the file cannot be read within bounds, is not in a format drape
    /// reads, or is malformed (named by line, element or accessor).
    pub fn read(path: &Path, scale: f64, max_bytes: u64) -> Result<Self, MeshFileError> {
        let name = path.display().to_string();
        let bytes = crate::input::read_bytes(path, max_bytes)?;
        match detect(path, &bytes)? {
            MeshFormat::Obj => Self::parse_obj(&text(bytes, &name)?, &name, scale),
            MeshFormat::Ply => Self::parse_ply(&bytes, &name, scale),
            MeshFormat::Gltf | MeshFormat::Glb => {
                let base = path.parent().unwrap_or_else(|| Path::new("."));
                Self::parse_gltf(&bytes, &name, scale, base, max_bytes)
            }
        }
    }

    /// The positions and the faces fanned into triangles, with where each triangle is in
    /// the file: what a body needs.
    pub fn into_mesh(self) -> ObjMesh {
        let (triangles, face_of) = self.triangles();
        ObjMesh {
            triangle_lines: face_of.iter().map(|&f| self.faces[f as usize].at).collect(),
            polygons_triangulated: self.faces.iter().filter(|f| f.corners.len() > 3).count(),
            place_word: self.format.place_word(),
            mesh: TriMesh {
                positions: self.positions,
                triangles,
            },
        }
    }

    /// Whether [`Self::write_as`] can write this file in `format`: its own format, or
    /// either glTF form for a glTF file.
    pub fn writes_as(&self, format: MeshFormat) -> bool {
        format == self.format
            || matches!(self.source, Source::Gltf(_)) && matches!(format, MeshFormat::Gltf | MeshFormat::Glb)
    }

    /// The file again in its own format with the vertices `moved` at `positions` (m; the
    /// same count as [`Self::positions`]): see [`Self::write_as`].
    ///
    /// # Failures
    /// As [`Self::write_as`].
    pub fn write(&self, positions: &[DVec3], moved: &[bool]) -> Result<Vec<u8>, MeshFileError> {
        self.write_as(self.format, positions, moved)
    }

    /// The file again, in `format`, with the vertices `moved` at `positions`: their
    /// coordinates written anew (in the file's units, axes and, for glTF, node frame), the
    /// normals they use recomputed from the faces around them (and a glTF position
    /// accessor's bounds), every other value as read.
    ///
    /// # Failures
    /// [`MeshFileError::Unsupported`] when `format` is not one [`Self::writes_as`] allows;
    /// [`MeshFileError::Format`] when the PLY writer fails.
    pub fn write_as(&self, format: MeshFormat, positions: &[DVec3], moved: &[bool]) -> Result<Vec<u8>, MeshFileError> {
        if !self.writes_as(format) {
            return Err(MeshFileError::Unsupported {
                path: self.name.clone(),
                message: format!(
                    "read as {}, written back as {} only (give a .{} file)",
                    self.format.name(),
                    self.format.name(),
                    self.format.extension()
                ),
            });
        }
        match &self.source {
            Source::Obj(text) => Ok(text.write(self, positions, moved).into_bytes()),
            Source::Ply(ply) => ply.write(self, positions, moved),
            Source::Gltf(gltf) => gltf.write(self, format, positions, moved),
        }
    }

    /// A position of [`Self::positions`] in the file's units and axes.
    pub(super) fn to_file(&self, p: DVec3) -> DVec3 {
        self.frame.transpose() * p / self.scale
    }

    /// Turns the positions by `rotation` (from the file's axes into drape's); [`Self::write`]
    /// turns them back.
    pub fn reorient(&mut self, rotation: DMat3) {
        for p in &mut self.positions {
            *p = rotation * *p;
        }
        self.frame = rotation * self.frame;
    }

    /// The faces fanned into triangles (file vertex indices), with the face of each.
    pub fn triangles(&self) -> (Vec<[u32; 3]>, Vec<u32>) {
        let mut triangles = Vec::new();
        let mut face_of = Vec::new();
        for (f, face) in self.faces.iter().enumerate() {
            let c = &face.corners;
            for k in 1..c.len() - 1 {
                triangles.push([c[0].v, c[k].v, c[k + 1].v]);
                face_of.push(f as u32);
            }
        }
        (triangles, face_of)
    }

    /// Per vertex, the area-weighted normal (not unit) of the triangles around it at
    /// `positions`, in drape's frame.
    pub(super) fn area_normals(&self, positions: &[DVec3]) -> Vec<DVec3> {
        let (triangles, _) = self.triangles();
        let mut at = vec![DVec3::ZERO; positions.len()];
        for t in &triangles {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            let n = (b - a).cross(c - a);
            for &i in t {
                at[i as usize] += n;
            }
        }
        at
    }

    /// The unit normal, in the file's axes, of each moved vertex: the area-weighted normals
    /// summed over every vertex at its position (a seam or a texture border written as two
    /// vertices gets one smooth normal). `None` where the faces around have no area.
    pub(super) fn moved_normals(&self, positions: &[DVec3], moved: &[bool]) -> Vec<Option<DVec3>> {
        let at = self.area_normals(positions);
        let key = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
        let mut by_position: BTreeMap<[u64; 3], DVec3> = BTreeMap::new();
        for (p, n) in positions.iter().zip(&at) {
            *by_position.entry(key(*p)).or_default() += *n;
        }
        positions
            .iter()
            .zip(moved)
            .map(|(p, &m)| {
                let n = by_position.get(&key(*p)).copied().unwrap_or_default();
                (m && n.length_squared() > 0.0).then(|| (self.frame.transpose() * n).normalize())
            })
            .collect()
    }

    /// A one-line account of what the file holds.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        write!(
            s,
            "{}: {} vertices, {} faces, {} texture coordinates, {} normals, {} group(s)",
            self.format.name(),
            self.positions.len(),
            self.faces.len(),
            self.texcoords,
            self.normals,
            self.groups.len() - usize::from(self.faces.iter().all(|f| f.group != 0))
        )
        .ok();
        s
    }
}
