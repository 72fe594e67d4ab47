//! A recording opened for `run`, `edit` and `replay --serve`: a file, or a viewer or a server
//! with a copy kept in the file (a viewer that goes away loses nothing), and Rerun's web
//! viewer served beside the server for `--serve-web`.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::Context as _;
use drape::viz::{KeptFile, RecordingStream, RecordingTarget, ViewerFlush, open_recording_kept, serve_web_viewer};

use crate::args::ViewerArgs;
use crate::failure::{Classify, Result};
use crate::files::{create_parent, host_name, partial_path};

/// An open recording and what keeps it alive.
pub(crate) struct LiveRecording {
    /// The stream the logger writes to.
    pub(crate) rec: RecordingStream,
    /// The file written beside its final name (`.partial`) and its final name.
    file: Option<(PathBuf, PathBuf)>,
    /// The file's own sink when the stream goes to a viewer or a server too.
    kept: Option<KeptFile>,
    /// The viewer URL for `--connect`.
    connect: Option<String>,
    /// The gRPC port for `--serve` / `--serve-web`.
    serving: Option<u16>,
    /// The web viewer's HTTP server (stops when dropped).
    _web: Option<re_web_viewer_server::WebViewerServer>,
}

impl ViewerArgs {
    /// Where the data go besides the file.
    fn target(&self) -> Option<RecordingTarget> {
        if let Some(url) = &self.connect {
            Some(RecordingTarget::Connect(url.clone()))
        } else if self.serve || self.serve_web {
            Some(RecordingTarget::Serve {
                bind: self.bind,
                port: self.port,
            })
        } else {
            None
        }
    }
}

/// Opens the recording `name`: the file `file` (written as `.partial`, renamed by
/// [`LiveRecording::finish`]), plus the viewer or server `viewer` asks for.
pub(crate) fn open_live(viewer: &ViewerArgs, file: Option<&Path>, name: &str) -> Result<LiveRecording> {
    if let Some(url) = &viewer.connect {
        reachable(url)?;
    }
    let file = match file {
        Some(f) => {
            create_parent(f).internal()?;
            Some((partial_path(f), f.to_path_buf()))
        }
        None => None,
    };
    let partial = file.as_ref().map(|(p, _)| p.as_path());
    let (rec, kept) = match (viewer.target(), partial) {
        (None, Some(p)) => drape::viz::open_recording(&RecordingTarget::File(p.to_path_buf()), name).map(|r| (r, None)),
        (Some(target), keep) => open_recording_kept(&target, name, keep),
        (None, None) => {
            return Err(anyhow::anyhow!("a recording needs a file, a viewer or a server")).internal();
        }
    }
    .context("cannot open the recording")
    .internal()?;
    let serving = (viewer.serve || viewer.serve_web).then_some(viewer.port);
    let mut web = None;
    if let Some(port) = serving {
        // Loopback: this machine only, and other machines through an SSH tunnel; another
        // address: open to a network, without authentication.
        let host = if viewer.bind.is_loopback() {
            println!(
                "serving on {}:{port}, this machine only; open it here with:",
                viewer.bind
            );
            "localhost".to_string()
        } else {
            eprintln!(
                "warning: serving on {}:{port}{}: Rerun's servers have no authentication, so anyone who can \
                 reach these ports can open this recording (a body scan is personal data)",
                viewer.bind,
                if viewer.serve_web {
                    format!(" and {}", viewer.web_port)
                } else {
                    String::new()
                }
            );
            println!("serving on {}:{port}; open it from any machine with:", viewer.bind);
            host_name()
        };
        println!("  rerun rerun+http://{host}:{port}/proxy");
        if viewer.serve_web {
            let (server, url) = serve_web_viewer(viewer.bind, port, viewer.web_port, &host)
                .with_context(|| format!("cannot serve the web viewer on port {}", viewer.web_port))
                .internal()?;
            println!("or in a browser:");
            println!("  {url}");
            web = Some(server);
        }
        if viewer.bind.is_loopback() {
            let web = if viewer.serve_web {
                format!(" -L {0}:localhost:{0}", viewer.web_port)
            } else {
                String::new()
            };
            println!(
                "from another machine, tunnel first (then open the same): ssh -L {port}:localhost:{port}{web} {}",
                host_name()
            );
        }
        std::io::stdout().flush().ok();
    }
    Ok(LiveRecording {
        rec,
        file,
        kept,
        connect: viewer.connect.clone(),
        serving,
        _web: web,
    })
}

impl LiveRecording {
    /// Ends the recording. The file is finished first (a viewer that went away cannot hold
    /// it up) and renamed to its final name; then a viewer gets what is left (a failure is
    /// reported, not fatal: the file has everything), or a server keeps serving late viewers
    /// until `stop` is set (Ctrl-C).
    pub(crate) fn finish(self, stop: &Arc<AtomicBool>) -> Result<Option<PathBuf>> {
        let Self {
            rec,
            file,
            kept,
            connect,
            serving,
            _web,
        } = self;
        let closed = kept.map(|k| k.close(&rec, std::time::Duration::from_secs(60)));
        let (viewer, written) = match closed {
            Some((viewer, written)) => (Some(viewer), written),
            None => (None, Ok(())),
        };
        written
            .map_err(|e| anyhow::anyhow!("the recording's file could not be written: {e}"))
            .internal()?;
        match viewer {
            None if serving.is_none() => {
                drop(rec); // closes the file sink
                return rename(file);
            }
            None | Some(ViewerFlush::Delivered) => {}
            Some(ViewerFlush::Failed(e)) => {
                let to = connect.as_deref().unwrap_or("the server");
                eprintln!("warning: the viewer at {to} did not get everything ({e}); the file has it all");
            }
            Some(ViewerFlush::TimedOut) => {
                eprintln!("warning: the viewer did not take the data within a minute; the file may lack the last of it")
            }
        }
        let path = rename(file)?;
        if connect.is_some() {
            // A viewer that went away would hold up the drop for good; the file is closed
            // and the process ends now.
            std::mem::forget(rec);
            return Ok(path);
        }
        if serving.is_some() {
            rec.flush_blocking().ok(); // the server holds everything now
            println!("all data sent; still serving for late viewers. Press Ctrl-C to stop.");
            std::io::stdout().flush().ok();
            while !stop.load(Ordering::SeqCst) {
                std::thread::sleep(std::time::Duration::from_millis(200));
            }
        }
        drop(rec); // stops the server
        Ok(path)
    }
}

/// Checks that a viewer listens at `url` (`rerun+http://HOST:PORT/proxy`) before anything is
/// logged: a stream to a viewer that is not there would hold the data back (and the file
/// with them) until it came.
fn reachable(url: &str) -> Result<()> {
    use std::net::ToSocketAddrs as _;
    let rest = url
        .strip_prefix("rerun+http://")
        .or_else(|| url.strip_prefix("rerun+https://"))
        .ok_or_else(|| anyhow::anyhow!("--connect {url}: expected rerun+http://HOST:PORT/proxy"))
        .bad_input()?;
    let authority = rest.split('/').next().unwrap_or(rest);
    let addrs: Vec<_> = authority
        .to_socket_addrs()
        .with_context(|| format!("--connect {url}: cannot resolve {authority}"))
        .bad_input()?
        .collect();
    let timeout = std::time::Duration::from_secs(3);
    if addrs
        .iter()
        .any(|a| std::net::TcpStream::connect_timeout(a, timeout).is_ok())
    {
        Ok(())
    } else {
        Err(anyhow::anyhow!(
            "--connect {url}: no viewer listens at {authority} (start one there with `rerun --serve-grpc` or \
             `rerun`, or use --serve and let viewers join)"
        ))
        .internal()
    }
}

/// Renames the finished `.partial` file to its final name.
fn rename(file: Option<(PathBuf, PathBuf)>) -> Result<Option<PathBuf>> {
    let Some((partial, path)) = file else {
        return Ok(None);
    };
    crate::files::finish_recording(&partial, &path)?;
    Ok(Some(path))
}
