//! `drape bench`: the whole edit step a user waits for, per resolution and per stage, on
//! one core and on every core; detection beside the peers asked the same question in the
//! same run; and how the step grows with the garment's vertices and the body's triangles.
//!
//! Data flow: [`steps`] runs the demo session with this same binary (`drape run
//! --metrics`) at each resolution, and on the built-in body split 4x and 16x; [`queries`]
//! measures the collision's queries in a child process of this binary (pinned like the
//! runs) and exports the points; [`peers`] asks FCPW, Open3D and libigl the same question on
//! them; [`report`] turns it all into Markdown (and `--write` into a page's generated
//! section).

mod peers;
mod queries;
mod report;
mod steps;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::Args;

use steps::{Runner, SessionRun, demo_at};

/// `drape bench`'s arguments.
#[derive(Args, Debug)]
pub(crate) struct BenchArgs {
    /// Runs of each session and of each query; every figure is the median over every step
    /// of every run.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub(crate) runs: u32,
    /// The garment resolutions of the step table, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "3,6,12,24", value_parser = clap::value_parser!(u32).range(1..=64))]
    pub(crate) resolutions: Vec<u32>,
    /// The body's triangles multiplied by these (each a power of 4: every triangle split in
    /// four, the same surface) for the scaling against body triangles; the demo runs on each
    /// at the largest resolution, on one core.
    #[arg(long, value_delimiter = ',', default_value = "1,4,16", value_parser = power_of_four)]
    pub(crate) body_factors: Vec<usize>,
    /// The Python that runs the peers (numpy, fcpw, libigl and open3d-cpu installed)
    /// [default: ~/.cache/drape-tools/peers/bin/python].
    #[arg(long, value_name = "PYTHON")]
    pub(crate) peers_python: Option<PathBuf>,
    /// Make the peers' venv (~/.cache/drape-tools/peers, pinned versions) when it is missing.
    #[arg(long)]
    pub(crate) make_peers: bool,
    /// Leave the peers out.
    #[arg(long, conflicts_with_all = ["peers_python", "make_peers"])]
    pub(crate) no_peers: bool,
    /// Write the report into the generated section `figures:bench` of this page (for
    /// example docs/performance.md); nothing else in the page changes.
    #[arg(long, value_name = "PAGE")]
    pub(crate) write: Option<PathBuf>,
    /// Also write every figure as JSON.
    #[arg(long, value_name = "PATH")]
    pub(crate) json: Option<PathBuf>,
    /// (internal) Measure the queries in this process, export the points into
    /// --export-to, and write the figures as JSON here.
    #[arg(long, hide = true, value_name = "PATH", requires = "export_to")]
    pub(crate) queries_json: Option<PathBuf>,
    /// (internal) Where --queries-json exports the points.
    #[arg(long, hide = true, value_name = "DIR")]
    pub(crate) export_to: Option<PathBuf>,
}

fn power_of_four(text: &str) -> Result<usize, String> {
    let n: usize = text.parse().map_err(|_| format!("'{text}' is not a whole number"))?;
    let mut p = 1;
    while p < n && p <= 1 << 20 {
        p *= 4;
    }
    if p == n {
        Ok(n)
    } else {
        Err(format!("{n} is not a power of 4 (1, 4, 16, 64)"))
    }
}

/// Everything one `drape bench` measured.
pub(crate) struct Measured {
    pub(crate) runs: usize,
    pub(crate) cores: usize,
    /// (resolution, threads) -> each run.
    pub(crate) sessions: BTreeMap<(usize, usize), Vec<SessionRun>>,
    /// (body factor, body triangles) -> each run, one thread, at the largest resolution.
    pub(crate) bodies: Vec<(usize, usize, Vec<SessionRun>)>,
    pub(crate) body_resolution: usize,
    /// threads -> the queries.
    pub(crate) queries: BTreeMap<usize, queries::Queries>,
    /// threads -> the peers' JSON, or why there is none.
    pub(crate) peers: BTreeMap<usize, Result<serde_json::Value, String>>,
}

/// `drape bench`.
pub(crate) fn bench(args: &BenchArgs) -> anyhow::Result<()> {
    // In increasing order, each once: the growth tables read the last as the largest.
    let mut resolutions: Vec<usize> = args.resolutions.iter().map(|&r| r as usize).collect();
    resolutions.sort_unstable();
    resolutions.dedup();
    let runs = args.runs as usize;
    if let Some(out) = &args.queries_json {
        let export = args.export_to.as_deref().context("--queries-json needs --export-to")?;
        let q = queries::measure(&resolutions, &args.body_factors, runs.max(5), export)?;
        std::fs::write(export.join("ease.txt"), format!("{}", q.ease)).context("cannot write the ease")?;
        return std::fs::write(out, serde_json::to_vec_pretty(&q)?)
            .with_context(|| format!("cannot write {}", out.display()));
    }
    if resolutions.is_empty() {
        bail!("--resolutions is empty");
    }
    if let Some(page) = &args.write {
        report::check_page(page, "bench")?;
    }
    let taskset = which("taskset")
        .context("drape bench pins its one-core runs with taskset (util-linux), which is not on the PATH")?;
    let python = if args.no_peers {
        None
    } else {
        Some(peers::python(args.peers_python.as_deref(), args.make_peers)?)
    };
    let folder = std::env::temp_dir().join(format!("drape-bench-{}", std::process::id()));
    std::fs::create_dir_all(&folder).with_context(|| format!("cannot create {}", folder.display()))?;
    let runner = Runner {
        exe: std::env::current_exe().context("cannot find this program")?,
        folder: folder.clone(),
        taskset: taskset.clone(),
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get()).min(16);
    let threads: Vec<usize> = if cores > 1 { vec![1, cores] } else { vec![1] };
    let result = measure(args, &runner, (&resolutions, &threads), python.as_deref(), runs);
    let _ = std::fs::remove_dir_all(&folder);
    let measured = result?;
    let text = report::markdown(&measured, &resolutions);
    println!("{text}");
    if let Some(page) = &args.write {
        report::splice(page, "bench", &text)?;
        eprintln!("bench: {} rewritten (figures:bench)", page.display());
    }
    if let Some(path) = &args.json {
        crate::files::write_atomic(path, serde_json::to_string_pretty(&report::json(&measured))?.as_bytes())?;
    }
    Ok(())
}

fn measure(
    args: &BenchArgs,
    runner: &Runner,
    (resolutions, threads): (&[usize], &[usize]),
    python: Option<&Path>,
    runs: usize,
) -> anyhow::Result<Measured> {
    let folder = &runner.folder;
    let total = runs * resolutions.len() * threads.len() + runs * args.body_factors.len();
    let mut done = 0;
    let mut sessions: BTreeMap<(usize, usize), Vec<SessionRun>> = BTreeMap::new();
    for run in 0..runs {
        for &r in resolutions {
            let session = folder.join(format!("demo-{r}.drape"));
            std::fs::write(&session, demo_at(r)?).context("cannot write the session")?;
            for &t in threads {
                done += 1;
                eprintln!(
                    "bench: [{done}/{total}] the demo at resolution {r}, {t} thread(s), run {} of {runs}",
                    run + 1
                );
                sessions.entry((r, t)).or_default().push(runner.run(&session, None, t)?);
            }
        }
    }
    let body_resolution = resolutions.iter().copied().max().unwrap_or(6);
    let session = folder.join(format!("demo-{body_resolution}.drape"));
    let base = queries::builtin_body()?.mesh;
    let mut bodies = Vec::new();
    for &factor in &args.body_factors {
        let mesh = queries::split_by(&base, factor);
        let path = folder.join(format!("body-{factor}x.obj"));
        let header = format!("the built-in body, each triangle split into {factor}");
        std::fs::write(&path, drape::mesh::obj::write_obj(&mesh, &header)).context("cannot write the split body")?;
        let mut got = Vec::new();
        for run in 0..runs {
            done += 1;
            eprintln!(
                "bench: [{done}/{total}] the demo at resolution {body_resolution} on the body split {factor}x ({} triangles), 1 thread, run {} of {runs}",
                mesh.triangles.len(),
                run + 1
            );
            got.push(runner.run(&session, Some(&path), 1)?);
        }
        bodies.push((factor, mesh.triangles.len(), got));
    }
    let mut queries = BTreeMap::new();
    let mut peer_figures = BTreeMap::new();
    for &t in threads {
        eprintln!("bench: the queries on {t} thread(s)");
        let export = folder.join(format!("export-{t}"));
        let out = folder.join(format!("queries-{t}.json"));
        let mut cmd = runner.command(t);
        cmd.arg("bench")
            .arg("--queries-json")
            .arg(&out)
            .arg("--export-to")
            .arg(&export)
            .arg("--runs")
            .arg(runs.to_string());
        cmd.arg("--resolutions")
            .arg(join(resolutions))
            .arg("--body-factors")
            .arg(join(&args.body_factors));
        let status = cmd.status().context("cannot run the queries")?;
        if !status.success() {
            bail!("the queries on {t} thread(s) failed ({status})");
        }
        let q: queries::Queries = serde_json::from_slice(&std::fs::read(&out)?).context("the queries' JSON")?;
        queries.insert(t, q);
        if let Some(py) = python {
            eprintln!("bench: the peers on {t} thread(s)");
            let names: Vec<String> = resolutions.iter().map(|r| format!("res{r}")).collect();
            let pin = (t == 1).then_some(runner.taskset.as_path());
            let nthreads = if t == 1 { 1 } else { 0 };
            peer_figures.insert(
                t,
                peers::run(py, pin, &export, &names, nthreads).map_err(|e| format!("{e:#}")),
            );
        }
    }
    Ok(Measured {
        runs,
        cores: *threads.last().unwrap_or(&1),
        sessions,
        bodies,
        body_resolution,
        queries,
        peers: peer_figures,
    })
}

fn join<T: ToString>(values: &[T]) -> String {
    values.iter().map(ToString::to_string).collect::<Vec<_>>().join(",")
}

/// The first `name` on the PATH.
fn which(name: &str) -> Option<PathBuf> {
    std::env::split_paths(&std::env::var_os("PATH")?)
        .map(|d| d.join(name))
        .find(|p| p.is_file())
}
