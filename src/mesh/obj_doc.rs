//! A whole OBJ file kept as written, to be written back with only some vertices moved.
//!
//! [`super::read_obj`] reads what drape needs of a body (positions and triangles). A garment
//! from another tool comes with texture coordinates, normals, groups, materials, smoothing
//! groups and comments that the tool it goes back to needs, and in an order it expects.
//! [`ObjDocument`] keeps every line; [`ObjDocument::write`] gives the same text with the
//! `v` lines of the moved vertices (and the `vn` lines they use) written anew, every other
//! line byte for byte as read, so an unmoved vertex keeps its exact coordinates.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use glam::{DMat3, DVec3};

use super::obj::{ObjError, tokens_with_columns, vertex};

/// One corner of a face: its vertex, texture coordinate and normal (0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Corner {
    /// Vertex.
    pub v: u32,
    /// Texture coordinate, if given.
    pub vt: Option<u32>,
    /// Normal, if given.
    pub vn: Option<u32>,
}

/// One polygon face as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjFace {
    /// 1-based line.
    pub line: usize,
    /// Its corners, in order.
    pub corners: Vec<Corner>,
    /// The group (`g` or `o`) it is in: an index into [`ObjDocument::groups`].
    pub group: u32,
}

/// An OBJ file: its lines and what they hold.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjDocument {
    /// The file's name, for messages.
    pub name: String,
    /// Every line as read, without its end.
    pub lines: Vec<String>,
    /// `\r\n` when the file's first line ends so, else `\n`.
    pub line_end: &'static str,
    /// Whether the last line ended with a line end.
    pub ends_with_newline: bool,
    /// Metres per file unit.
    pub scale: f64,
    /// The rotation from the file's axes to the frame [`Self::positions`] are in
    /// (identity unless [`Self::reorient`]ed).
    pub frame: DMat3,
    /// Vertex positions, m.
    pub positions: Vec<DVec3>,
    /// The line (0-based) of each `v`.
    pub vertex_lines: Vec<usize>,
    /// The line (0-based) of each `vn`.
    pub normal_lines: Vec<usize>,
    /// `vt` lines.
    pub texcoords: usize,
    /// The faces.
    pub faces: Vec<ObjFace>,
    /// Group names in the order met; index 0 is the faces before any `g` or `o`.
    pub groups: Vec<String>,
    /// `usemtl` and `mtllib` lines.
    pub material_lines: usize,
}

impl ObjDocument {
    /// Reads an OBJ file of at most `max_bytes`; coordinates times `scale` are metres.
    ///
    /// # Failures
    /// As [`super::read_obj`], and texture-coordinate or normal indices out of range.
    pub fn read(path: &Path, scale: f64, max_bytes: u64) -> Result<Self, ObjError> {
        let text = crate::input::read_text(path, max_bytes)?;
        Self::parse(&text, &path.display().to_string(), scale)
    }

    /// Parses OBJ text; `name` is used in messages.
    pub fn parse(text: &str, name: &str, scale: f64) -> Result<Self, ObjError> {
        let syntax = |line: usize, column: usize, message: String| ObjError::Syntax {
            path: name.to_string(),
            line,
            column,
            message,
        };
        let mut doc = Self {
            name: name.to_string(),
            lines: Vec::new(),
            line_end: if text.find('\n').is_some_and(|k| text[..k].ends_with('\r')) {
                "\r\n"
            } else {
                "\n"
            },
            ends_with_newline: text.ends_with('\n'),
            scale,
            frame: DMat3::IDENTITY,
            positions: Vec::new(),
            vertex_lines: Vec::new(),
            normal_lines: Vec::new(),
            texcoords: 0,
            faces: Vec::new(),
            groups: vec![String::new()],
            material_lines: 0,
        };
        let mut group = 0u32;
        for (k, raw) in text.lines().enumerate() {
            let line = k + 1;
            let raw = raw.strip_suffix('\r').unwrap_or(raw);
            doc.lines.push(raw.to_string());
            let content = raw.split('#').next().unwrap_or("");
            let mut tokens = tokens_with_columns(content);
            let Some((_, keyword)) = tokens.next() else {
                continue;
            };
            match keyword {
                "v" => {
                    doc.positions.push(vertex(tokens, line, scale, &syntax)?);
                    doc.vertex_lines.push(k);
                }
                "vt" => doc.texcoords += 1,
                "vn" => doc.normal_lines.push(k),
                "g" | "o" => {
                    let label: Vec<&str> = tokens.map(|(_, t)| t).collect();
                    let label = label.join(" ");
                    group = match doc.groups.iter().position(|g| *g == label) {
                        Some(i) => i as u32,
                        None => {
                            doc.groups.push(label);
                            (doc.groups.len() - 1) as u32
                        }
                    };
                }
                "usemtl" | "mtllib" => doc.material_lines += 1,
                "f" => {
                    let mut corners = Vec::new();
                    for (column, token) in tokens {
                        corners.push(corner(token, (line, column), &doc, &syntax)?);
                    }
                    if corners.len() < 3 {
                        return Err(syntax(
                            line,
                            content.trim_end().len() + 1,
                            format!("a face needs at least 3 vertices, found {}", corners.len()),
                        ));
                    }
                    doc.faces.push(ObjFace { line, corners, group });
                }
                _ => {}
            }
        }
        if doc.positions.is_empty() {
            return Err(ObjError::Empty {
                path: name.into(),
                message: "no vertices ('v' lines)".into(),
            });
        }
        if doc.faces.is_empty() {
            return Err(ObjError::Empty {
                path: name.into(),
                message: "no faces ('f' lines)".into(),
            });
        }
        Ok(doc)
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

    /// The file again with the vertices `moved` at `positions` (m; the same count as
    /// [`Self::positions`]): their `v` lines written anew (any values after the three
    /// coordinates, such as colours, kept), the `vn` lines their corners use recomputed
    /// from the faces around them, every other line as read.
    pub fn write(&self, positions: &[DVec3], moved: &[bool]) -> String {
        let mut replaced: BTreeMap<usize, String> = BTreeMap::new();
        for (v, (&line, p)) in self.vertex_lines.iter().zip(positions).enumerate() {
            if !moved.get(v).copied().unwrap_or(false) {
                continue;
            }
            let rest: Vec<&str> = self.lines[line]
                .split('#')
                .next()
                .unwrap_or("")
                .split_ascii_whitespace()
                .skip(4)
                .collect();
            let q = self.frame.transpose() * *p / self.scale;
            let mut text = format!("v {} {} {}", q.x, q.y, q.z);
            for r in rest {
                text.push(' ');
                text.push_str(r);
            }
            replaced.insert(line, text);
        }
        for (n, normal) in self.normals_of_moved(positions, moved) {
            let normal = self.frame.transpose() * normal;
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

    /// The normals (by `vn` index) that corners of moved vertices use: each the unit sum
    /// of the area-weighted normals at the vertices whose corners use it.
    fn normals_of_moved(&self, positions: &[DVec3], moved: &[bool]) -> BTreeMap<u32, DVec3> {
        let mut used: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
        for face in &self.faces {
            for c in &face.corners {
                if let Some(n) = c.vn
                    && moved.get(c.v as usize).copied().unwrap_or(false)
                {
                    used.entry(n).or_default().push(c.v);
                }
            }
        }
        if used.is_empty() {
            return BTreeMap::new();
        }
        let (triangles, _) = self.triangles();
        let mut at = vec![DVec3::ZERO; positions.len()];
        for t in &triangles {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            let n = (b - a).cross(c - a);
            for &i in t {
                at[i as usize] += n;
            }
        }
        used.into_iter()
            .filter_map(|(n, mut vertices)| {
                vertices.sort_unstable();
                vertices.dedup();
                let sum: DVec3 = vertices.iter().map(|&v| at[v as usize]).sum();
                (sum.length_squared() > 0.0).then(|| (n, sum.normalize()))
            })
            .collect()
    }

    /// A one-line account of what the file holds.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        write!(
            s,
            "{} vertices, {} faces, {} texture coordinates, {} normals, {} group(s)",
            self.positions.len(),
            self.faces.len(),
            self.texcoords,
            self.normal_lines.len(),
            self.groups.len() - usize::from(self.faces.iter().all(|f| f.group != 0))
        )
        .ok();
        s
    }
}

/// One corner token `v`, `v/vt`, `v//vn` or `v/vt/vn` (negative indices count back from the
/// elements read so far), checked against them.
fn corner(
    token: &str,
    (line, column): (usize, usize),
    doc: &ObjDocument,
    syntax: &dyn Fn(usize, usize, String) -> ObjError,
) -> Result<Corner, ObjError> {
    let mut parts = token.split('/');
    let index = |text: Option<&str>, read: usize, what: &str| -> Result<Option<u32>, ObjError> {
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
    let v = index(parts.next(), doc.positions.len(), "vertex")?
        .ok_or_else(|| syntax(line, column, format!("'{token}' is not a vertex index")))?;
    let vt = index(parts.next(), doc.texcoords, "texture coordinate")?;
    let vn = index(parts.next(), doc.normal_lines.len(), "normal")?;
    Ok(Corner { v, vt, vn })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unchanged_document_writes_back_byte_for_byte() {
        let text = "# made elsewhere\r\nmtllib a.mtl\r\nv 0 0 0 1 0 0\r\nv 1.0000001 0 0\r\nv 0 1 0\r\nvt 0 0\r\nvn 0 0 1\r\ng front\r\nusemtl cotton\r\nf 1/1/1 2/1/1 3/1/1\r\n";
        let doc = ObjDocument::parse(text, "a.obj", 1.0).unwrap();
        assert_eq!(doc.write(&doc.positions, &[false; 3]), text);
        assert_eq!(doc.groups, vec!["".to_string(), "front".to_string()]);
        assert_eq!(doc.faces[0].group, 1);
    }

    #[test]
    fn a_moved_vertex_keeps_its_colour_and_the_normal_it_uses_is_recomputed() {
        let text = "v 0 0 0 0.5 0.5 0.5\nv 1 0 0\nv 0 1 0\nvn 1 0 0\nf 1//1 2//1 3//1\n";
        let doc = ObjDocument::parse(text, "a.obj", 0.01).unwrap();
        let mut p = doc.positions.clone();
        p[0].z = -0.01;
        let out = doc.write(&p, &[true, false, false]);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "v 0 0 -1 0.5 0.5 0.5");
        assert_eq!(lines[1], "v 1 0 0");
        assert!(lines[3].starts_with("vn "), "{}", lines[3]);
        assert_ne!(lines[3], "vn 1 0 0");
    }
}
