//! The whole step a user waits for: the demo session run by this same binary (`drape run
//! --metrics`, its recording written to a file as a user's is), pinned to one core for one
//! thread, and each drag's and `set`'s stages read from its metrics.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context as _, bail};
use drape::bench::{growth_exponent, median};
use serde_json::Value;

/// The columns of a step row: a name and the timing keys (prefixes) it sums.
pub(crate) const STAGES: [(&str, &[&str]); 6] = [
    ("solve", &["constraints.", "garment.solve"]),
    ("assemble", &["garment.assemble"]),
    ("M0 collision", &["collision."]),
    ("M1 select", &["m1.select"]),
    ("M1 subdivide", &["m1.subdivide"]),
    ("M1 collide", &["m1.collide"]),
];

/// One step's figures, ms: each of [`STAGES`], then the rest of the compute, the compute,
/// the logging and the whole step.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub(crate) struct StepTimes {
    pub(crate) stages: Vec<f64>,
    pub(crate) other: f64,
    pub(crate) compute: f64,
    pub(crate) logging: f64,
    pub(crate) whole: f64,
}

impl StepTimes {
    fn of(timings: &serde_json::Map<String, Value>) -> Self {
        let ms = |k: &str| timings.get(k).and_then(Value::as_f64).unwrap_or(0.0);
        let compute_keys: Vec<&String> = timings.keys().filter(|k| !k.starts_with("log.")).collect();
        let stages: Vec<f64> = STAGES
            .iter()
            .map(|(_, prefixes)| {
                compute_keys
                    .iter()
                    .filter(|k| prefixes.iter().any(|p| k.starts_with(p)))
                    .map(|k| ms(k))
                    .sum()
            })
            .collect();
        let compute: f64 = compute_keys.iter().map(|k| ms(k)).sum();
        let logging: f64 = timings.keys().filter(|k| k.starts_with("log.")).map(|k| ms(k)).sum();
        Self {
            other: (compute - stages.iter().sum::<f64>()).max(0.0),
            stages,
            compute,
            logging,
            whole: compute + logging,
        }
    }

    /// The median of each figure over `rows` (NaN for none).
    pub(crate) fn median(rows: &[Self]) -> Self {
        let med = |f: &dyn Fn(&Self) -> f64| median(rows.iter().map(f).collect());
        Self {
            stages: (0..STAGES.len()).map(|i| med(&|r: &Self| r.stages[i])).collect(),
            other: med(&|r| r.other),
            compute: med(&|r| r.compute),
            logging: med(&|r| r.logging),
            whole: med(&|r| r.whole),
        }
    }
}

/// What one run of a session gave: its drags' and `set`s' times (the steps that made an
/// M1), the garment's M0 vertices, and the body's load (analysis and index, every `body.`
/// stage), ms.
#[derive(Clone, Debug, Default)]
pub(crate) struct SessionRun {
    pub(crate) drags: Vec<StepTimes>,
    pub(crate) sets: Vec<StepTimes>,
    pub(crate) m0_vertices: usize,
    pub(crate) body_ms: f64,
}

/// How a session is run: this binary, where its files go, and how it is pinned.
pub(crate) struct Runner {
    pub(crate) exe: PathBuf,
    pub(crate) folder: PathBuf,
    /// `taskset`, to pin one-thread runs to one core.
    pub(crate) taskset: PathBuf,
}

impl Runner {
    /// A command of this binary on `threads` worker threads, pinned to core 0 for one.
    pub(crate) fn command(&self, threads: usize) -> Command {
        let mut cmd = if threads == 1 {
            let mut c = Command::new(&self.taskset);
            c.arg("-c").arg("0").arg(&self.exe);
            c
        } else {
            Command::new(&self.exe)
        };
        cmd.arg("--threads").arg(threads.to_string());
        cmd
    }

    /// Runs `session` (with `body` instead of its own, if given) on `threads` and reads its
    /// metrics. The body index is built every run (no cache), as on a body seen first.
    pub(crate) fn run(&self, session: &Path, body: Option<&Path>, threads: usize) -> anyhow::Result<SessionRun> {
        let metrics = self.folder.join("metrics.json");
        let mut cmd = self.command(threads);
        cmd.arg("--no-index-cache").arg("run").arg(session);
        if let Some(body) = body {
            cmd.arg("--body").arg(body);
        }
        cmd.arg("--metrics")
            .arg(&metrics)
            .arg("--save")
            .arg(self.folder.join("run.rrd"));
        let out = cmd
            .output()
            .with_context(|| format!("cannot start {}", self.exe.display()))?;
        if !out.status.success() {
            bail!(
                "`drape run {}` failed ({}): {}",
                session.display(),
                out.status,
                String::from_utf8_lossy(&out.stderr).lines().last().unwrap_or("")
            );
        }
        let text = std::fs::read_to_string(&metrics).with_context(|| format!("cannot read {}", metrics.display()))?;
        let steps: Vec<Value> = serde_json::from_str(&text).context("the run's metrics are not a JSON list")?;
        Ok(read_run(&steps))
    }
}

fn read_run(steps: &[Value]) -> SessionRun {
    let mut out = SessionRun::default();
    for step in steps {
        let Some(timings) = step.get("timings_ms").and_then(Value::as_object) else {
            continue;
        };
        let count = |k: &str| step.get(k).and_then(Value::as_u64).map(|v| v as usize);
        if let Some(n) = count("m0_vertices") {
            out.m0_vertices = out.m0_vertices.max(n);
        }
        out.body_ms += timings
            .iter()
            .filter(|(k, _)| k.starts_with("body."))
            .filter_map(|(_, v)| v.as_f64())
            .sum::<f64>();
        if !timings.contains_key("m1.select") {
            continue;
        }
        match step.get("op").and_then(Value::as_str) {
            Some("drag") => out.drags.push(StepTimes::of(timings)),
            Some("set") => out.sets.push(StepTimes::of(timings)),
            _ => {}
        }
    }
    out
}

/// The demo session at `resolution`.
pub(crate) fn demo_at(resolution: usize) -> anyhow::Result<String> {
    let demo = drape::session::DEMO_SESSION;
    let from = "resolution=6";
    if demo.matches(from).count() != 1 {
        bail!("the demo session does not set its garment's resolution once ({from})");
    }
    Ok(demo.replace(from, &format!("resolution={resolution}")))
}

/// The growth exponent of `(size, ms)` pairs as text ("n^0.41 (n^0.78 between the two
/// largest)": a fixed cost flattens the fit over every size), "-" when it cannot be fitted.
pub(crate) fn growth(points: &[(f64, f64)]) -> String {
    let Some(all) = growth_exponent(points) else {
        return "-".into();
    };
    match points.len() {
        0..=2 => format!("n^{all:.2}"),
        n => growth_exponent(&points[n - 2..]).map_or(format!("n^{all:.2}"), |last| {
            format!("n^{all:.2} (n^{last:.2} between the two largest)")
        }),
    }
}
