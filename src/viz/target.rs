//! Where a recording goes: a file, a remote viewer, a gRPC server viewers join, or memory.

use std::path::PathBuf;

use rerun::{RecordingStream, RecordingStreamBuilder, RecordingStreamResult};

use super::{APP_ID, default_blueprint};

/// A recording's destination.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RecordingTarget {
    /// An `.rrd` file.
    File(PathBuf),
    /// A viewer or proxy at a `rerun+http://host:port/proxy` URL.
    Connect(String),
    /// A gRPC server on `0.0.0.0:port` that viewers connect to, now or later.
    Serve(u16),
}

/// Batching without clock- or size-driven flushes: the logger flushes after every log call
/// (see [`super::logger::OrderedRecording`]), so two runs write the same chunks in the same
/// order.
fn batcher() -> rerun::log::ChunkBatcherConfig {
    rerun::log::ChunkBatcherConfig::NEVER
}

/// Opens a recording with the default blueprint, no wall-clock `log_time`, a recording id
/// derived from `name` and chunks that follow the log calls, so the same session logs the
/// same data.
pub fn open_recording(target: &RecordingTarget, name: &str) -> RecordingStreamResult<RecordingStream> {
    let builder = RecordingStreamBuilder::new(APP_ID)
        .recording_id(format!("drape-{name}"))
        .recording_name(name)
        .batcher_config(batcher())
        .with_blueprint(default_blueprint());
    let rec = match target {
        RecordingTarget::File(path) => builder.save(path)?,
        RecordingTarget::Connect(url) => builder.connect_grpc_opts(url.as_str())?,
        RecordingTarget::Serve(port) => builder.serve_grpc_opts("0.0.0.0", *port, rerun::ServerOptions::default())?,
    };
    rec.set_log_time_enabled(false);
    Ok(rec)
}

/// An in-memory recording for tests, set up like [`open_recording`].
pub fn memory_recording(name: &str) -> RecordingStreamResult<(RecordingStream, rerun::sink::MemorySinkStorage)> {
    let (rec, storage) = RecordingStreamBuilder::new(APP_ID)
        .recording_id(format!("drape-{name}"))
        .recording_name(name)
        .batcher_config(batcher())
        .memory()?;
    rec.set_log_time_enabled(false);
    Ok((rec, storage))
}
