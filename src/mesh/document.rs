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

use super::file_parts::Moved;
pub use super::file_parts::{Corner, Face, FileMesh, MeshFormat, READABLE};
use super::gltf_read::GltfKeep;
use super::obj::ObjMesh;
use super::obj_doc::ObjText;
use super::ply_doc::PlyKeep;
use super::{MeshFileError, TriMesh, gltf_read, gltf_write, obj_doc, ply_doc};

/// The unit normal of each moved vertex: the area-weighted normals `area` summed over every
/// vertex at its position (a seam or a texture border written as two vertices gets one
/// smooth normal). `None` for an unmoved vertex or where the faces around have no area.
fn smooth_normals(positions: &[DVec3], area: &[DVec3], moved: &[bool]) -> Vec<Option<DVec3>> {
    let key = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    let mut by_position: BTreeMap<[u64; 3], DVec3> = BTreeMap::new();
    for (p, n) in positions.iter().zip(area) {
        *by_position.entry(key(*p)).or_default() += *n;
    }
    positions
        .iter()
        .zip(moved)
        .map(|(p, &m)| {
            let n = by_position.get(&key(*p)).copied().unwrap_or_default();
            (m && n.length_squared() > 0.0).then(|| n.normalize())
        })
        .collect()
}

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
    /// What it holds: vertices, faces, groups.
    pub contents: FileMesh,
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

    /// Parses OBJ text; `name` is used in messages.
    ///
    /// # Failures
    /// As [`super::read_obj`], and texture-coordinate or normal indices out of range.
    pub fn parse_obj(text: &str, name: &str, scale: f64) -> Result<Self, MeshFileError> {
        let (parts, keep) = obj_doc::parse(text, name, scale)?;
        Ok(Self::from_parts(name, MeshFormat::Obj, scale, parts, Source::Obj(keep)))
    }

    /// Parses a PLY file's bytes; `name` is used in messages.
    ///
    /// # Failures
    /// [`MeshFileError`]: a malformed header or payload, no `vertex` element with float or
    /// double `x y z`, no `face` element with a list of vertex indices, a coordinate that is
    /// not finite (named by vertex), an index out of range or a face of fewer than 3
    /// vertices (named by face), or no vertices or faces.
    pub fn parse_ply(bytes: &[u8], name: &str, scale: f64) -> Result<Self, MeshFileError> {
        let (parts, keep) = ply_doc::parse(bytes, name, scale)?;
        Ok(Self::from_parts(name, MeshFormat::Ply, scale, parts, Source::Ply(keep)))
    }

    /// Parses a glTF or GLB file's bytes; `base` is the folder its external buffers are
    /// in, each read within `max_bytes`; `name` is used in messages.
    ///
    /// # Failures
    /// [`MeshFileError`]: an invalid document, a buffer that cannot be had, a primitive
    /// that is not triangles, a position accessor that is not three floats or is placed by
    /// two different nodes, a byte range outside its buffer, an index out of range, no
    /// triangles.
    pub fn parse_gltf(
        bytes: &[u8],
        name: &str,
        scale: f64,
        base: &Path,
        max_bytes: u64,
    ) -> Result<Self, MeshFileError> {
        let (parts, keep) = gltf_read::parse(bytes, name, scale, base, max_bytes)?;
        let format = if bytes.starts_with(b"glTF") {
            MeshFormat::Glb
        } else {
            MeshFormat::Gltf
        };
        Ok(Self::from_parts(name, format, scale, parts, Source::Gltf(keep)))
    }

    fn from_parts(name: &str, format: MeshFormat, scale: f64, parts: FileMesh, source: Source) -> Self {
        Self {
            name: name.to_string(),
            format,
            scale,
            frame: DMat3::IDENTITY,
            contents: parts,
            source,
        }
    }

    /// The positions and the faces fanned into triangles, with where each triangle is in
    /// the file: what a body needs.
    pub fn into_mesh(self) -> ObjMesh {
        let (triangles, face_of) = self.triangles();
        ObjMesh {
            triangle_lines: face_of.iter().map(|&f| self.contents.faces[f as usize].at).collect(),
            polygons_triangulated: self.contents.faces.iter().filter(|f| f.corners.len() > 3).count(),
            place_word: self.format.place_word(),
            mesh: TriMesh {
                positions: self.contents.positions,
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
        // One position and one flag per vertex of the file: a vertex past the end of
        // `positions` or `moved` stays where it was read.
        let moved: Vec<bool> = (0..self.contents.positions.len())
            .map(|v| moved.get(v).copied().unwrap_or(false) && v < positions.len())
            .collect();
        let file: Vec<DVec3> = (0..self.contents.positions.len())
            .map(|v| {
                let p = if moved[v] {
                    positions[v]
                } else {
                    self.contents.positions[v]
                };
                self.frame.transpose() * p / self.scale
            })
            .collect();
        // Normals are made again only for a file that has them; one smooth normal per
        // position for the formats that store a normal per vertex (OBJ's `vn` lines are
        // shared by corners instead: see its writer).
        let has_normals = self.contents.normals > 0 && moved.iter().any(|&m| m);
        let area = if has_normals {
            self.area_normals(&file)
        } else {
            Vec::new()
        };
        let smooth = match self.source {
            Source::Ply(_) | Source::Gltf(_) if has_normals => smooth_normals(&file, &area, &moved),
            _ => vec![None; file.len()],
        };
        let job = Moved {
            name: &self.name,
            positions: &file,
            moved: &moved,
            faces: &self.contents.faces,
            area: &area,
            smooth: &smooth,
        };
        match &self.source {
            Source::Obj(text) => Ok(text.write(&job).into_bytes()),
            Source::Ply(ply) => ply.write(&job),
            Source::Gltf(gltf) => gltf_write::write(gltf, format, &job),
        }
    }

    /// Turns the positions by `rotation` (from the file's axes into drape's); [`Self::write`]
    /// turns them back.
    pub fn reorient(&mut self, rotation: DMat3) {
        for p in &mut self.contents.positions {
            *p = rotation * *p;
        }
        self.frame = rotation * self.frame;
    }

    /// The faces fanned into triangles (file vertex indices), with the face of each.
    pub fn triangles(&self) -> (Vec<[u32; 3]>, Vec<u32>) {
        let mut triangles = Vec::new();
        let mut face_of = Vec::new();
        for (f, face) in self.contents.faces.iter().enumerate() {
            let c = &face.corners;
            for k in 1..c.len() - 1 {
                triangles.push([c[0].v, c[k].v, c[k + 1].v]);
                face_of.push(f as u32);
            }
        }
        (triangles, face_of)
    }

    /// Per vertex, the area-weighted normal (not unit) of the triangles around it at
    /// `positions`.
    fn area_normals(&self, positions: &[DVec3]) -> Vec<DVec3> {
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

    /// A one-line account of what the file holds.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        write!(
            s,
            "{}: {} vertices, {} faces, {} texture coordinates, {} normals, {} group(s)",
            self.format.name(),
            self.contents.positions.len(),
            self.contents.faces.len(),
            self.contents.texcoords,
            self.contents.normals,
            self.contents.groups.len() - usize::from(self.contents.faces.iter().all(|f| f.group != 0))
        )
        .ok();
        s
    }
}
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unchanged_document_writes_back_byte_for_byte() {
        let text = "# made elsewhere\r\nmtllib a.mtl\r\nv 0 0 0 1 0 0\r\nv 1.0000001 0 0\r\nv 0 1 0\r\nvt 0 0\r\nvn 0 0 1\r\ng front\r\nusemtl cotton\r\nf 1/1/1 2/1/1 3/1/1\r\n";
        let doc = MeshDocument::parse_obj(text, "a.obj", 1.0).unwrap();
        assert_eq!(
            doc.write(&doc.contents.positions, &[false; 3]).unwrap(),
            text.as_bytes()
        );
        assert_eq!(doc.contents.groups, vec!["".to_string(), "front".to_string()]);
        assert_eq!(doc.contents.faces[0].group, 1);
    }

    #[test]
    fn a_moved_vertex_keeps_its_colour_and_the_normal_it_uses_is_recomputed() {
        let text = "v 0 0 0 0.5 0.5 0.5\nv 1 0 0\nv 0 1 0\nvn 1 0 0\nf 1//1 2//1 3//1\n";
        let doc = MeshDocument::parse_obj(text, "a.obj", 0.01).unwrap();
        let mut p = doc.contents.positions.clone();
        p[0].z = -0.01;
        let out = String::from_utf8(doc.write(&p, &[true, false, false]).unwrap()).unwrap();
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "v 0 0 -1 0.5 0.5 0.5");
        assert_eq!(lines[1], "v 1 0 0");
        assert!(lines[3].starts_with("vn "), "{}", lines[3]);
        assert_ne!(lines[3], "vn 1 0 0");
    }
}
