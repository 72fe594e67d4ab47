//! The error of every mesh file reader and writer.

use thiserror::Error;

/// Why a mesh file (OBJ, PLY, glTF or GLB) could not be read or written.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MeshFileError {
    /// The file could not be opened or read.
    #[error("{path}: cannot read: {message}")]
    Io {
        /// File name.
        path: String,
        /// The system's message.
        message: String,
    },
    /// A statement is malformed.
    #[error("{path}:{line}:{column}: {message}")]
    Syntax {
        /// File name.
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What was expected.
        message: String,
    },
    /// The file cannot be read within bounds (not a regular file, too large, not text).
    #[error(transparent)]
    Input(#[from] crate::input::InputError),
    /// A PLY or glTF file is malformed, or holds what drape cannot use (named by element,
    /// accessor or byte).
    #[error("{path}: {format}: {message}")]
    Format {
        /// File name.
        path: String,
        /// "PLY" or "glTF".
        format: &'static str,
        /// What is wrong and where.
        message: String,
    },
    /// A kind of file drape does not read or write.
    #[error("{path}: {message}")]
    Unsupported {
        /// File name.
        path: String,
        /// What drape reads instead.
        message: String,
    },
    /// The file has no vertices or no faces.
    #[error("{path}: {message}")]
    Empty {
        /// File name.
        path: String,
        /// What is missing.
        message: String,
    },
}
