//! OBJ in a [`super::MeshDocument`]: every line kept, to write back with only some vertices moved.
//!
//! [`ObjText::write`] gives the same text with the `v` lines of the moved vertices (and the
//! `vn` lines they use) written anew, every other line byte for byte as read, so an unmoved
//! vertex keeps its exact coordinates.

use std::collections::BTreeMap;

use glam::DVec3;

use super::MeshFileError;
use super::file_parts::{Corner, Face, FileMesh, Moved};
use super::obj::{require_both, tokens_with_columns, vertex};

/// What an OBJ file needs kept to be written again.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjText {
    /// Every line as read, without its end.
    lines: Vec<String>,
    /// `\r\n` when the file's first line ends so, else `\n`.
    line_end: &'static str,
    /// Whether the last line ended with a line end.
    ends_with_newline: bool,
    /// The line (0-based) of each `v`.
    vertex_lines: Vec<usize>,
    /// The line (0-based) of each `vn`.
    normal_lines: Vec<usize>,
}

/// Parses OBJ text; `name` is used in messages: the vertices and faces, and every line.
///
/// # Failures
/// As [`super::read_obj`], and texture-coordinate or normal indices out of range.
pub(super) fn parse(text: &str, name: &str, scale: f64) -> Result<(FileMesh, ObjText), MeshFileError> {
    let syntax = |line: usize, column: usize, message: String| MeshFileError::Syntax {
        path: name.to_string(),
        line,
        column,
        message,
    };
    let mut keep = ObjText {
        lines: Vec::new(),
        line_end: if text.find('\n').is_some_and(|k| text[..k].ends_with('\r')) {
            "\r\n"
        } else {
            "\n"
        },
        ends_with_newline: text.ends_with('\n'),
        vertex_lines: Vec::new(),
        normal_lines: Vec::new(),
    };
    let mut parts = FileMesh {
        groups: vec![String::new()],
        ..FileMesh::default()
    };
    let mut group = 0u32;
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let raw = raw.strip_suffix('\r').unwrap_or(raw);
        keep.lines.push(raw.to_string());
        let content = raw.split('#').next().unwrap_or("");
        let mut tokens = tokens_with_columns(content);
        let Some((_, keyword)) = tokens.next() else {
            continue;
        };
        match keyword {
            "v" => {
                parts.positions.push(vertex(tokens, line, scale, &syntax)?);
                keep.vertex_lines.push(k);
            }
            "vt" => parts.texcoords += 1,
            "vn" => keep.normal_lines.push(k),
            "g" | "o" => {
                let label: Vec<&str> = tokens.map(|(_, t)| t).collect();
                let label = label.join(" ");
                group = match parts.groups.iter().position(|g| *g == label) {
                    Some(i) => i as u32,
                    None => {
                        parts.groups.push(label);
                        (parts.groups.len() - 1) as u32
                    }
                };
            }
            "usemtl" | "mtllib" => parts.materials += 1,
            "f" => {
                let read = [parts.positions.len(), parts.texcoords, keep.normal_lines.len()];
                let mut corners = Vec::new();
                for (column, token) in tokens {
                    corners.push(corner(token, (line, column), read, &syntax)?);
                }
                if corners.len() < 3 {
                    return Err(syntax(
                        line,
                        content.trim_end().len() + 1,
                        format!("a face needs at least 3 vertices, found {}", corners.len()),
                    ));
                }
                parts.faces.push(Face {
                    at: line,
                    corners,
                    group,
                });
            }
            _ => {}
        }
    }
    require_both(name, parts.positions.len(), parts.faces.len())?;
    parts.normals = keep.normal_lines.len();
    Ok((parts, keep))
}

impl ObjText {
    /// The file again with the vertices `job.moved` at `job.positions`: their `v` lines
    /// written anew (any values after the three coordinates, such as colours, kept), the
    /// `vn` lines their corners use recomputed from the faces around them, every other
    /// line as read.
    pub(super) fn write(&self, job: &Moved) -> String {
        let mut replaced: BTreeMap<usize, String> = BTreeMap::new();
        for (v, (&line, q)) in self.vertex_lines.iter().zip(job.positions).enumerate() {
            if !job.moved.get(v).copied().unwrap_or(false) {
                continue;
            }
            let rest: Vec<&str> = self.lines[line]
                .split('#')
                .next()
                .unwrap_or("")
                .split_ascii_whitespace()
                .skip(4)
                .collect();
            let mut text = format!("v {} {} {}", q.x, q.y, q.z);
            for r in rest {
                text.push(' ');
                text.push_str(r);
            }
            replaced.insert(line, text);
        }
        for (n, normal) in normals_of_moved(job) {
            replaced.insert(
                self.normal_lines[n as usize],
                format!("vn {} {} {}", normal.x, normal.y, normal.z),
            );
        }
        let mut out = String::with_capacity(self.lines.iter().map(|l| l.len() + 2).sum());
        for (k, line) in self.lines.iter().enumerate() {
            if k > 0 {
                out.push_str(self.line_end);
            }
            out.push_str(replaced.get(&k).map_or(line.as_str(), String::as_str));
        }
        if self.ends_with_newline {
            out.push_str(self.line_end);
        }
        out
    }
}

/// The normals (by `vn` index) that corners of moved vertices use: each the unit sum of the
/// area-weighted normals at the vertices whose corners use it.
fn normals_of_moved(job: &Moved) -> BTreeMap<u32, DVec3> {
    let mut used: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for face in job.faces {
        for c in &face.corners {
            if let Some(n) = c.vn
                && job.moved.get(c.v as usize).copied().unwrap_or(false)
            {
                used.entry(n).or_default().push(c.v);
            }
        }
    }
    used.into_iter()
        .filter_map(|(n, mut vertices)| {
            vertices.sort_unstable();
            vertices.dedup();
            let sum: DVec3 = vertices.iter().map(|&v| job.area[v as usize]).sum();
            (sum.length_squared() > 0.0).then(|| (n, sum.normalize()))
        })
        .collect()
}

/// One corner token `v`, `v/vt`, `v//vn` or `v/vt/vn` (negative indices count back from the
/// elements read so far: `read` vertices, texture coordinates and normals), checked
/// against them.
fn corner(
    token: &str,
    (line, column): (usize, usize),
    read: [usize; 3],
    syntax: &dyn Fn(usize, usize, String) -> MeshFileError,
) -> Result<Corner, MeshFileError> {
    let mut parts = token.split('/');
    let index = |text: Option<&str>, read: usize, what: &str| -> Result<Option<u32>, MeshFileError> {
        let Some(text) = text.filter(|t| !t.is_empty()) else {
            return Ok(None);
        };
        let i: i64 = text
            .parse()
            .map_err(|_| syntax(line, column, format!("'{token}' is not a vertex index")))?;
        if i == 0 {
            return Err(syntax(
                line,
                column,
                format!("{what} index 0 is invalid (OBJ indices start at 1)"),
            ));
        }
        let resolved = if i < 0 { read as i64 + i + 1 } else { i };
        if resolved < 1 || resolved as usize > read {
            return Err(syntax(
                line,
                column,
                format!("{what} index {i} is out of range: {read} read so far"),
            ));
        }
        Ok(Some((resolved - 1) as u32))
    };
    let v = index(parts.next(), read[0], "vertex")?
        .ok_or_else(|| syntax(line, column, format!("'{token}' is not a vertex index")))?;
    let vt = index(parts.next(), read[1], "texture coordinate")?;
    let vn = index(parts.next(), read[2], "normal")?;
    Ok(Corner { v, vt, vn })
}
