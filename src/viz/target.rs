//! Where a recording goes: a file, a remote viewer, a gRPC server viewers join (with the
//! web viewer served beside it if asked), or memory.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use rerun::{RecordingStream, RecordingStreamBuilder, RecordingStreamResult};

use super::session_file::SessionFile;
use super::{APP_ID, default_blueprint};

/// A recording's destination.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RecordingTarget {
    /// An `.rrd` file.
    File(PathBuf),
    /// A viewer or proxy at a `rerun+http://host:port/proxy` URL.
    Connect(String),
    /// A gRPC server on `bind:port` that viewers connect to, now or later (`127.0.0.1`:
    /// this machine only; Rerun's servers have no authentication).
    Serve {
        /// The address to listen on.
        bind: std::net::IpAddr,
        /// The port.
        port: u16,
    },
}

/// Batching without clock- or size-driven flushes: the logger flushes after every log call
/// (see [`super::recording::OrderedRecording`]), so two runs write the same chunks in the same
/// order.
fn batcher() -> rerun::log::ChunkBatcherConfig {
    rerun::log::ChunkBatcherConfig::NEVER
}

/// Opens a recording with the default blueprint, no wall-clock `log_time`, a recording id
/// derived from `name` and chunks that follow the log calls, so the same session logs the
/// same data. A file (the target, or the copy kept beside a viewer) is a session's file
/// ([`super::session_file::SessionFile`]: uncompressed, without Rerun's index): once the
/// recording is closed, [`super::rrd_index::index_into`] compresses and indexes it.
pub fn open_recording(target: &RecordingTarget, name: &str) -> RecordingStreamResult<RecordingStream> {
    open_recording_kept(target, name, None).map(|(rec, _)| rec)
}

/// A recording to a file with its own `blueprint` (the studies' layouts), otherwise as
/// [`open_recording`].
pub fn open_file_recording(
    path: &Path,
    name: &str,
    blueprint: rerun::blueprint::Blueprint,
) -> RecordingStreamResult<RecordingStream> {
    let rec = RecordingStreamBuilder::new(APP_ID)
        .recording_id(format!("drape-{name}"))
        .recording_name(name)
        .batcher_config(batcher())
        .with_blueprint(blueprint)
        .save(path)?;
    rec.set_log_time_enabled(false);
    Ok(rec)
}

/// [`open_recording`], with a copy of everything logged also written to the file `keep` when
/// the target is a viewer or a server: if the viewer goes away mid-session, the session goes
/// on and the file holds every step. The file is closed by [`KeptFile::close`], which does
/// not wait for the viewer (a file target ignores `keep` and returns no [`KeptFile`]).
pub fn open_recording_kept(
    target: &RecordingTarget,
    name: &str,
    keep: Option<&Path>,
) -> RecordingStreamResult<(RecordingStream, Option<KeptFile>)> {
    let builder = RecordingStreamBuilder::new(APP_ID)
        .recording_id(format!("drape-{name}"))
        .recording_name(name)
        .batcher_config(batcher())
        .with_blueprint(default_blueprint());
    let kept = match (target, keep) {
        (RecordingTarget::File(_), _) | (_, None) => None,
        (_, Some(file)) => Some(KeptFile::new(SessionFile::create(file)?)),
    };
    let rec = match (target, &kept) {
        (RecordingTarget::File(path), _) => {
            let sink: Box<dyn rerun::sink::LogSink> = Box::new(SessionFile::create(path)?);
            builder.set_sinks(vec![sink])?
        }
        (RecordingTarget::Connect(url), None) => builder.connect_grpc_opts(url.as_str())?,
        (RecordingTarget::Connect(url), Some(file)) => {
            let rerun::external::re_uri::RedapUri::Proxy(uri) = url.parse()? else {
                return Err(rerun::RecordingStreamError::NotAProxyEndpoint);
            };
            let sinks: Vec<Box<dyn rerun::sink::LogSink>> =
                vec![Box::new(file.clone()), Box::new(rerun::sink::GrpcSink::new(uri))];
            builder.set_sinks(sinks)?
        }
        (RecordingTarget::Serve { bind, port }, None) => {
            builder.serve_grpc_opts(bind.to_string(), *port, rerun::ServerOptions::default())?
        }
        (RecordingTarget::Serve { bind, port }, Some(file)) => {
            let server =
                rerun::grpc_server::GrpcServerSink::new(&bind.to_string(), *port, rerun::ServerOptions::default())
                    .map_err(|e| rerun::RecordingStreamError::WebSink(e.into()))?;
            let sinks: Vec<Box<dyn rerun::sink::LogSink>> = vec![Box::new(file.clone()), Box::new(server)];
            builder.set_sinks(sinks)?
        }
    };
    rec.set_log_time_enabled(false);
    Ok((rec, kept))
}

/// The file copy of a recording that goes to a viewer or a server: a sink beside the
/// viewer's, closed on its own so that a viewer that went away (whose sink would wait for it
/// for good when dropped) cannot keep the file from being finished.
#[derive(Clone)]
pub struct KeptFile(Arc<SessionFile>);

/// How closing a [`KeptFile`] went for the viewer (the file is closed either way).
#[derive(Debug)]
pub enum ViewerFlush {
    /// The viewer or server got everything.
    Delivered,
    /// The viewer went away or failed; the file has everything.
    Failed(rerun::sink::SinkFlushError),
    /// The viewer did not take the data in time: the file may lack the last of it.
    TimedOut,
}

impl KeptFile {
    fn new(file: SessionFile) -> Self {
        Self(Arc::new(file))
    }

    /// Flushes the stream (every message logged so far reaches this sink, in order, before
    /// the flush completes or fails at the viewer's sink), then closes the file. What is
    /// logged afterwards goes to the viewer only. Returns how the viewer fared, and the
    /// file's first failed write, if any.
    pub fn close(
        &self,
        rec: &RecordingStream,
        timeout: std::time::Duration,
    ) -> (ViewerFlush, Result<(), rerun::sink::SinkFlushError>) {
        let outcome = match rec.flush_with_timeout(timeout) {
            Ok(()) => ViewerFlush::Delivered,
            Err(rerun::sink::SinkFlushError::Timeout) => ViewerFlush::TimedOut,
            Err(e) => ViewerFlush::Failed(e),
        };
        (outcome, self.0.close())
    }
}

impl rerun::sink::LogSink for KeptFile {
    fn send(&self, msg: rerun::log::LogMsg) {
        rerun::sink::LogSink::send(&*self.0, msg);
    }

    fn flush_blocking(&self, timeout: std::time::Duration) -> Result<(), rerun::sink::SinkFlushError> {
        rerun::sink::LogSink::flush_blocking(&*self.0, timeout)
    }

    fn defers_finalization_to_shutdown(&self) -> bool {
        true
    }
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

/// Serves Rerun's web viewer (shipped inside the binary) over HTTP on `bind:web_port`, set
/// to load the gRPC server on `grpc_port` of `host`: a browser is all a remote person needs.
/// Returns the server (it stops when dropped) and the URL to open.
pub fn serve_web_viewer(
    bind: std::net::IpAddr,
    grpc_port: u16,
    web_port: u16,
    host: &str,
) -> Result<(re_web_viewer_server::WebViewerServer, String), WebViewerError> {
    let server = rerun::serve_web_viewer(rerun::web_viewer::WebViewerConfig {
        bind_ip: bind.to_string(),
        web_port: re_web_viewer_server::WebViewerServerPort(web_port),
        open_browser: false,
        ..Default::default()
    })?;
    let url = format!("http://{host}:{web_port}/?url=rerun%2Bhttp://{host}:{grpc_port}/proxy");
    Ok((server, url))
}

/// The web viewer could not be served (the port is taken, most often).
pub type WebViewerError = re_web_viewer_server::WebViewerServerError;
