//! The body index kept between runs: one file per body, so that the second session on a body
//! reads its [`BodyIndex`] instead of building it again (pseudo-normals, eight trees, the
//! shell's self-test, the slices: tens of milliseconds on a 27,000-triangle body).
//!
//! A file is named by a key, a 64-bit xxHash of everything the build reads: the mesh
//! (positions and triangles, bit for bit), the partitions (bounds, rules and triangles), the
//! landmarks and slice settings the slices use, the file format, and a fingerprint of the
//! sources of this build of drape (made by `build.rs`: any change to the code makes new
//! keys, so an index is never read by code that would have built it differently). The key
//! is also stored in the file with the payload's length and checksum; a file that is
//! truncated, damaged, of another format or made for another body is not used (the index
//! is built and the file written again). Files are written beside their final name and
//! renamed into place, so a reader never sees half a file, and two runs writing the same
//! key at once both leave a whole one. The folder keeps the [`KEEP`] most recently used
//! files.
//!
//! The index read back is the one that was written, field for field (the payload is
//! postcard, which stores `f32` and `f64` bit for bit): every answer it gives is the same.

use std::fmt;
use std::fs::File;
use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

use thiserror::Error;
use xxhash_rust::xxh64::{Xxh64, xxh64};

use super::Body;
use super::index::BodyIndex;
use super::slices::SliceOptions;

/// The first bytes of every index file.
const MAGIC: &[u8; 8] = b"DRAPEIDX";
/// The file format; a reader refuses any other (2: one section, the index with its own
/// trees; 1 stored parry3d's trees in sections of their own).
const FORMAT: u32 = 2;
/// Magic, format, key, payload length, payload checksum.
const HEADER: usize = 8 + 4 + 8 + 8 + 8;
/// The sources' fingerprint (see `build.rs`).
const SOURCE: &str = env!("DRAPE_SOURCE_FINGERPRINT");
/// Index files the folder keeps (the most recently used; about 10 MB each for a
/// 27,000-triangle body).
pub const KEEP: usize = 16;

/// Why a cache file could not be used or written.
#[derive(Debug, Error)]
pub enum CacheError {
    /// Reading or writing failed.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The file is there but is not a usable index for this body and this build.
    #[error("{path}: {what}")]
    Unusable {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        what: String,
    },
    /// The index could not be encoded.
    #[error("encoding the index: {0}")]
    Encode(#[from] postcard::Error),
}

/// Where the index came from.
#[derive(Debug)]
pub enum CacheOutcome {
    /// Read from this file.
    Read(PathBuf),
    /// Built, because no file was there or the one there could not be used (`unusable`),
    /// then written to `path` (`written` says whether that worked; the index is good
    /// either way).
    Built {
        /// The file for this body.
        path: PathBuf,
        /// Why the file that was there was not used.
        unusable: Option<CacheError>,
        /// The write's failure, if it failed.
        write_error: Option<CacheError>,
    },
}

impl fmt::Display for CacheOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read(path) => write!(f, "body index read from the cache ({})", path.display()),
            Self::Built {
                path,
                unusable,
                write_error,
            } => {
                write!(f, "body index built")?;
                if let Some(e) = unusable {
                    write!(f, " (the cached one was not used: {e})")?;
                }
                match write_error {
                    None => write!(f, " and cached ({})", path.display()),
                    Some(e) => write!(f, "; not cached: {e}"),
                }
            }
        }
    }
}

/// A folder of body index files.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IndexCache {
    dir: PathBuf,
}

impl IndexCache {
    /// A cache in `dir` (made when the first file is written).
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Self { dir: dir.into() }
    }

    /// The user's cache folder for drape's body indexes (`~/.cache/drape/index` on Linux);
    /// `None` where the system has no home folder.
    pub fn default_dir() -> Option<PathBuf> {
        directories::ProjectDirs::from("", "", "drape").map(|d| d.cache_dir().join("index"))
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The file that holds (or would hold) the index of `body` with `slices`.
    pub fn path_for(&self, body: &Body, slices: &SliceOptions) -> PathBuf {
        self.path_of(key(body, slices))
    }

    fn path_of(&self, key: u64) -> PathBuf {
        self.dir.join(format!("{key:016x}.index"))
    }

    /// The index of `body` with `slices`: read from its file, or built (and written) when
    /// there is none or it cannot be used. Never fails: a cache that cannot be read or
    /// written only costs the build, and the outcome says why.
    pub fn load_or_build(&self, body: &Body, slices: &SliceOptions) -> (BodyIndex, CacheOutcome) {
        let key = key(body, slices);
        let path = self.path_of(key);
        let unusable = match read(&path, key, body) {
            Ok(Some(index)) => {
                // Most recently used: the pruning keeps it.
                if let Ok(file) = File::options().append(true).open(&path) {
                    let _ = file.set_modified(SystemTime::now());
                }
                return (index, CacheOutcome::Read(path));
            }
            Ok(None) => None,
            Err(e) => Some(e),
        };
        let index = BodyIndex::new(body, slices);
        let write_error = write(&self.dir, &path, key, &index).err();
        if write_error.is_none() {
            prune(&self.dir, KEEP);
        }
        (
            index,
            CacheOutcome::Built {
                path,
                unusable,
                write_error,
            },
        )
    }
}

/// The key of `body`'s index with `slices`: everything [`BodyIndex::new`] reads.
pub fn key(body: &Body, slices: &SliceOptions) -> u64 {
    let mut h = Feed::default();
    h.bytes(b"drape body index\0");
    h.bytes(&FORMAT.to_le_bytes());
    h.bytes(SOURCE.as_bytes());
    let mesh = &body.mesh.mesh;
    h.count(mesh.positions.len());
    for p in &mesh.positions {
        for c in p.to_array() {
            h.bytes(&c.to_bits().to_le_bytes());
        }
    }
    h.count(mesh.triangles.len());
    for t in &mesh.triangles {
        for i in t {
            h.bytes(&i.to_le_bytes());
        }
    }
    h.count(body.partitions.len());
    for p in &body.partitions {
        h.bytes(format!("{:?} {:?} {:?}", p.id, p.method, p.response).as_bytes());
        h.bytes(&p.lower_y.to_bits().to_le_bytes());
        h.bytes(&p.upper_y.to_bits().to_le_bytes());
        h.count(p.triangles.len());
        for t in &p.triangles {
            h.bytes(&t.to_le_bytes());
        }
    }
    // `{:?}` prints every f64 so that it reads back to the same bits.
    h.bytes(format!("{:?}", body.landmarks).as_bytes());
    h.bytes(format!("{slices:?}").as_bytes());
    h.digest()
}

/// An xxHash fed through a buffer (one hash update per 16 KiB, not per number).
struct Feed {
    hash: Xxh64,
    buf: Vec<u8>,
}

impl Default for Feed {
    fn default() -> Self {
        Self {
            hash: Xxh64::new(0),
            buf: Vec::with_capacity(1 << 14),
        }
    }
}

impl Feed {
    fn bytes(&mut self, b: &[u8]) {
        if self.buf.len() + b.len() > self.buf.capacity() {
            self.hash.update(&self.buf);
            self.buf.clear();
        }
        self.buf.extend_from_slice(b);
    }

    fn count(&mut self, n: usize) {
        self.bytes(&(n as u64).to_le_bytes());
    }

    fn digest(mut self) -> u64 {
        self.hash.update(&self.buf);
        self.hash.digest()
    }
}

/// The index in `path` if it is there and usable for `body` (whose key is `key`).
///
/// The payload is a run of sections (now one: the index), each its length then its postcard
/// bytes; they are read one at a time into one buffer, which spares the memory (and the
/// page faults) of the whole file at once.
fn read(path: &Path, key: u64, body: &Body) -> Result<Option<BodyIndex>, CacheError> {
    let mut file = match File::open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(source) => {
            return Err(CacheError::Io {
                path: path.to_path_buf(),
                source,
            });
        }
    };
    let unusable = |what: String| CacheError::Unusable {
        path: path.to_path_buf(),
        what,
    };
    let io = |source| CacheError::Io {
        path: path.to_path_buf(),
        source,
    };
    let size = file.metadata().map_err(io)?.len();
    let mut header = [0u8; HEADER];
    if size < HEADER as u64 || file.read_exact(&mut header).is_err() || &header[..8] != MAGIC {
        return Err(unusable("not a drape body index file".into()));
    }
    let word = |at: usize| u64::from_le_bytes(header[at..at + 8].try_into().unwrap_or_default());
    let format = u32::from_le_bytes(header[8..12].try_into().unwrap_or_default());
    if format != FORMAT {
        return Err(unusable(format!("format {format}, this build reads {FORMAT}")));
    }
    if word(12) != key {
        return Err(unusable("made for another body or another build".into()));
    }
    let payload = size - HEADER as u64;
    if word(20) != payload {
        return Err(unusable(format!("truncated: {payload} payload bytes of {}", word(20))));
    }
    let mut sections = Sections {
        file,
        left: payload,
        hash: Xxh64::new(0),
        buf: Vec::new(),
    };
    let decode_error = |e: postcard::Error| unusable(format!("cannot be decoded: {e}"));
    let mut index: BodyIndex = postcard::from_bytes(sections.next().map_err(unusable)?).map_err(decode_error)?;
    if sections.left != 0 {
        return Err(unusable(format!("{} bytes after the last section", sections.left)));
    }
    if sections.hash.digest() != word(28) {
        return Err(unusable("damaged (checksum mismatch)".into()));
    }
    let mesh = &body.mesh.mesh;
    if !index.restore()
        || index.positions.len() != mesh.positions.len()
        || index.triangles.len() != mesh.triangles.len()
        || index.partitions.len() != body.partitions.len()
    {
        return Err(unusable("its counts do not match the body".into()));
    }
    Ok(Some(index))
}

/// The sections of an index file, read one at a time into one buffer and hashed.
struct Sections {
    file: File,
    /// Payload bytes not read yet.
    left: u64,
    hash: Xxh64,
    buf: Vec<u8>,
}

impl Sections {
    /// The next section's bytes; what is wrong if it cannot be read.
    fn next(&mut self) -> Result<&[u8], String> {
        let mut len = [0u8; 8];
        if self.left < 8 || self.file.read_exact(&mut len).is_err() {
            return Err("truncated: a section is missing".into());
        }
        let n = u64::from_le_bytes(len);
        if n > self.left - 8 {
            return Err("truncated: a section runs past the end".into());
        }
        self.left -= 8 + n;
        self.buf.clear();
        self.buf.resize(n as usize, 0);
        self.file
            .read_exact(&mut self.buf)
            .map_err(|e| format!("cannot be read: {e}"))?;
        self.hash.update(&len);
        self.hash.update(&self.buf);
        Ok(&self.buf)
    }
}

/// Writes `index` to `path` (in `dir`): to a temporary file beside it, then renamed.
fn write(dir: &Path, path: &Path, key: u64, index: &BodyIndex) -> Result<(), CacheError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| CacheError::Io { path, source }
    };
    // One buffer: the header (its length and checksum filled in last), then each section's
    // length (filled in after it) and bytes.
    let mut bytes = Vec::with_capacity(HEADER + (16 << 20));
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&FORMAT.to_le_bytes());
    bytes.extend_from_slice(&key.to_le_bytes());
    bytes.resize(HEADER, 0);
    append_section(&mut bytes, index)?;
    let payload = (bytes.len() - HEADER) as u64;
    let checksum = xxh64(&bytes[HEADER..], 0);
    bytes[20..28].copy_from_slice(&payload.to_le_bytes());
    bytes[28..36].copy_from_slice(&checksum.to_le_bytes());
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let nanos = SystemTime::now()
        .duration_since(SystemTime::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    let tmp = dir.join(format!(".{key:016x}.{}.{nanos}.tmp", std::process::id()));
    let written = std::fs::write(&tmp, &bytes).and_then(|()| std::fs::rename(&tmp, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written.map_err(io(path))
}
/// Appends `value` as one section: its length, then its postcard bytes.
fn append_section<T: serde::Serialize>(bytes: &mut Vec<u8>, value: &T) -> Result<(), CacheError> {
    let at = bytes.len();
    bytes.extend_from_slice(&[0; 8]);
    *bytes = postcard::to_extend(value, std::mem::take(bytes))?;
    let n = (bytes.len() - at - 8) as u64;
    bytes[at..at + 8].copy_from_slice(&n.to_le_bytes());
    Ok(())
}

/// Deletes all but the `keep` most recently modified index files of `dir` (best effort).
fn prune(dir: &Path, keep: usize) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut files: Vec<(SystemTime, PathBuf)> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "index"))
        .filter_map(|p| Some((std::fs::metadata(&p).ok()?.modified().ok()?, p)))
        .collect();
    files.sort_by(|a, b| b.cmp(a));
    for (_, path) in files.into_iter().skip(keep) {
        let _ = std::fs::remove_file(path);
    }
}
