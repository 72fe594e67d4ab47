//! Files written through a temporary name and a rename, so a failure never leaves half a
//! file where a good one was.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use drape::session::Session;

/// Writes `bytes` to `path` through a temporary file and a rename.
pub(crate) fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let tmp = partial_path(path);
    std::fs::write(&tmp, bytes).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("cannot rename {} to {}", tmp.display(), path.display()))
}

/// The temporary name `path` is written under before its rename: beside it, marked with
/// this process, so that two runs writing the same file at once each write their own and
/// each rename a whole file into place (the last one stays), never one the other half wrote
/// or already moved.
pub(crate) fn partial_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(format!(".{}.partial", std::process::id()));
    path.with_file_name(name)
}

/// Puts the recording written at `partial` (closed, without its index) at `path` with Rerun's
/// index ([`drape::viz::rrd_index`]). Where indexing fails, the recording still takes its
/// name without the index (the data are complete; `rerun rrd optimize` adds one), with a
/// warning.
pub(crate) fn finish_recording(partial: &Path, path: &Path) -> crate::failure::Result<()> {
    use crate::failure::Classify as _;
    if let Err(e) = drape::viz::rrd_index::index_into(partial, path) {
        eprintln!(
            "warning: {e}; {} keeps the recording without its index (`rerun rrd optimize` adds one)",
            path.display()
        );
        std::fs::rename(partial, path)
            .with_context(|| format!("cannot rename {} to {}", partial.display(), path.display()))
            .internal()?;
    }
    Ok(())
}

pub(crate) fn create_parent(path: &Path) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    Ok(())
}

/// Writes a study's recording to `path` (through a temporary name and a rename): one stage,
/// `stage` named `name` of step 1 `op`, logged with `options` under `blueprint`.
pub(crate) fn save_study(
    path: &Path,
    (op, name): (&'static str, &'static str),
    blueprint: drape::viz::Blueprint,
    options: drape::viz::LogOptions,
    stage: drape::session::Stage<'_>,
) -> anyhow::Result<()> {
    use drape::session::StageSink as _;
    let partial = partial_path(path);
    create_parent(path)?;
    {
        let rec = drape::viz::open_file_recording(&partial, op, blueprint)?;
        let mut logger = drape::viz::RerunLogger::new(rec, options)?;
        let info = drape::session::StageInfo {
            step: 1,
            op,
            stage: 0,
            name,
            layer: None,
        };
        logger.stage(&info, stage)?;
    }
    std::fs::rename(&partial, path)
        .with_context(|| format!("cannot rename {} to {}", partial.display(), path.display()))?;
    eprintln!("recording: {}", path.display());
    Ok(())
}

pub(crate) fn session_stem(session: &Session) -> String {
    Path::new(&session.name)
        .file_stem()
        .map_or_else(|| "session".into(), |s| s.to_string_lossy().into_owned())
}

pub(crate) fn host_name() -> String {
    std::env::var("HOSTNAME")
        .ok()
        .or_else(|| std::fs::read_to_string("/etc/hostname").ok())
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "localhost".into())
}
