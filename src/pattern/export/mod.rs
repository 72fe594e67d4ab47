//! A pattern written for other tools: DXF in the AAMA/ASTM D6673 layout ([`dxf`]), an SVG
//! of the laid-out pieces at 1:1 in millimetres ([`svg`]), a JSON summary ([`json`]) and one
//! OBJ per piece with its 3D positions and its 2D positions as texture coordinates
//! ([`obj`]). Each file is written beside its final name and renamed, so a failure never
//! leaves half a file.

pub mod dxf;
pub mod json;
pub mod obj;
pub mod svg;

use std::path::{Path, PathBuf};

use super::Pattern;

/// Why a pattern could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The DXF writer failed.
    #[error("cannot write the DXF {path}: {message}")]
    Dxf {
        /// The file.
        path: PathBuf,
        /// The writer's message.
        message: String,
    },
}

/// A file name part from a piece name (`torso.front_left` stays, anything but letters,
/// digits, `.`, `_` and `-` becomes `_`).
pub fn file_part(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Writes `bytes` to `path` through a temporary file.
fn write_file(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    let tmp = path.with_extension("partial");
    std::fs::write(&tmp, bytes)
        .and_then(|()| std::fs::rename(&tmp, path))
        .map_err(|source| ExportError::Io {
            path: path.to_path_buf(),
            source,
        })
}

/// Writes every file of one step's pattern into `dir` as `{prefix}_patterns.dxf`, `.svg`,
/// `.json` and `{prefix}_panel_{name}.obj`; returns the paths written.
pub fn write_all(dir: &Path, prefix: &str, pattern: &Pattern) -> Result<Vec<PathBuf>, ExportError> {
    std::fs::create_dir_all(dir).map_err(|source| ExportError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut written = Vec::new();
    let dxf_path = dir.join(format!("{prefix}_patterns.dxf"));
    let bytes = dxf::to_dxf(pattern).map_err(|message| ExportError::Dxf {
        path: dxf_path.clone(),
        message,
    })?;
    write_file(&dxf_path, &bytes)?;
    written.push(dxf_path);
    for (ext, text) in [("svg", svg::to_svg(pattern)), ("json", json::to_json(pattern))] {
        let path = dir.join(format!("{prefix}_patterns.{ext}"));
        write_file(&path, text.as_bytes())?;
        written.push(path);
    }
    for piece in &pattern.pieces {
        let path = dir.join(format!("{prefix}_panel_{}.obj", file_part(&piece.panel.name)));
        write_file(&path, obj::to_obj(piece).as_bytes())?;
        written.push(path);
    }
    Ok(written)
}
