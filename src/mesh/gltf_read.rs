//! glTF 2.0 (`.gltf` with its buffers embedded or beside it, or `.glb`) in a
//! [`super::MeshDocument`]: the document read and checked by the `gltf` crate, the JSON kept as
//! read, to be written back with only the moved vertices' bytes, their normals and their
//! accessors' bounds changed.
//!
//! The vertices are the `POSITION` accessors of the triangle primitives of the nodes of
//! the scene, each accessor once, in the order the scene meets them, placed by its node's
//! world transform; each primitive is a group. Every byte range is checked before it is
//! read, so a bad offset, stride or count is an error that names the accessor.

use std::path::Path;

use base64::Engine as _;
use glam::{DMat4, DVec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use serde_json::Value;

use super::MeshFileError;
use super::file_parts::{Corner, Face, FileMesh};

/// The vertices of one position accessor.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Block {
    /// The accessor.
    pub accessor: usize,
    /// Its first vertex in the document's positions.
    pub first: usize,
    /// Its vertices.
    pub count: usize,
    /// The node's world transform (file units).
    pub world: DMat4,
    /// `NORMAL` accessors of the primitives that use it.
    pub normals: Vec<usize>,
}

/// Where an accessor's elements are: buffer, first byte, stride.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Layout {
    pub buffer: usize,
    pub offset: usize,
    pub stride: usize,
}

/// The document and its buffers, to write it again.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfKeep {
    pub(super) json: Value,
    pub(super) buffers: Vec<Vec<u8>>,
    pub(super) blocks: Vec<Block>,
    /// Per accessor, where its elements are (`None`: no buffer view).
    pub(super) layouts: Vec<Option<Layout>>,
}

pub(super) fn error(name: &str, message: impl Into<String>) -> MeshFileError {
    MeshFileError::Format {
        path: name.to_string(),
        format: "glTF",
        message: message.into(),
    }
}

/// One file's reading: the names and what is read so far.
struct Reading<'a> {
    name: &'a str,
    scale: f64,
    buffers: &'a [Vec<u8>],
    layouts: &'a [Option<Layout>],
    contents: FileMesh,
    blocks: Vec<Block>,
}

/// Parses a glTF or GLB file's bytes; `base` is the folder its external buffers are in,
/// each read within `max_bytes`; `name` is used in messages.
///
/// # Failures
/// As [`super::MeshDocument::parse_gltf`].
pub(super) fn parse(
    bytes: &[u8],
    name: &str,
    scale: f64,
    base: &Path,
    max_bytes: u64,
) -> Result<(FileMesh, GltfKeep), MeshFileError> {
    let glb = bytes.starts_with(b"glTF");
    let (json_bytes, blob) = if glb {
        let g = gltf::binary::Glb::from_slice(bytes).map_err(|e| error(name, format!("the GLB container: {e}")))?;
        (g.json.into_owned(), g.bin.map(std::borrow::Cow::into_owned))
    } else {
        (bytes.to_vec(), None)
    };
    let json: Value = serde_json::from_slice(&json_bytes).map_err(|e| error(name, format!("the JSON: {e}")))?;
    let document = gltf::Gltf::from_slice(bytes)
        .map_err(|e| error(name, format!("the document: {e}")))?
        .document;
    let buffers = load_buffers(&document, blob, base, max_bytes, name)?;
    let layouts: Vec<Option<Layout>> = document.accessors().map(|a| layout(&a)).collect();
    let mut reading = Reading {
        name,
        scale,
        buffers: &buffers,
        layouts: &layouts,
        contents: FileMesh {
            groups: vec![String::new()],
            materials: document.materials().count(),
            ..FileMesh::default()
        },
        blocks: Vec::new(),
    };
    for (node, world) in placed_nodes(&document) {
        if let Some(mesh) = node.mesh() {
            reading.mesh(&mesh, world)?;
        }
    }
    if reading.contents.positions.is_empty() || reading.contents.faces.is_empty() {
        return Err(MeshFileError::Empty {
            path: name.into(),
            message: "no triangles in the scene's meshes".into(),
        });
    }
    let Reading {
        mut contents, blocks, ..
    } = reading;
    contents.normals = blocks.iter().filter(|b| !b.normals.is_empty()).map(|b| b.count).sum();
    Ok((
        contents,
        GltfKeep {
            json,
            buffers,
            blocks,
            layouts,
        },
    ))
}

/// Every buffer's bytes: the GLB's BIN chunk, a `data:` URI, or a file beside the document.
fn load_buffers(
    document: &gltf::Document,
    blob: Option<Vec<u8>>,
    base: &Path,
    max_bytes: u64,
    name: &str,
) -> Result<Vec<Vec<u8>>, MeshFileError> {
    let mut blob = blob;
    let mut out = Vec::new();
    for buffer in document.buffers() {
        let k = buffer.index();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob
                .take()
                .ok_or_else(|| error(name, format!("buffer {k} is the GLB's BIN chunk, which is missing")))?,
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                let encoded = uri
                    .split_once(";base64,")
                    .map(|(_, d)| d)
                    .ok_or_else(|| error(name, format!("buffer {k}: a data URI that is not base64")))?;
                base64::engine::general_purpose::STANDARD
                    .decode(encoded)
                    .map_err(|e| error(name, format!("buffer {k}: its base64 data: {e}")))?
            }
            gltf::buffer::Source::Uri(uri) => {
                if uri.contains("://") {
                    return Err(error(
                        name,
                        format!("buffer {k} is at '{uri}': drape reads buffers from files, not the network"),
                    ));
                }
                crate::input::read_bytes(&base.join(percent_decoded(uri)), max_bytes)?
            }
        };
        if data.len() < buffer.length() {
            return Err(error(
                name,
                format!(
                    "buffer {k} holds {} bytes, less than its byteLength {}",
                    data.len(),
                    buffer.length()
                ),
            ));
        }
        out.push(data);
    }
    Ok(out)
}

/// A relative URI's `%XX` escapes decoded.
fn percent_decoded(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        let hex = bytes
            .get(k + 1..k + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[k], hex) {
            (b'%', Some(b)) => {
                out.push(b);
                k += 3;
            }
            (b, _) => {
                out.push(b);
                k += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Where an accessor's elements lie (the view's stride, or the element's size).
fn layout(a: &gltf::Accessor) -> Option<Layout> {
    let view = a.view()?;
    Some(Layout {
        buffer: view.buffer().index(),
        offset: view.offset().checked_add(a.offset())?,
        stride: view.stride().unwrap_or(a.size()),
    })
}

/// The nodes of the default scene (else the first, else every root node), each with its
/// world transform, depth first in file order; a node met twice is placed once.
fn placed_nodes(document: &gltf::Document) -> Vec<(gltf::Node<'_>, DMat4)> {
    let roots: Vec<gltf::Node> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let mut child = vec![false; document.nodes().len()];
            for n in document.nodes() {
                for c in n.children() {
                    child[c.index()] = true;
                }
            }
            document.nodes().filter(|n| !child[n.index()]).collect()
        }
    };
    let mut seen = vec![false; document.nodes().len()];
    let mut out = Vec::new();
    let mut stack: Vec<(gltf::Node, DMat4)> = roots.into_iter().rev().map(|n| (n, DMat4::IDENTITY)).collect();
    while let Some((node, parent)) = stack.pop() {
        if std::mem::replace(&mut seen[node.index()], true) {
            continue;
        }
        let local = node.transform().matrix().map(|c| c.map(f64::from));
        let world = parent * DMat4::from_cols_array_2d(&local);
        let children: Vec<gltf::Node> = node.children().collect();
        for c in children.into_iter().rev() {
            stack.push((c, world));
        }
        out.push((node, world));
    }
    out
}

impl Reading<'_> {
    /// The bytes of element `i` of accessor `a` (`size` of them), checked.
    fn element(&self, a: &gltf::Accessor, i: usize, size: usize) -> Result<&[u8], MeshFileError> {
        let k = a.index();
        let l = self.layouts[k].ok_or_else(|| error(self.name, format!("accessor {k} has no buffer view")))?;
        let start = i.checked_mul(l.stride).and_then(|s| s.checked_add(l.offset));
        start
            .and_then(|s| self.buffers.get(l.buffer)?.get(s..s.checked_add(size)?))
            .ok_or_else(|| {
                error(
                    self.name,
                    format!("accessor {k}: element {i} lies outside buffer {}", l.buffer),
                )
            })
    }

    /// Checks an accessor is of three floats, not sparse.
    fn vec3(&self, a: &gltf::Accessor, what: &str) -> Result<(), MeshFileError> {
        if a.data_type() != DataType::F32
            || a.dimensions() != Dimensions::Vec3
            || a.normalized()
            || a.sparse().is_some()
        {
            return Err(error(
                self.name,
                format!(
                    "accessor {} ({what}) is {:?} {:?}{}: drape reads three floats (quantized or sparse positions are not supported)",
                    a.index(),
                    a.dimensions(),
                    a.data_type(),
                    if a.sparse().is_some() { ", sparse" } else { "" }
                ),
            ));
        }
        Ok(())
    }

    fn read_vec3(&self, a: &gltf::Accessor, i: usize) -> Result<DVec3, MeshFileError> {
        let b = self.element(a, i, 12)?;
        let f = |k: usize| f64::from(f32::from_le_bytes([b[k], b[k + 1], b[k + 2], b[k + 3]]));
        Ok(DVec3::new(f(0), f(4), f(8)))
    }

    /// Reads one mesh placed at `world`: its triangle primitives, each a group.
    fn mesh(&mut self, mesh: &gltf::Mesh, world: DMat4) -> Result<(), MeshFileError> {
        let mesh_name = mesh
            .name()
            .map_or_else(|| format!("mesh {}", mesh.index()), str::to_string);
        let primitives = mesh.primitives().len();
        for primitive in mesh.primitives() {
            let place = format!("{mesh_name}, primitive {}", primitive.index());
            let mode = primitive.mode();
            if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
                return Err(error(
                    self.name,
                    format!("{place} draws {mode:?}: drape needs triangles"),
                ));
            }
            let a = primitive
                .get(&gltf::Semantic::Positions)
                .ok_or_else(|| error(self.name, format!("{place} has no POSITION")))?;
            self.vec3(&a, "POSITION")?;
            let (block, new) = self.block(&a, world, &place)?;
            if new && primitive.get(&gltf::Semantic::TexCoords(0)).is_some() {
                self.contents.texcoords += a.count();
            }
            if let Some(n) = primitive.get(&gltf::Semantic::Normals)
                && n.count() == a.count()
                && self.vec3(&n, "NORMAL").is_ok()
                && (n.count() == 0 || self.element(&n, n.count() - 1, 12).is_ok())
                && !self.blocks[block].normals.contains(&n.index())
            {
                self.blocks[block].normals.push(n.index());
            }
            let indices = self.indices(&primitive, a.count(), &place)?;
            self.contents
                .groups
                .push(if primitives > 1 { place } else { mesh_name.clone() });
            let group = (self.contents.groups.len() - 1) as u32;
            let first = self.blocks[block].first as u32;
            let triangles = triangles(mode, &indices);
            for t in triangles {
                let at = self.contents.faces.len() + 1;
                let corners = t
                    .map(|v| Corner {
                        v: first + v,
                        vt: None,
                        vn: None,
                    })
                    .to_vec();
                self.contents.faces.push(Face { at, corners, group });
            }
        }
        Ok(())
    }

    /// The block of position accessor `a`, read now if it is new (then `true`).
    fn block(&mut self, a: &gltf::Accessor, world: DMat4, place: &str) -> Result<(usize, bool), MeshFileError> {
        if let Some(k) = self.blocks.iter().position(|b| b.accessor == a.index()) {
            if self.blocks[k].world != world {
                return Err(error(
                    self.name,
                    format!(
                        "{place}: its positions (accessor {}) are placed by two nodes at different places: drape needs each vertex once",
                        a.index()
                    ),
                ));
            }
            return Ok((k, false));
        }
        let first = self.contents.positions.len();
        for i in 0..a.count() {
            let local = self.read_vec3(a, i)?;
            let p = world.transform_point3(local) * self.scale;
            if !p.is_finite() {
                return Err(error(
                    self.name,
                    format!("{place}: vertex {i} of accessor {} is not finite: {local}", a.index()),
                ));
            }
            self.contents.positions.push(p);
        }
        self.blocks.push(Block {
            accessor: a.index(),
            first,
            count: a.count(),
            world,
            normals: Vec::new(),
        });
        Ok((self.blocks.len() - 1, true))
    }

    /// A primitive's vertex indices (or 0..count without an index accessor), checked
    /// against its `count` vertices.
    fn indices(&self, primitive: &gltf::Primitive, count: usize, place: &str) -> Result<Vec<u32>, MeshFileError> {
        let Some(a) = primitive.indices() else {
            return Ok((0..count as u32).collect());
        };
        let size = match a.data_type() {
            DataType::U8 => 1,
            DataType::U16 => 2,
            DataType::U32 => 4,
            other => return Err(error(self.name, format!("{place}: indices of type {other:?}"))),
        };
        if a.dimensions() != Dimensions::Scalar || a.sparse().is_some() {
            return Err(error(self.name, format!("{place}: indices that are not plain scalars")));
        }
        let mut out = Vec::with_capacity(a.count().min(self.buffers.iter().map(Vec::len).sum()));
        for i in 0..a.count() {
            let b = self.element(&a, i, size)?;
            let v = match size {
                1 => u32::from(b[0]),
                2 => u32::from(u16::from_le_bytes([b[0], b[1]])),
                _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            };
            if v as usize >= count {
                return Err(error(
                    self.name,
                    format!(
                        "{place}: index {i} (accessor {}) is {v}, out of range: {count} vertices",
                        a.index()
                    ),
                ));
            }
            out.push(v);
        }
        Ok(out)
    }
}

/// The triangles of a primitive's indices drawn in `mode` (a strip's every other triangle
/// turned to keep the winding).
fn triangles(mode: Mode, v: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (0..v.len().saturating_sub(2))
            .map(|k| {
                if k % 2 == 0 {
                    [v[k], v[k + 1], v[k + 2]]
                } else {
                    [v[k + 1], v[k], v[k + 2]]
                }
            })
            .collect(),
        Mode::TriangleFan => (1..v.len().saturating_sub(1)).map(|k| [v[0], v[k], v[k + 1]]).collect(),
        _ => v.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}
