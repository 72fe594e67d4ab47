//! Two runs writing the same recording at once: each writes its own temporary file beside
//! the recording and renames a whole one into place, so both succeed and the file left is
//! whole (the last one renamed), with no temporary file left behind.

use std::process::Stdio;

#[test]
fn two_runs_saving_the_same_recording_at_once_both_succeed_and_leave_a_whole_file() {
    let dir = std::env::temp_dir().join(format!("drape-concurrent-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("same.drape");
    let text = "drape 1\ngarment jumpsuit resolution=3\nset waist_girth +0.01\nset waist_girth -0.01\n";
    std::fs::write(&session, text).unwrap();
    let rrd = dir.join("same.rrd");
    let spawn = || {
        super::common::drape_cli()
            .args(["run", session.to_str().unwrap(), "--save", rrd.to_str().unwrap()])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("drape starts")
    };
    let (a, b) = (spawn(), spawn());
    for run in [a, b] {
        let out = run.wait_with_output().expect("drape ends");
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    // The file left decodes to its end and holds the last step; Rerun's verifier agrees.
    let bytes = std::fs::read(&rrd).expect("the recording is there");
    let summary = super::snapshot::summarize_rrd(&bytes);
    assert!(summary.contains("step 3 ("), "{summary}");
    let out = super::common::rerun_cli()
        .args(["rrd", "verify", rrd.to_str().unwrap()])
        .output()
        .expect("rerun runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["same.drape", "same.rrd"], "no temporary file left");
    std::fs::remove_dir_all(&dir).ok();
}
