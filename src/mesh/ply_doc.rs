//! PLY in a [`super::MeshDocument`], read and written by `ply-rs-bw` in the file's own encoding
//! (text, binary little or big endian) with every element and property kept.
//!
//! The vertices are the `vertex` element's `x y z` (float or double); the faces its
//! `face` element's `vertex_indices` (or `vertex_index`) lists. Before the payload is
//! handed to the parser, its element counts and list lengths are walked against the
//! bytes there are, so a header or a list length that promises more than the file holds
//! is an error that names it, not an allocation the size of the promise.

use std::io::Cursor;

use glam::DVec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{ElementDef, Encoding, Header, Ply, Property, PropertyAccess as _, PropertyType, ScalarType};
use ply_rs_bw::writer::Writer;

use super::MeshFileError;
use super::file_parts::{Corner, Face, FileMesh, Moved};
use super::ply_row::{Row, name_hash};

/// The parsed file, to write it again.
#[derive(Clone, Debug, PartialEq)]
pub struct PlyKeep {
    ply: Ply<Row>,
}

/// The coordinate and normal property names of a vertex.
const XYZ: [&str; 3] = ["x", "y", "z"];
const NORMAL: [&str; 3] = ["nx", "ny", "nz"];

fn error(name: &str, message: impl Into<String>) -> MeshFileError {
    MeshFileError::Format {
        path: name.to_string(),
        format: "PLY",
        message: message.into(),
    }
}

/// Parses a PLY file's bytes; `name` is used in messages.
///
/// # Failures
/// [`MeshFileError`]: a malformed header or payload, no `vertex` element with float or
/// double `x y z`, no `face` element with a list of vertex indices, a coordinate that is
/// not finite (named by vertex), an index out of range or a face of fewer than 3
/// vertices (named by face), or no vertices or faces.
pub(super) fn parse(bytes: &[u8], name: &str, scale: f64) -> Result<(FileMesh, PlyKeep), MeshFileError> {
    let parser = Parser::<Row>::new();
    let mut reader = Cursor::new(bytes);
    let header = parser
        .read_header(&mut reader)
        .map_err(|e| error(name, format!("the header: {e}")))?;
    let (vertex_def, indices) = check_header(&header, name)?;
    let start = reader.position() as usize;
    check_payload(&header, &bytes[start.min(bytes.len())..], name)?;
    let payload = parser
        .read_payload(&mut reader, &header)
        .map_err(|e| error(name, format!("the payload: {e}")))?;
    let ply = Ply { header, payload };
    let vertices = ply.payload.get("vertex").map_or(&[][..], Vec::as_slice);
    let mut positions = Vec::with_capacity(vertices.len());
    for (v, element) in vertices.iter().enumerate() {
        let [x, y, z] = XYZ.map(|k| element.get(k).and_then(number).unwrap_or(f64::NAN));
        let p = DVec3::new(x, y, z) * scale;
        if !p.is_finite() {
            return Err(error(
                name,
                format!("vertex {} has a coordinate that is not finite: {x} {y} {z}", v + 1),
            ));
        }
        positions.push(p);
    }
    let faces = read_faces(&ply, &indices, positions.len(), name)?;
    if positions.is_empty() || faces.is_empty() {
        return Err(MeshFileError::Empty {
            path: name.into(),
            message: format!("{} vertices and {} faces", positions.len(), faces.len()),
        });
    }
    let has = |keys: &[&str]| keys.iter().all(|k| vertex_def.properties.contains_key(*k));
    let uv = has(&["s", "t"]) || has(&["u", "v"]) || has(&["texture_u", "texture_v"]);
    let parts = FileMesh {
        texcoords: if uv { positions.len() } else { 0 },
        normals: if has(&NORMAL) { positions.len() } else { 0 },
        positions,
        faces,
        groups: vec![String::new()],
        materials: 0,
    };
    Ok((parts, PlyKeep { ply }))
}

/// The vertex element and the name of the face element's index list, checked: `x y z`
/// float or double, the list of an integer type, no element without properties.
fn check_header(header: &Header, name: &str) -> Result<(ElementDef, String), MeshFileError> {
    if let Some(empty) = header
        .elements
        .values()
        .find(|e| e.properties.is_empty() && e.count > 0)
    {
        return Err(error(name, format!("element '{}' has no properties", empty.name)));
    }
    for e in header.elements.values() {
        let mut hashes: Vec<u64> = e.properties.keys().map(|k| name_hash(k)).collect();
        hashes.sort_unstable();
        if hashes.windows(2).any(|w| w[0] == w[1]) {
            return Err(error(name, format!("element '{}' names a property twice", e.name)));
        }
    }
    let vertex = header
        .elements
        .get("vertex")
        .ok_or_else(|| error(name, "no 'vertex' element"))?;
    for k in XYZ {
        match vertex.properties.get(k).map(|p| &p.data_type) {
            Some(PropertyType::Scalar(ScalarType::Float | ScalarType::Double)) => {}
            Some(other) => {
                return Err(error(
                    name,
                    format!("vertex property '{k}' is {other:?}: drape reads float or double coordinates"),
                ));
            }
            None => return Err(error(name, format!("the 'vertex' element has no '{k}'"))),
        }
    }
    let face = header.elements.get("face").ok_or_else(|| {
        error(
            name,
            "no 'face' element (a point cloud or a triangle-strip file): drape needs faces",
        )
    })?;
    let indices = ["vertex_indices", "vertex_index"]
        .into_iter()
        .find(|k| face.properties.contains_key(*k))
        .ok_or_else(|| error(name, "the 'face' element has no 'vertex_indices' list"))?;
    match &face.properties[indices].data_type {
        PropertyType::List(_, ScalarType::Float | ScalarType::Double) | PropertyType::Scalar(_) => Err(error(
            name,
            format!("face property '{indices}' is not a list of integers"),
        )),
        PropertyType::List(..) => Ok((vertex.clone(), indices.to_string())),
    }
}

/// Bytes of a scalar in a binary file.
fn size_of(t: &ScalarType) -> usize {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// Walks the payload's elements and lists against its bytes without keeping anything, so
/// that no count the parser will allocate for exceeds what the file holds.
fn check_payload(header: &Header, payload: &[u8], name: &str) -> Result<(), MeshFileError> {
    let short = |e: &ElementDef, k: usize, what: &str| {
        error(
            name,
            format!(
                "element '{}' declares {} items, but the file ends in item {} ({what})",
                e.name,
                e.count,
                k + 1
            ),
        )
    };
    if header.encoding == Encoding::Ascii {
        let mut lines = payload.split(|&b| b == b'\n');
        for e in header.elements.values() {
            for k in 0..e.count {
                let line = lines.next().ok_or_else(|| short(e, k, "no line"))?;
                if e.properties
                    .values()
                    .any(|p| matches!(p.data_type, PropertyType::List(..)))
                {
                    check_ascii_lists(line, e, k, name)?;
                }
            }
        }
        return Ok(());
    }
    let big = header.encoding == Encoding::BinaryBigEndian;
    let mut at = 0usize;
    for e in header.elements.values() {
        let fixed: usize = e
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(t) => size_of(t),
                PropertyType::List(count, _) => size_of(count),
            })
            .sum();
        if e.count.saturating_mul(fixed) > payload.len() - at {
            return Err(short(e, (payload.len() - at) / fixed.max(1), "too few bytes"));
        }
        for k in 0..e.count {
            for p in e.properties.values() {
                let (count_type, item) = match &p.data_type {
                    PropertyType::Scalar(t) => {
                        at += size_of(t);
                        continue;
                    }
                    PropertyType::List(c, t) => (c, size_of(t)),
                };
                let n = size_of(count_type);
                let raw = payload.get(at..at + n).ok_or_else(|| short(e, k, "too few bytes"))?;
                let count = list_count(raw, big);
                at += n;
                if count.saturating_mul(item as u64) > (payload.len() - at) as u64 {
                    return Err(error(
                        name,
                        format!(
                            "element '{}' item {}: a list of {count} values, more than the file holds",
                            e.name,
                            k + 1
                        ),
                    ));
                }
                at += count as usize * item;
            }
            if at > payload.len() {
                return Err(short(e, k, "too few bytes"));
            }
        }
    }
    Ok(())
}

/// A binary list's length (an integer of 1, 2 or 4 bytes; negative read as 0, which the
/// parser then refuses).
fn list_count(raw: &[u8], big: bool) -> u64 {
    let mut b = [0u8; 4];
    let n = raw.len();
    if big {
        b[4 - n..].copy_from_slice(raw);
        u32::from_be_bytes(b) as u64
    } else {
        b[..n].copy_from_slice(raw);
        u32::from_le_bytes(b) as u64
    }
}

/// Checks that each list on an ASCII line (its length cannot exceed the values on it) is no longer than the values after its count.
fn check_ascii_lists(line: &[u8], e: &ElementDef, k: usize, name: &str) -> Result<(), MeshFileError> {
    let tokens: Vec<&[u8]> = line
        .split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
        .collect();
    let mut at = 0usize;
    for p in e.properties.values() {
        match p.data_type {
            PropertyType::Scalar(_) => at += 1,
            PropertyType::List(..) => {
                let count: u64 = tokens
                    .get(at)
                    .and_then(|t| std::str::from_utf8(t).ok())
                    .and_then(|t| t.trim().parse().ok())
                    .unwrap_or(0);
                at += 1;
                if count > (tokens.len().saturating_sub(at)) as u64 {
                    return Err(error(
                        name,
                        format!(
                            "element '{}' item {}: a list of {count} values on a line of {} values",
                            e.name,
                            k + 1,
                            tokens.len()
                        ),
                    ));
                }
                at += count as usize;
            }
        }
    }
    Ok(())
}

/// A scalar property as a number.
fn number(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        Property::Float(v) => v.into(),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// A list property as indices (`None` for a negative or non-integer value).
fn indices(p: &Property) -> Option<Vec<i64>> {
    fn all<T: Copy + Into<i64>>(v: &[T]) -> Vec<i64> {
        v.iter().map(|&x| x.into()).collect()
    }
    Some(match p {
        Property::ListChar(v) => all(v),
        Property::ListUChar(v) => all(v),
        Property::ListShort(v) => all(v),
        Property::ListUShort(v) => all(v),
        Property::ListInt(v) => all(v),
        Property::ListUInt(v) => all(v),
        _ => return None,
    })
}

/// The faces, each checked: at least 3 vertices, every index in range.
fn read_faces(ply: &Ply<Row>, key: &str, vertices: usize, name: &str) -> Result<Vec<Face>, MeshFileError> {
    let elements = ply.payload.get("face").map_or(&[][..], Vec::as_slice);
    let mut faces = Vec::with_capacity(elements.len());
    for (f, element) in elements.iter().enumerate() {
        let at = f + 1;
        let list = element
            .get(key)
            .and_then(indices)
            .ok_or_else(|| error(name, format!("face {at}: '{key}' is not a list of integers")))?;
        if list.len() < 3 {
            return Err(error(
                name,
                format!("face {at}: a face needs at least 3 vertices, found {}", list.len()),
            ));
        }
        let mut corners = Vec::with_capacity(list.len());
        for &i in &list {
            if i < 0 || i as usize >= vertices {
                return Err(error(
                    name,
                    format!(
                        "face {at}: vertex index {i} is out of range: {vertices} vertices (PLY indices start at 0)"
                    ),
                ));
            }
            corners.push(Corner {
                v: i as u32,
                vt: None,
                vn: None,
            });
        }
        faces.push(Face { at, corners, group: 0 });
    }
    Ok(faces)
}

/// A value of the declared type of property `key` of `def`, from `x`.
fn typed(def: &ElementDef, key: &str, x: f64) -> Option<Property> {
    match def.properties.get(key)?.data_type {
        PropertyType::Scalar(ScalarType::Float) => Some(Property::Float(x as f32)),
        PropertyType::Scalar(ScalarType::Double) => Some(Property::Double(x)),
        _ => None,
    }
}

impl PlyKeep {
    /// The file again, in its encoding, with the vertices `job.moved` at `job.positions`
    /// (`x y z` in the declared type) and their `nx ny nz`, where the file has them, made
    /// again; every other element and property as read.
    pub(super) fn write(&self, job: &Moved) -> Result<Vec<u8>, MeshFileError> {
        let fail = |e: std::io::Error| error(job.name, format!("writing: {e}"));
        let writer = Writer::<Row>::new();
        let header = &self.ply.header;
        let mut out = Vec::new();
        writer.write_header(&mut out, header).map_err(fail)?;
        for (key, def) in &header.elements {
            let rows = self.ply.payload.get(key).map_or(&[][..], Vec::as_slice);
            for (v, row) in rows.iter().enumerate() {
                let moved = key == "vertex" && job.moved.get(v).copied().unwrap_or(false);
                let changed = moved.then(|| {
                    let mut row = row.clone();
                    let normal = job.smooth[v].map(|n| n.to_array());
                    let values = XYZ.into_iter().zip(job.positions[v].to_array());
                    let normals = normal.into_iter().flat_map(|n| NORMAL.into_iter().zip(n));
                    for (k, x) in values.chain(normals) {
                        if let Some(p) = typed(def, k, x) {
                            row.set_property(k, p);
                        }
                    }
                    row
                });
                let row = changed.as_ref().unwrap_or(row);
                match header.encoding {
                    Encoding::Ascii => writer.write_ascii_element(&mut out, row, def),
                    Encoding::BinaryBigEndian => writer.write_big_endian_element(&mut out, row, def),
                    Encoding::BinaryLittleEndian => writer.write_little_endian_element(&mut out, row, def),
                }
                .map_err(fail)?;
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_header_that_promises_more_than_the_file_holds_is_named() {
        let text = b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
        let err = parse(text, "a.ply", 1.0).unwrap_err().to_string();
        assert!(err.contains("element 'vertex' declares 1000000000 items"), "{err}");
    }

    #[test]
    fn a_list_longer_than_the_file_is_named() {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list int int vertex_indices\nend_header\n".to_vec();
        bytes.extend(std::iter::repeat_n(0u8, 36));
        bytes.extend(2_000_000_000i32.to_le_bytes());
        let err = parse(&bytes, "a.ply", 1.0).unwrap_err().to_string();
        assert!(err.contains("a list of 2000000000 values"), "{err}");
    }
}
