//! The recording file as a session writes it: each message encoded and written by the
//! thread that hands it to the sink, uncompressed and without Rerun's index, so that a step
//! pays for neither; [`super::rrd_index::index_into`] compresses and indexes the file when the
//! recording is closed.
//!
//! Rerun's own file sink hands every message to a writer thread of its own, compresses it
//! (LZ4) and adds it to the index it builds as it goes: on one core, work and thread switches
//! every step waits for, since a step ends when its chunks are in the file. The file written
//! here is a valid recording (the viewer opens it; its stream header says it is not
//! compressed), so a file a crash left holds every finished step.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use rerun::external::re_build_info::CrateVersion;
use rerun::external::re_log_encoding::{Encoder, EncodingOptions, FileSinkError};
use rerun::log::LogMsg;
use rerun::sink::{LogSink, SinkFlushError};

/// A file sink: uncompressed, unindexed, written on the caller's thread (see the module's
/// notes). The file is closed by [`Self::close`] or when the sink is dropped.
pub struct SessionFile {
    path: PathBuf,
    encoder: Mutex<Option<Encoder<BufWriter<File>>>>,
    /// The first write that failed: every later flush reports it.
    failed: Mutex<Option<String>>,
}

impl SessionFile {
    /// Creates the file at `path` (replacing one there) and writes the stream's header.
    pub fn create(path: &Path) -> Result<Self, FileSinkError> {
        let file = File::create(path).map_err(|source| FileSinkError::CreateFile {
            source,
            path: path.to_path_buf(),
        })?;
        let writer = BufWriter::with_capacity(1 << 20, file);
        let mut encoder = Encoder::new_eager(CrateVersion::LOCAL, EncodingOptions::PROTOBUF_UNCOMPRESSED, writer)?;
        encoder.do_not_emit_footer();
        Ok(Self {
            path: path.to_path_buf(),
            encoder: Mutex::new(Some(encoder)),
            failed: Mutex::new(None),
        })
    }

    /// Writes what is buffered and closes the file; what is sent afterwards is dropped.
    /// Returns the first write that failed, if any.
    pub fn close(&self) -> Result<(), SinkFlushError> {
        let encoder = self.encoder.lock().ok().and_then(|mut slot| slot.take());
        if let Some(mut encoder) = encoder
            && let Err(e) = encoder.finish().and_then(|()| encoder.flush_blocking())
        {
            self.fail(e.to_string());
        }
        self.reported()
    }

    /// Runs `write` on the open file's encoder (nothing once the file is closed), keeping
    /// its error as the first failed write if there was none.
    fn with_encoder(&self, write: impl FnOnce(&mut Encoder<BufWriter<File>>) -> Result<(), String>) {
        let result = match self.encoder.lock() {
            Ok(mut slot) => slot.as_mut().map_or(Ok(()), write),
            Err(_) => Err("the file's writer panicked".to_string()),
        };
        if let Err(message) = result {
            self.fail(message);
        }
    }

    fn fail(&self, message: String) {
        if let Ok(mut failed) = self.failed.lock()
            && failed.is_none()
        {
            *failed = Some(format!("{}: {message}", self.path.display()));
        }
    }

    fn reported(&self) -> Result<(), SinkFlushError> {
        match self.failed.lock().ok().and_then(|f| f.clone()) {
            Some(message) => Err(SinkFlushError::failed(message)),
            None => Ok(()),
        }
    }
}

impl LogSink for SessionFile {
    fn send(&self, msg: LogMsg) {
        self.with_encoder(|encoder| encoder.append(&msg).map(|_| ()).map_err(|e| e.to_string()));
    }

    /// Writes what is buffered to the file, at once (no writer thread to wait for, so no
    /// timeout), and returns the first failed write, if any.
    fn flush_blocking(&self, _timeout: std::time::Duration) -> Result<(), SinkFlushError> {
        self.with_encoder(|encoder| encoder.flush_blocking().map_err(|e| e.to_string()));
        self.reported()
    }

    fn defers_finalization_to_shutdown(&self) -> bool {
        true
    }
}

impl Drop for SessionFile {
    fn drop(&mut self) {
        self.close().ok();
    }
}
