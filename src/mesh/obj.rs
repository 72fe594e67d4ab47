//! Wavefront OBJ input and output.
//!
//! Reads `v` and `f` statements (faces of any size are fan-triangulated; `i`, `i/t`,
//! `i//n`, `i/t/n` and negative relative indices are accepted) and ignores the rest
//! (normals, texture coordinates, groups, materials). Every error names the file, line
//! and column, which a general OBJ crate does not, and that is why this reader exists.

use std::fmt::Write as _;
use std::path::Path;

use glam::DVec3;

use super::TriMesh;
pub use super::file_error::MeshFileError;

/// A mesh read from a file, with where each triangle came from (for later error messages).
#[derive(Clone, Debug, PartialEq)]
pub struct ObjMesh {
    /// The triangles and vertices, coordinates multiplied by the unit scale.
    pub mesh: TriMesh,
    /// 1-based source line of each triangle.
    pub triangle_lines: Vec<usize>,
    /// Number of polygons with more than 3 corners that were fan-triangulated.
    pub polygons_triangulated: usize,
    /// What [`Self::triangle_lines`] count: "line" (OBJ) or "face" (PLY, glTF).
    pub place_word: &'static str,
}

/// Reads an OBJ file of at most `max_bytes`; coordinates are multiplied by `scale` (e.g.
/// 0.01 for centimetres).
///
/// # Failures
/// [`MeshFileError`]: unreadable file, not a regular file or too large, malformed numbers,
/// non-finite coordinates, invalid or out-of-range indices, faces with fewer than 3
/// corners, no vertices or no faces.
pub fn read_obj(path: &Path, scale: f64, max_bytes: u64) -> Result<ObjMesh, MeshFileError> {
    let text = crate::input::read_text(path, max_bytes)?;
    parse_obj(&text, &path.display().to_string(), scale)
}

/// Parses OBJ text; `name` is used in error messages.
pub fn parse_obj(text: &str, name: &str, scale: f64) -> Result<ObjMesh, MeshFileError> {
    let syntax = |line: usize, column: usize, message: String| MeshFileError::Syntax {
        path: name.to_string(),
        line,
        column,
        message,
    };
    let mut positions = Vec::new();
    // (line, column, raw index) per corner, resolved once all vertices are known.
    let mut faces: Vec<(usize, Vec<(usize, i64)>)> = Vec::new();
    for (line_index, raw_line) in text.lines().enumerate() {
        let line = line_index + 1;
        let content = raw_line.split('#').next().unwrap_or("");
        let mut tokens = tokens_with_columns(content);
        let Some((_, keyword)) = tokens.next() else {
            continue;
        };
        match keyword {
            "v" => positions.push(vertex(tokens, line, scale, &syntax)?),
            "f" => faces.push((line, face(tokens, (line, content), positions.len(), &syntax)?)),
            _ => {}
        }
    }
    require_both(name, positions.len(), faces.len())?;
    let mut triangles = Vec::new();
    let mut triangle_lines = Vec::new();
    let mut polygons_triangulated = 0;
    for (line, corners) in &faces {
        let mut ids = Vec::with_capacity(corners.len());
        for &(column, index) in corners {
            if index as usize > positions.len() {
                return Err(syntax(
                    *line,
                    column,
                    format!(
                        "vertex index {index} is out of range: the file has {} vertices",
                        positions.len()
                    ),
                ));
            }
            ids.push((index - 1) as u32);
        }
        if ids.len() > 3 {
            polygons_triangulated += 1;
        }
        for k in 1..ids.len() - 1 {
            triangles.push([ids[0], ids[k], ids[k + 1]]);
            triangle_lines.push(*line);
        }
    }
    Ok(ObjMesh {
        mesh: TriMesh { positions, triangles },
        triangle_lines,
        polygons_triangulated,
        place_word: "line",
    })
}

/// The coordinates of a `v` line (after its keyword), scaled to metres.
pub(super) fn vertex<'t>(
    mut tokens: impl Iterator<Item = (usize, &'t str)>,
    line: usize,
    scale: f64,
    syntax: &dyn Fn(usize, usize, String) -> MeshFileError,
) -> Result<DVec3, MeshFileError> {
    let mut xyz = [0.0; 3];
    let mut last_column = 2;
    for (k, slot) in xyz.iter_mut().enumerate() {
        let Some((column, token)) = tokens.next() else {
            return Err(syntax(
                line,
                last_column,
                format!("expected 3 coordinates after 'v', found {k}"),
            ));
        };
        last_column = column + token.len();
        let value: f64 = token
            .parse()
            .map_err(|_| syntax(line, column, format!("'{token}' is not a number")))?;
        if !value.is_finite() {
            return Err(syntax(line, column, format!("coordinate '{token}' is not finite")));
        }
        *slot = value * scale;
    }
    Ok(DVec3::from_array(xyz))
}

/// Refuses an OBJ file without vertices or without faces.
pub(super) fn require_both(name: &str, vertices: usize, faces: usize) -> Result<(), MeshFileError> {
    let missing = if vertices == 0 {
        "no vertices ('v' lines)"
    } else if faces == 0 {
        "no faces ('f' lines)"
    } else {
        return Ok(());
    };
    Err(MeshFileError::Empty {
        path: name.into(),
        message: missing.into(),
    })
}

/// The corners of an `f` line (after its keyword), each with its column and its index from
/// 1 (a negative one counted back from the `read` vertices so far); at least 3.
fn face<'t>(
    tokens: impl Iterator<Item = (usize, &'t str)>,
    (line, content): (usize, &str),
    read: usize,
    syntax: &dyn Fn(usize, usize, String) -> MeshFileError,
) -> Result<Vec<(usize, i64)>, MeshFileError> {
    let mut corners = Vec::new();
    for (column, token) in tokens {
        let index_text = token.split('/').next().unwrap_or("");
        let index: i64 = index_text
            .parse()
            .map_err(|_| syntax(line, column, format!("'{token}' is not a vertex index")))?;
        if index == 0 {
            return Err(syntax(
                line,
                column,
                "vertex index 0 is invalid (OBJ indices start at 1)".into(),
            ));
        }
        // Negative indices count back from the vertices read so far.
        let resolved = if index < 0 { read as i64 + index + 1 } else { index };
        if resolved < 1 {
            return Err(syntax(
                line,
                column,
                format!("relative index {index} reaches before the first vertex"),
            ));
        }
        corners.push((column, resolved));
    }
    if corners.len() < 3 {
        let end = content.trim_end().len() + 1;
        return Err(syntax(
            line,
            end,
            format!("a face needs at least 3 vertices, found {}", corners.len()),
        ));
    }
    Ok(corners)
}

/// Whitespace-separated tokens with their 1-based byte columns.
pub(super) fn tokens_with_columns(line: &str) -> impl Iterator<Item = (usize, &str)> {
    line.split_ascii_whitespace()
        .map(move |token| (token.as_ptr() as usize - line.as_ptr() as usize + 1, token))
}

/// Writes a mesh as OBJ text (`v` and `f` lines, 1-based), with a comment header.
pub fn write_obj(mesh: &TriMesh, header: &str) -> String {
    let mut out = String::with_capacity(mesh.positions.len() * 40 + mesh.triangles.len() * 24);
    for line in header.lines() {
        writeln!(out, "# {line}").ok();
    }
    for p in &mesh.positions {
        writeln!(out, "v {:.6} {:.6} {:.6}", p.x, p.y, p.z).ok();
    }
    for [a, b, c] in &mesh.triangles {
        writeln!(out, "f {} {} {}", a + 1, b + 1, c + 1).ok();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_and_negative_indices_are_triangulated() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3/1 -2//3 -1/2/3\n";
        let obj = parse_obj(text, "q.obj", 1.0).unwrap();
        assert_eq!(obj.mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(obj.polygons_triangulated, 1);
    }

    #[test]
    fn round_trip_keeps_the_mesh() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let obj = parse_obj(text, "t.obj", 1.0).unwrap();
        let again = parse_obj(&write_obj(&obj.mesh, "x"), "t2.obj", 1.0).unwrap();
        assert_eq!(obj.mesh, again.mesh);
    }
}
