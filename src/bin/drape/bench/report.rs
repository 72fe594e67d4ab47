//! `drape bench`'s report: Markdown tables (and the same figures as JSON), and the splice of
//! the report into a page's generated section.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context as _, bail};
use drape::bench::median;
use serde_json::{Value, json};

use super::Measured;
use super::steps::{STAGES, SessionRun, StepTimes, growth};

#[derive(Clone, Copy, PartialEq)]
enum Op {
    Drag,
    Set,
}

impl Op {
    fn name(self) -> &'static str {
        match self {
            Self::Drag => "drag",
            Self::Set => "set",
        }
    }

    fn steps(self, run: &SessionRun) -> &[StepTimes] {
        match self {
            Self::Drag => &run.drags,
            Self::Set => &run.sets,
        }
    }
}

/// The median step of kind `op` over every run.
fn step(runs: &[SessionRun], op: Op) -> StepTimes {
    let all: Vec<StepTimes> = runs.iter().flat_map(|r| op.steps(r).iter().cloned()).collect();
    StepTimes::median(&all)
}

/// M1's stages of a step (select, subdivide, collide).
fn m1_ms(s: &StepTimes) -> f64 {
    STAGES
        .iter()
        .zip(&s.stages)
        .filter(|((name, _), _)| name.starts_with("M1"))
        .map(|(_, ms)| ms)
        .sum()
}

/// The report, Markdown.
pub(crate) fn markdown(m: &Measured, resolutions: &[usize]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Measured by `drape bench --runs {}` on this machine ({} core(s)); one thread is pinned to one core \
(`taskset -c 0`). Every figure is a median over every step of every run.\n",
        m.runs, m.cores
    );
    goals(&mut out, m);
    step_table(&mut out, m, resolutions);
    peers_table(&mut out, m);
    growth_table(&mut out, m);
    out.trim_end().to_string()
}

fn sessions(m: &Measured, r: usize, t: usize) -> &[SessionRun] {
    m.sessions.get(&(r, t)).map_or(&[], Vec::as_slice)
}

fn goals(out: &mut String, m: &Measured) {
    let _ = writeln!(out, "#### Against the goals (one core)\n");
    let _ = writeln!(out, "| what | measured | goal | met |\n|---|---:|---|---|");
    let mut row = |what: &str, v: f64, goal: f64, unit: &str, lower: bool| {
        let sign = if lower { "<=" } else { ">=" };
        if v.is_nan() {
            let _ = writeln!(out, "| {what} | not measured | {sign} {goal} {unit} | - |");
            return;
        }
        let met = if (lower && v <= goal) || (!lower && v >= goal) {
            "yes"
        } else {
            "no"
        };
        let _ = writeln!(out, "| {what} | {v:.2} {unit} | {sign} {goal} {unit} | {met} |");
    };
    let drag24 = step(sessions(m, 24, 1), Op::Drag);
    let drag6 = step(sessions(m, 6, 1), Op::Drag);
    let set24 = step(sessions(m, 24, 1), Op::Set);
    row("whole drag step, resolution 24", drag24.whole, 33.0, "ms", true);
    row("whole drag step, resolution 6", drag6.whole, 8.0, "ms", true);
    row("`set`, resolution 24, whole step", set24.whole, 60.0, "ms", true);
    row("M1 after a drag, resolution 24", m1_ms(&drag24), 8.0, "ms", true);
    row("logging a drag, resolution 24", drag24.logging, 10.0, "ms", true);
    if let Some(ratio) = detect_over_best_peer(m, 24, 1) {
        row(
            "cold detection over the best peer, resolution 24",
            ratio,
            0.2,
            "x",
            true,
        );
    }
    if m.cores > 1 {
        let one = step(sessions(m, 24, 1), Op::Set).compute;
        let all = step(sessions(m, 24, m.cores), Op::Set).compute;
        row(
            &format!(
                "`set` compute at resolution 24, {} threads against 1 (the goal is for 8)",
                m.cores
            ),
            one / all,
            4.0,
            "x",
            false,
        );
    }
    out.push('\n');
}

fn step_table(out: &mut String, m: &Measured, resolutions: &[usize]) {
    let _ = writeln!(
        out,
        "#### The whole step, per stage (the demo's drags and `set`s, ms)\n"
    );
    let mut header = String::from("| resolution | M0 vertices | step | threads |");
    for (name, _) in STAGES {
        let _ = write!(header, " {name} |");
    }
    header.push_str(" other compute | compute | logging | whole step |");
    let _ = writeln!(
        out,
        "{header}\n|---:|---:|---|---:|{}",
        "---:|".repeat(STAGES.len() + 4)
    );
    for &r in resolutions {
        for op in [Op::Drag, Op::Set] {
            for (&(_, t), runs) in m.sessions.iter().filter(|((rr, _), _)| *rr == r) {
                let s = step(runs, op);
                let vertices = runs.first().map_or(0, |x| x.m0_vertices);
                let cells: Vec<String> = s
                    .stages
                    .iter()
                    .chain([&s.other, &s.compute, &s.logging, &s.whole])
                    .map(|v| format!("{:.1}", v + 0.0))
                    .collect(); // + 0.0: an empty sum is -0.0
                let _ = writeln!(
                    out,
                    "| {r} | {vertices} | {} | {t} | {} |",
                    op.name(),
                    cells.join(" | ")
                );
            }
        }
    }
    out.push('\n');
}

/// drape's cold detection per vertex over the fastest peer's same question, at resolution
/// `r` on `t` threads.
fn detect_over_best_peer(m: &Measured, r: usize, t: usize) -> Option<f64> {
    let q = m.queries.get(&t)?.garments.iter().find(|g| g.resolution == r)?;
    let p = m.peers.get(&t)?.as_ref().ok()?.get(format!("res{r}"))?;
    let best = ["fcpw_us", "open3d_us", "libigl_us"]
        .iter()
        .filter_map(|k| p.get(*k)?.as_f64())
        .fold(f64::INFINITY, f64::min);
    best.is_finite().then(|| q.detect_us / best)
}

fn us(v: Option<&Value>) -> String {
    v.and_then(Value::as_f64).map_or("-".into(), |x| format!("{x:.3}"))
}

fn count(v: Option<&Value>) -> String {
    v.and_then(Value::as_u64).map_or("-".into(), |x| x.to_string())
}

fn peers_table(out: &mut String, m: &Measured) {
    let _ = writeln!(
        out,
        "#### Detection beside the peers (the same points and body, the same question: is the vertex inside, or nearer than the ease?)\n"
    );
    let _ = writeln!(
        out,
        "| garment | vertices | threads | drape cold detection, us/vertex | drape exact signed distance, us/vertex | FCPW capped closest + contains, us | Open3D signed distance, us | libigl signed distance, us | drape over the best peer | inside verdicts differing from drape (FCPW, Open3D, libigl) |"
    );
    let _ = writeln!(out, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    let mut notes = Vec::new();
    for (t, q) in &m.queries {
        let peers = m.peers.get(t);
        if let Some(Err(e)) = peers {
            notes.push(format!("Peers on {t} thread(s) not measured: {e}"));
        }
        let peers = peers.and_then(|p| p.as_ref().ok());
        if let Some(errors) = peers.and_then(|p| p.get("errors")).and_then(Value::as_object) {
            notes.extend(
                errors
                    .iter()
                    .map(|(k, v)| format!("{k} on {t} thread(s) not measured: {v}")),
            );
        }
        for g in &q.garments {
            let p = peers.and_then(|p| p.get(format!("res{}", g.resolution)));
            let get = |k: &str| p.and_then(|p| p.get(k));
            let ratio = detect_over_best_peer(m, g.resolution, *t).map_or("-".into(), |r| format!("{r:.2}x"));
            let _ = writeln!(
                out,
                "| M0 resolution {} | {} | {t} | {:.3} | {:.3} | {} | {} | {} | {ratio} | {}, {}, {} |",
                g.resolution,
                g.vertices,
                g.detect_us,
                g.signed_us,
                us(get("fcpw_us")),
                us(get("open3d_us")),
                us(get("libigl_us")),
                count(get("fcpw_differ")),
                count(get("open3d_differ")),
                count(get("libigl_differ"))
            );
        }
    }
    if m.peers.is_empty() {
        notes.push("Peers not measured (--no-peers).".into());
    }
    for n in notes {
        let _ = writeln!(out, "\n{n}");
    }
    out.push('\n');
}

fn growth_table(out: &mut String, m: &Measured) {
    let _ = writeln!(
        out,
        "#### Growth (one core): time against size, with the exponent k of the best fit `time = c n^k`\n"
    );
    let _ = writeln!(out, "| against | sizes | what | ms | growth |\n|---|---|---|---|---|");
    let garment: Vec<(f64, &[SessionRun])> = m
        .sessions
        .iter()
        .filter(|((_, t), _)| *t == 1)
        .map(|(_, runs)| (runs.first().map_or(0.0, |r| r.m0_vertices as f64), runs.as_slice()))
        .collect();
    let sizes = |xs: &[f64]| xs.iter().map(|x| format!("{x:.0}")).collect::<Vec<_>>().join(", ");
    let mut line = |against: &str, xs: &[f64], what: &str, ys: &[f64]| {
        let points: Vec<(f64, f64)> = xs.iter().copied().zip(ys.iter().copied()).collect();
        let times = ys.iter().map(|y| format!("{y:.1}")).collect::<Vec<_>>().join(", ");
        let _ = writeln!(
            out,
            "| {against} | {} | {what} | {times} | {} |",
            sizes(xs),
            growth(&points)
        );
    };
    let xs: Vec<f64> = garment.iter().map(|g| g.0).collect();
    for (what, f) in [
        ("drag compute", (|s: &StepTimes| s.compute) as fn(&StepTimes) -> f64),
        ("drag logging", |s| s.logging),
        ("drag, whole step", |s| s.whole),
    ] {
        let ys: Vec<f64> = garment.iter().map(|g| f(&step(g.1, Op::Drag))).collect();
        line("garment vertices (M0)", &xs, what, &ys);
    }
    if let Some(q) = m.queries.get(&1) {
        let xs: Vec<f64> = q.garments.iter().map(|g| g.vertices as f64).collect();
        let ys: Vec<f64> = q
            .garments
            .iter()
            .map(|g| g.detect_us * g.vertices as f64 / 1e3)
            .collect();
        line("garment vertices (M0)", &xs, "cold detection of every vertex", &ys);
        let xs: Vec<f64> = q.bodies.iter().map(|b| b.triangles as f64).collect();
        let ys: Vec<f64> = q
            .bodies
            .iter()
            .map(|b| b.signed_us * q.garments.last().map_or(0.0, |g| g.vertices as f64) / 1e3)
            .collect();
        line(
            "body triangles (split flat)",
            &xs,
            "exact signed distance of the largest M0",
            &ys,
        );
        let ys: Vec<f64> = q.bodies.iter().map(|b| b.index_ms).collect();
        line(
            "body triangles (split flat)",
            &xs,
            "body index build (one partition)",
            &ys,
        );
    }
    let xs: Vec<f64> = m.bodies.iter().map(|b| b.1 as f64).collect();
    let r = m.body_resolution;
    for (what, f) in [
        (
            format!("the demo at resolution {r}: drag compute"),
            (|s: &StepTimes| s.compute) as fn(&StepTimes) -> f64,
        ),
        (format!("the demo at resolution {r}: drag, whole step"), |s| s.whole),
    ] {
        let ys: Vec<f64> = m.bodies.iter().map(|b| f(&step(&b.2, Op::Drag))).collect();
        line("body triangles (split)", &xs, &what, &ys);
    }
    let ys: Vec<f64> = m
        .bodies
        .iter()
        .map(|b| median(b.2.iter().map(|r| r.body_ms).collect()))
        .collect();
    line(
        "body triangles (split)",
        &xs,
        "the body's load (landmarks, partitions, rings, index)",
        &ys,
    );
}

/// Every figure as JSON.
pub(crate) fn json(m: &Measured) -> Value {
    let sessions: Vec<Value> = m
        .sessions
        .iter()
        .map(|((r, t), runs)| {
            json!({"resolution": r, "threads": t, "m0_vertices": runs.first().map(|x| x.m0_vertices),
                   "drag": step(runs, Op::Drag), "set": step(runs, Op::Set)})
        })
        .collect();
    let bodies: Vec<Value> = m
        .bodies
        .iter()
        .map(|(f, tris, runs)| json!({"factor": f, "triangles": tris, "drag": step(runs, Op::Drag), "body_ms": median(runs.iter().map(|r| r.body_ms).collect())}))
        .collect();
    let peers: serde_json::Map<String, Value> = m
        .peers
        .iter()
        .map(|(t, p)| (t.to_string(), p.clone().unwrap_or_else(|e| json!({"error": e}))))
        .collect();
    json!({"runs": m.runs, "cores": m.cores, "stages": STAGES.map(|s| s.0), "sessions": sessions, "bodies": bodies,
           "queries": m.queries.values().collect::<Vec<_>>(), "peers": peers})
}

/// Where `page`'s section `name` begins and ends (the byte ranges of its two markers' ends).
fn section(page: &Path, name: &str) -> anyhow::Result<(String, usize, usize)> {
    let text = std::fs::read_to_string(page).with_context(|| format!("cannot read {}", page.display()))?;
    let (open, close) = (
        format!("<!-- figures:{name} -->\n"),
        format!("<!-- /figures:{name} -->"),
    );
    let (Some(a), Some(b)) = (text.find(&open), text.find(&close)) else {
        bail!("{} has no section {}...{close}", page.display(), open.trim_end());
    };
    if b < a {
        bail!("{}: {close} comes before {}", page.display(), open.trim_end());
    }
    Ok((text, a + open.len(), b))
}

/// Checks that `page` can take the section `name` (before a long measurement).
pub(crate) fn check_page(page: &Path, name: &str) -> anyhow::Result<()> {
    section(page, name).map(|_| ())
}

/// Writes `body` into `page` between `<!-- figures:NAME -->` and `<!-- /figures:NAME -->`.
pub(crate) fn splice(page: &Path, name: &str, body: &str) -> anyhow::Result<()> {
    let (text, start, end) = section(page, name)?;
    let new = format!("{}{}\n{}", &text[..start], body.trim_matches('\n'), &text[end..]);
    crate::files::write_atomic(page, new.as_bytes())
}
