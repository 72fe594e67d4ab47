//! `drape bench` on the smallest case: its report goes into a page's section and nowhere
//! else, and a page without the section is refused before anything is measured, untouched.

use std::path::Path;

/// The smallest bench: resolution 3, one run, the body as it is, no peers.
fn bench(page: &Path, json: &Path) -> std::process::Output {
    super::common::drape_cli()
        .args([
            "bench",
            "--runs",
            "1",
            "--resolutions",
            "3",
            "--body-factors",
            "1",
            "--no-peers",
            "--write",
        ])
        .arg(page)
        .arg("--json")
        .arg(json)
        .output()
        .expect("drape runs")
}

/// The report lands between the page's markers: the text before and after is byte for
/// byte what it was, the section holds the printed report, and the JSON holds a drag and a
/// `set` row of the demo at resolution 3 with its M0 (637 vertices, as the docs' tables and
/// `cargo bench --bench speed` give it) on one thread and on every core.
#[test]
fn drape_bench_writes_its_report_into_the_section_and_leaves_the_rest_of_the_page() {
    let dir = std::env::temp_dir().join(format!("drape-bench-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let (before, after) = ("# A page\n\nText before, kept.\n\n", "\nText after, kept.\n");
    let page = dir.join("page.md");
    std::fs::write(
        &page,
        format!("{before}<!-- figures:bench -->\nold figures\n<!-- /figures:bench -->{after}"),
    )
    .expect("writes the page");
    let json = dir.join("bench.json");
    let out = bench(&page, &json);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&page).expect("the page");
    let report = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        text,
        format!(
            "{before}<!-- figures:bench -->\n{}\n<!-- /figures:bench -->{after}",
            report.trim()
        ),
        "the page changes only between its markers"
    );
    assert!(report.contains("| 3 | 637 | drag | 1 |"), "{report}");
    assert!(
        report.contains("| whole drag step, resolution 24 | not measured |"),
        "{report}"
    );
    let figures: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("the JSON")).expect("JSON");
    let sessions = figures["sessions"].as_array().expect("sessions");
    assert!(
        sessions.iter().any(|s| s["threads"] == 1 && s["m0_vertices"] == 637),
        "{sessions:?}"
    );
    for s in sessions {
        for op in ["drag", "set"] {
            // Each step's whole is its compute plus its logging, so the median whole is at
            // least either median.
            let whole = s[op]["whole"].as_f64().expect("a whole step");
            let (compute, logging) = (
                s[op]["compute"].as_f64().expect("compute"),
                s[op]["logging"].as_f64().expect("logging"),
            );
            assert!(
                compute > 0.0 && logging > 0.0 && whole >= compute && whole >= logging,
                "{op}: {whole} {compute} {logging}"
            );
        }
    }
    // A page without the section: refused, and left as it was.
    let plain = dir.join("plain.md");
    std::fs::write(&plain, before).expect("writes the page");
    let out = bench(&plain, &dir.join("plain.json"));
    assert!(!out.status.success(), "a page without the section is refused");
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("has no section"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(std::fs::read_to_string(&plain).expect("the page"), before);
    std::fs::remove_dir_all(&dir).ok();
}
