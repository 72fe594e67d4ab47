//! What every mesh file reader gives and every writer takes: the formats, the faces as
//! written, the vertices and faces of a file, and the moved vertices to write back.

use std::path::Path;

use glam::DVec3;

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

/// What a mesh file holds: vertices in the file's order, faces, groups, and how many
/// texture coordinates, normals and materials came with them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FileMesh {
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
}

/// The vertices to write back, in the file's units and axes.
pub(super) struct Moved<'a> {
    /// The file's name, for messages.
    pub name: &'a str,
    /// Every vertex's position.
    pub positions: &'a [DVec3],
    /// Which moved.
    pub moved: &'a [bool],
    /// The faces.
    pub faces: &'a [Face],
    /// Per vertex, the area-weighted normal (not unit) of the triangles around it; empty
    /// when the file has no normals or nothing moved.
    pub area: &'a [DVec3],
    /// Per vertex, for a moved one, the unit normal summed over every vertex at its
    /// position (a seam or a texture border written as two vertices gets one normal);
    /// `None` for every vertex of an OBJ file, whose writer makes its shared `vn` lines
    /// from [`Self::area`], or of a file without normals.
    pub smooth: &'a [Option<DVec3>],
}
