//! SIGINT in the middle of a run: the run ends after the current step with exit code 130,
//! and the recording holds every finished step, decodes to its end (its footer written)
//! and says where it stopped.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};

#[test]
fn sigint_mid_run_leaves_a_recording_that_verifies_and_holds_the_finished_steps() {
    let dir = std::env::temp_dir().join(format!("drape-sigint-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("long.drape");
    let mut text = String::from("drape 1\ngarment jumpsuit resolution=3\n");
    for _ in 0..400 {
        text.push_str("set waist_girth +0.0005\n");
    }
    std::fs::write(&session, text).unwrap();
    let rrd = dir.join("long.rrd");
    let mut child = super::common::drape_cli()
        .args(["run", session.to_str().unwrap(), "--save", rrd.to_str().unwrap()])
        .stderr(Stdio::piped())
        .spawn()
        .expect("drape starts");
    let stderr = child.stderr.take().expect("stderr");
    let mut lines = BufReader::new(stderr).lines();
    // Wait until step 3 is done, then interrupt.
    let mut seen = Vec::new();
    for line in lines.by_ref() {
        let line = line.expect("utf-8");
        let done = line.contains("step 3 set") && line.contains("done");
        seen.push(line);
        if done {
            break;
        }
    }
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
    seen.extend(lines.map(|l| l.expect("utf-8")));
    let code = child.wait().expect("drape ends").code();
    let all = seen.join("\n");
    assert_eq!(code, Some(130), "{all}");
    let after: usize = all
        .lines()
        .find_map(|l| l.strip_prefix("interrupted after step "))
        .and_then(|rest| rest.split(':').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no 'interrupted after step' line: {all}"));
    assert!((3..401).contains(&after), "stopped after step {after}");
    // The file decodes to its end, every message whole, and holds the stop and every
    // finished step's end.
    let bytes = std::fs::read(&rrd).expect("the recording was written (not left .partial)");
    let summary = super::snapshot::summarize_rrd(&bytes);
    assert!(
        summary.contains(&format!("interrupted by a signal after step {after}")),
        "{summary}"
    );
    for step in 1..=after {
        assert!(summary.contains(&format!("step {step} (")), "step {step} missing");
    }
    assert!(!summary.contains(&format!("step {} (", after + 1)));
    // Rerun's own verifier agrees.
    let out = super::common::rerun_cli()
        .args(["rrd", "verify", rrd.to_str().unwrap()])
        .output()
        .expect("rerun runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).ok();
}
