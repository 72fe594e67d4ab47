//! The peers, asked the question drape's detection answers on the points it exported: FCPW
//! (closest point capped at the ease, plus `contains`), Open3D's RaycastingScene (signed
//! distance, Embree) and libigl (signed distance, pseudo-normal signs), in their own Python
//! (a venv of pinned versions that `--make-peers` makes).

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context as _, bail};
use serde_json::Value;

/// The peers' Python code (one process per core setting).
const PEERS_PY: &str = include_str!("peers.py");

/// The pinned peer packages.
pub(crate) const PACKAGES: [&str; 4] = ["numpy==2.4.6", "fcpw==1.2.0", "libigl==2.6.3", "open3d-cpu==0.20.0"];

/// The peers' venv: ~/.cache/drape-tools/peers.
pub(crate) fn default_venv() -> Option<PathBuf> {
    std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache/drape-tools/peers"))
}

/// The Python to run the peers with: `given`, else the venv's, made first with `make`.
pub(crate) fn python(given: Option<&Path>, make: bool) -> anyhow::Result<PathBuf> {
    if let Some(p) = given {
        return Ok(p.to_path_buf());
    }
    let venv = default_venv().context("no HOME: give --peers-python")?;
    let py = venv.join("bin/python");
    if py.exists() {
        return Ok(py);
    }
    if !make {
        bail!(
            "the peers' Python is not there ({}): run `drape bench --make-peers` once (python3 -m venv, then pip install {}), give --peers-python, or --no-peers",
            py.display(),
            PACKAGES.join(" ")
        );
    }
    eprintln!("bench: making the peers' venv in {} ...", venv.display());
    let status = Command::new("python3")
        .arg("-m")
        .arg("venv")
        .arg(&venv)
        .status()
        .context("cannot run python3")?;
    if !status.success() {
        bail!("python3 -m venv {} failed ({status})", venv.display());
    }
    let status = Command::new(&py)
        .args(["-m", "pip", "install", "-q"])
        .args(PACKAGES)
        .status()
        .context("cannot run the venv's pip")?;
    if !status.success() {
        bail!(
            "pip install {} failed ({status}); Open3D also needs the system's libusb-1.0",
            PACKAGES.join(" ")
        );
    }
    Ok(py)
}

/// Runs the peers on `names` (resN) of `folder` with `nthreads` threads (0: all), pinned
/// to core 0 by `pin` (taskset) for one.
pub(crate) fn run(
    python: &Path,
    pin: Option<&Path>,
    folder: &Path,
    names: &[String],
    nthreads: usize,
) -> anyhow::Result<Value> {
    let script = folder.join("peers.py");
    std::fs::write(&script, PEERS_PY).with_context(|| format!("cannot write {}", script.display()))?;
    let mut cmd = match pin {
        Some(taskset) => {
            let mut c = Command::new(taskset);
            c.arg("-c").arg("0").arg(python);
            c
        }
        None => Command::new(python),
    };
    cmd.arg(&script)
        .arg(folder)
        .arg(names.join(","))
        .arg(nthreads.to_string());
    let out = cmd
        .output()
        .with_context(|| format!("cannot run {}", python.display()))?;
    if !out.status.success() {
        bail!(
            "the peers failed ({}): {}",
            out.status,
            String::from_utf8_lossy(&out.stderr).lines().last().unwrap_or("")
        );
    }
    serde_json::from_slice(&out.stdout).context("the peers did not print JSON")
}
