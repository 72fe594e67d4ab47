//! Reading input files within bounds: only a regular file, and no larger than a limit, so a
//! device (`/dev/zero`), a pipe or a huge file is refused at once instead of read until the
//! memory runs out.

use std::io::Read as _;
use std::path::Path;

use thiserror::Error;

/// The default limit on an input file (a body or a session), bytes: 256 MiB, some 400 times
/// a 13,000-vertex body OBJ.
pub const DEFAULT_MAX_INPUT_BYTES: u64 = 256 * 1024 * 1024;

/// Why an input file cannot be read.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum InputError {
    /// The file cannot be opened or read.
    #[error("{path}: cannot read: {message}")]
    Io {
        /// The file.
        path: String,
        /// The system's message.
        message: String,
    },
    /// Not a regular file (a folder, a device, a pipe).
    #[error("{path}: not a regular file ({kind}): give a file")]
    NotAFile {
        /// The path.
        path: String,
        /// What it is.
        kind: &'static str,
    },
    /// Larger than the limit.
    #[error("{path}: {size} bytes, more than the limit of {limit} bytes (raise it with --max-input-mb)")]
    TooLarge {
        /// The file.
        path: String,
        /// Its size, bytes (at least, for a file still growing).
        size: u64,
        /// The limit, bytes.
        limit: u64,
    },
    /// Not UTF-8 text.
    #[error("{path}: not UTF-8 text (byte {at})")]
    NotText {
        /// The file.
        path: String,
        /// Offset of the first bad byte.
        at: usize,
    },
}

/// What a path that is not a regular file is.
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a folder";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_fifo() {
            return "a pipe";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "not a file"
}

/// Reads the text of the regular file `path`, at most `max_bytes` long. The size is checked
/// before reading (a huge file is refused without reading it) and while reading (a file
/// that grows).
///
/// # Failures
/// [`InputError`]: unreadable, not a regular file, too large, not UTF-8.
pub fn read_text(path: &Path, max_bytes: u64) -> Result<String, InputError> {
    let bytes = read_bytes(path, max_bytes)?;
    String::from_utf8(bytes).map_err(|e| InputError::NotText {
        path: path.display().to_string(),
        at: e.utf8_error().valid_up_to(),
    })
}

/// Reads the bytes of the regular file `path`, at most `max_bytes` long, checked as
/// [`read_text`] checks them.
///
/// # Failures
/// [`InputError`]: unreadable, not a regular file, too large.
pub fn read_bytes(path: &Path, max_bytes: u64) -> Result<Vec<u8>, InputError> {
    let name = path.display().to_string();
    let io = |e: std::io::Error| InputError::Io {
        path: name.clone(),
        message: e.to_string(),
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(InputError::NotAFile {
            path: name,
            kind: kind_of(&meta),
        });
    }
    let too_large = |size: u64| InputError::TooLarge {
        path: name.clone(),
        size,
        limit: max_bytes,
    };
    if meta.len() > max_bytes {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
    std::fs::File::open(path)
        .and_then(|f| f.take(max_bytes.saturating_add(1)).read_to_end(&mut bytes))
        .map_err(io)?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}
