//! A recording file's index, written when the recording is closed.
//!
//! Rerun ends an `.rrd` file with a footer: a manifest of every chunk (where it lies in the
//! file, its entity, its time ranges and components), which gives the viewer random access
//! and which `rerun rrd verify` requires. Rerun's file sink builds it as it writes: for each
//! chunk it reads the encoded chunk back and pads the manifest's columns, on its writer's
//! thread, and compresses the chunk (LZ4). That is work per chunk that every step waited for
//! (a step ends when its chunks are in the file).
//!
//! So a session writes its file uncompressed and without the footer
//! ([`super::session_file::SessionFile`]), and [`index_into`] writes the whole file again,
//! compressed and with its footer, when the session is over: the same messages in the same
//! order (Rerun's decoder reads them back, its encoder writes them with the footer it builds),
//! into a file beside the final one that then takes its name. It costs about one decode and
//! one encode of the file, once, after the last step.

use std::io::{BufReader, BufWriter, Write as _};
use std::path::{Path, PathBuf};

use rerun::external::re_build_info::CrateVersion;
use rerun::external::re_log_encoding::{DecoderApp, Encoder, EncodingOptions};
use rerun::log::LogMsg;

use crate::session::SinkError;

/// Writes the recording `from` (closed: written by a [`super::session_file::SessionFile`], or
/// any recording) to `to`, compressed and with Rerun's footer, message by message (never the
/// whole recording in memory), through a file beside `to` that then takes its name; `from`
/// is removed once `to` is in place. On an error (a file, or Rerun's decoder or encoder,
/// failed) `from` is left as it was and `to` untouched.
pub fn index_into(from: &Path, to: &Path) -> Result<(), SinkError> {
    let io = |path: &Path, action: &'static str| {
        let path = path.to_path_buf();
        move |source| SinkError::Io { path, action, source }
    };
    let rerun = |path: &Path| {
        let path = path.to_path_buf();
        move |e: &dyn std::fmt::Display| SinkError::Backend {
            what: "rerun recording",
            source: format!("{}: {e}", path.display()).into(),
        }
    };
    // Marked with this process: two runs indexing the same recording at once each write
    // their own file.
    let mut next = to.as_os_str().to_owned();
    next.push(format!(".{}.indexing", std::process::id()));
    let next = PathBuf::from(next);
    let reader = BufReader::new(std::fs::File::open(from).map_err(io(from, "read"))?);
    let writer = BufWriter::new(std::fs::File::create(&next).map_err(io(&next, "create"))?);
    let written = (|| {
        let decoder = DecoderApp::decode_eager(reader).map_err(|e| rerun(from)(&e))?;
        let mut encoder = Encoder::new_eager(CrateVersion::LOCAL, EncodingOptions::PROTOBUF_COMPRESSED, writer)
            .map_err(|e| rerun(&next)(&e))?;
        for msg in decoder {
            let msg: LogMsg = msg.map_err(|e| rerun(from)(&e))?;
            encoder.append(&msg).map_err(|e| rerun(&next)(&e))?;
        }
        encoder.finish().map_err(|e| rerun(&next)(&e))?;
        let mut writer = encoder.into_inner().map_err(|e| rerun(&next)(&e))?;
        writer.flush().map_err(io(&next, "write"))?;
        let file = writer.into_inner().map_err(|e| io(&next, "write")(e.into_error()))?;
        file.sync_all().map_err(io(&next, "write"))
    })();
    if let Err(e) = written {
        std::fs::remove_file(&next).ok();
        return Err(e);
    }
    std::fs::rename(&next, to).map_err(io(&next, "rename"))?;
    if from != to {
        std::fs::remove_file(from).map_err(io(from, "remove"))?;
    }
    Ok(())
}
