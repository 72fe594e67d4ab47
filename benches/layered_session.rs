//! Layered sessions benchmark: on every shipped body, the whole step a user waits for
//! (compute, M1 when asked, the certificates and the recording written to a file), timed
//! from one step's end to the next on one worker thread, medians of 3: a drag and a
//! dimension change of a jumpsuit worn alone beside the same edits of the jumpsuit worn
//! under a loose dress (the dress collided again and pushed out in front of it), and a
//! drag of the dress worn alone beside the same drag of the dress over the jumpsuit; with
//! the certificates after each layered step (body-inner, body-outer, inner-outer: vertices
//! inside or behind, edges through, faces pierced).
//!
//! `taskset -c 0 cargo bench --bench layered_session` prints the table; `-- --write` puts
//! it into docs/layers.md.

use std::path::Path;
use std::time::Instant;

use drape::session::{RunOptions, Stage, StageInfo, StageSink, StepEnd, parse_session, run_session};
use drape::viz::{LogOptions, RerunLogger, default_blueprint, open_file_recording};

#[path = "bodies.rs"]
mod bodies;
use bodies::shipped_bodies;
#[path = "write_figures.rs"]
mod write_figures;
use write_figures::write_block;

/// When each step ended, and its metrics.
#[derive(Default)]
struct StepClock {
    ends: Vec<Instant>,
    metrics: Vec<serde_json::Value>,
}

impl StageSink for StepClock {
    fn stage(&mut self, _info: &StageInfo, stage: Stage<'_>) -> Result<(), drape::session::SinkError> {
        if let Stage::Step(StepEnd::Done(m)) = stage {
            self.ends.push(Instant::now());
            self.metrics.push(m.to_json());
        }
        Ok(())
    }
}

/// Runs `text` on `body`, writing its recording; per step (after the scene) its whole time,
/// ms, and its metrics.
fn run(text: &str, body: &Path) -> Vec<(f64, serde_json::Value)> {
    let text = format!("drape 1\nbody \"{}\"\n{text}", body.display());
    let session = parse_session(&text, "layered-bench", Path::new(".")).expect("the session parses");
    let file = std::env::temp_dir().join(format!("drape-layered-bench-{}.rrd", std::process::id()));
    let rec = open_file_recording(&file, "layered-bench", default_blueprint()).expect("the recording");
    let mut logger = RerunLogger::new(rec, LogOptions::default().with_settle(true)).expect("the logger");
    let mut clock = StepClock::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut logger, &mut clock]);
    assert!(report.error.is_none(), "{:?}", report.error);
    drop(logger);
    let _ = std::fs::remove_file(&file);
    clock
        .ends
        .windows(2)
        .zip(clock.metrics.into_iter().skip(1))
        .map(|(w, m)| ((w[1] - w[0]).as_secs_f64() * 1e3, m))
        .collect()
}

/// Median of `runs` of `f`'s per-step times; the metrics of the last run.
fn median_steps(runs: usize, f: impl Fn() -> Vec<(f64, serde_json::Value)>) -> (Vec<f64>, Vec<serde_json::Value>) {
    let all: Vec<Vec<(f64, serde_json::Value)>> = (0..runs).map(|_| f()).collect();
    let steps = all[0].len();
    let medians = (0..steps)
        .map(|s| {
            let mut t: Vec<f64> = all.iter().map(|r| r[s].0).collect();
            t.sort_by(f64::total_cmp);
            t[t.len() / 2]
        })
        .collect();
    (medians, all[runs - 1].iter().map(|(_, m)| m.clone()).collect())
}

/// The certificates a layered step records (`worn`): body-inner, body-outer, inner-outer.
fn certificates(m: &serde_json::Value) -> String {
    ["body/inner", "body/outer", "inner/outer"]
        .map(|k| {
            let c = &m["worn"][k];
            format!(
                "{}/{}/{}",
                c["inside_or_behind"], c["edges_through"], c["faces_pierced"]
            )
        })
        .join(", ")
}

fn main() {
    drape::par::set_threads(1);
    let write = std::env::args().any(|a| a == "--write");
    let mut table = String::from(
        "| body | inner drag alone ms | layered ms | outer drag alone ms | layered ms | inner set alone ms | layered ms | certificates after the layered steps (body-inner, body-outer, inner-outer) |\n|---|---|---|---|---|---|---|---|\n",
    );
    for path in shipped_bodies() {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("?").to_string();
        let inner = "drag waist.front by=0,0,0.03\nset waist_girth +0.03\n";
        let (alone, _) = median_steps(3, || run(&format!("garment jumpsuit\n{inner}"), &path));
        let (dress, _) = median_steps(3, || {
            run("garment dress fit=loose\ndrag waist.front by=0,0,-0.05\n", &path)
        });
        let (layered, metrics) = median_steps(3, || {
            run(
                "garment jumpsuit name=inner\ngarment dress name=outer over=inner fit=loose\n\
                 drag inner:waist.front by=0,0,0.03\ndrag outer:waist.front by=0,0,-0.05\nset inner:waist_girth +0.03\n",
                &path,
            )
        });
        // Layered steps: 3 drag inner, 4 drag outer, 5 set inner (indices 2, 3, 4).
        let certificates: Vec<String> = (2..5).map(|s| certificates(&metrics[s])).collect();
        let row = format!(
            "| {name} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {} |\n",
            alone[1],
            layered[2],
            dress[1],
            layered[3],
            alone[2],
            layered[4],
            certificates.join("; ")
        );
        print!("{row}");
        table.push_str(&row);
    }
    println!("\n{table}");
    if write {
        write_block("docs/layers.md", "layered-session", &table);
    }
}
