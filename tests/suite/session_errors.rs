//! Malformed sessions: each error names file, line and column and says what was expected.
//! Then a step that fails at run time: the recording keeps what came before, plus the error.

use std::path::Path;
use std::process::Command;

use drape::session::{Op, parse_session};

fn error_of(text: &str) -> String {
    match parse_session(text, "s.drape", Path::new(".")) {
        Ok(s) => panic!("accepted {text:?}: {s:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn empty_session() {
    assert_eq!(
        error_of("# only a comment\n"),
        "s.drape:1:1: empty session: expected 'drape 1' as the first statement"
    );
}

#[test]
fn missing_header() {
    assert_eq!(
        error_of("body builtin\n"),
        "s.drape:1:1: expected 'drape 1' as the first statement, found 'body'"
    );
}

#[test]
fn unsupported_version() {
    assert_eq!(
        error_of("drape 2\n"),
        "s.drape:1:7: unsupported format version '2': this drape reads version 1"
    );
}

#[test]
fn unknown_statement() {
    assert_eq!(
        error_of("drape 1\n  frobnicate y=1\n"),
        "s.drape:2:3: unknown statement 'frobnicate': expected a scene statement (drape, body, units, landmark, solver, m1, patterns, log) or a step (mannequin, section, garment, set, drag, undo, cut, nurbs, move, sculpt)"
    );
}

#[test]
fn unknown_key() {
    assert_eq!(
        error_of("drape 1\nmannequin layer=18\n"),
        "s.drape:2:11: unknown key 'layer' for 'mannequin': expected one of layers, points, subdivisions"
    );
}

#[test]
fn not_a_number() {
    assert_eq!(
        error_of("drape 1\nsection y=abc\n"),
        "s.drape:2:11: expected a number for y, found 'abc'"
    );
}

#[test]
fn not_finite() {
    assert_eq!(
        error_of("drape 1\nsection y=nan\n"),
        "s.drape:2:11: y must be finite, found 'nan'"
    );
}

#[test]
fn out_of_range() {
    assert_eq!(
        error_of("drape 1\nmannequin points=12 layers=2\n"),
        "s.drape:2:28: layers must be from 4 to 200, found 2"
    );
}

#[test]
fn unknown_units() {
    assert_eq!(
        error_of("drape 1\nunits ft\n"),
        "s.drape:2:7: unknown units 'ft': expected km, m, cm or mm"
    );
}

#[test]
fn scene_after_a_step() {
    assert_eq!(
        error_of("drape 1\nsection y=0.5\nunits m\n"),
        "s.drape:3:1: 'units' belongs to the scene and must come before the first step"
    );
}

#[test]
fn unknown_landmark() {
    assert_eq!(
        error_of("drape 1\nlandmark thumb y=1\n"),
        "s.drape:2:10: unknown landmark 'thumb': expected one of ankle, knee, crotch, hip, waist, bust, armpit, shoulder, front_neck, side_neck, neck, elbow, wrist"
    );
}

#[test]
fn landmark_point_with_two_coordinates() {
    assert_eq!(
        error_of("drape 1\nlandmark waist at=0,1\n"),
        "s.drape:2:19: expected at=x,y,z (3 numbers), found '0,1'"
    );
}

#[test]
fn landmark_point_with_a_bad_coordinate() {
    assert_eq!(
        error_of("drape 1\nlandmark waist at=0,1.0,zz\n"),
        "s.drape:2:25: expected a number for a coordinate, found 'zz'"
    );
}

#[test]
fn unterminated_string() {
    assert_eq!(
        error_of("drape 1\nbody \"my body.obj\n"),
        "s.drape:2:6: unterminated string: expected a closing '\"'"
    );
}

#[test]
fn key_given_twice() {
    assert_eq!(
        error_of("drape 1\nsection y=1 y=2\n"),
        "s.drape:2:13: 'y' is given twice"
    );
}

#[test]
fn missing_required_key() {
    assert_eq!(
        error_of("drape 1\nsection name=a   \n"),
        "s.drape:2:15: expected y=<height> for 'section'"
    );
}

#[test]
fn positional_argument() {
    assert_eq!(
        error_of("drape 1\nmannequin 18\n"),
        "s.drape:2:11: expected key=value after 'mannequin', found '18'"
    );
}

#[test]
fn body_set_twice() {
    assert_eq!(
        error_of("drape 1\nbody builtin\nbody builtin\n"),
        "s.drape:3:1: the body is already set on line 2"
    );
}

#[test]
fn a_valid_session_parses_to_typed_steps() {
    let s = parse_session(
        "drape 1 # v1\nbody \"b.obj\"\nunits cm\nlandmark waist y=0.98\n\nmannequin layers=20\nsection y=0.6 name=thigh\n",
        "ok.drape",
        Path::new("/data"),
    )
    .unwrap();
    assert_eq!(s.scene.body, drape::body::BodySource::File("/data/b.obj".into()));
    assert_eq!(s.scene.units.scale(), 0.01);
    assert_eq!(s.steps.len(), 2);
    assert_eq!((s.steps[0].line, s.steps[1].line), (6, 7));
    assert!(matches!(&s.steps[0].op, Op::Mannequin(o) if o.layers == 20 && o.points == 12));
    assert_eq!(
        s.steps[1].op,
        Op::Section {
            name: "thigh".into(),
            y: 0.6
        }
    );
}

/// The built-in demo (no session given) is the shipped file: the binary, run without a
/// session and with `assets/sessions/demo.drape` read at run time, prints the same
/// constraint network of the same garment, line for line.
#[test]
fn the_built_in_demo_is_the_shipped_session_file() {
    let network = |args: &[&str]| {
        let out = super::common::drape_cli().args(args).output().expect("drape runs");
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8(out.stdout).expect("utf-8")
    };
    let (built_in, file) = (
        network(&["constraints"]),
        network(&["constraints", "assets/sessions/demo.drape"]),
    );
    assert!(
        built_in.contains("constraint network: ") && built_in.lines().count() > 100,
        "{built_in}"
    );
    assert_eq!(built_in, file);
}

/// Runs the binary; returns (exit code, stderr).
pub(super) fn drape(args: &[&str]) -> (i32, String) {
    let out = super::common::drape_cli().args(args).output().expect("drape runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_step_failing_at_run_time_keeps_a_valid_recording_with_the_error() {
    let dir = std::env::temp_dir().join(format!("drape-fail-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("fail.drape");
    std::fs::write(
        &session,
        "drape 1\nsection y=0.5 name=ok\nsection y=5 name=too_high\nsection y=0.7\n",
    )
    .unwrap();
    let rrd = dir.join("fail.rrd");
    let metrics = dir.join("fail.json");
    let (code, stderr) = drape(&[
        "run",
        session.to_str().unwrap(),
        "--save",
        rrd.to_str().unwrap(),
        "--metrics",
        metrics.to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains(":3: step 2 (section) failed: section 'too_high' at y = 5.0000 m cuts nothing: the body spans 0.0000..1.5898 m"),
        "{stderr}"
    );
    // The file decodes completely and holds the body, the first section and the error.
    let bytes = std::fs::read(&rrd).unwrap();
    let summary = super::snapshot::summarize_rrd(&bytes);
    assert!(summary.contains("/body/mesh"), "{summary}");
    assert!(summary.contains("/section/ok"), "{summary}");
    assert!(!summary.contains("/section/too_high"), "{summary}");
    assert!(summary.contains("ERROR"), "{summary}");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&metrics).unwrap()).unwrap();
    let steps = json.as_array().unwrap();
    assert_eq!(steps.len(), 3);
    assert!(steps[2]["error"].as_str().unwrap().contains("cuts nothing"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn check_reports_a_parse_error_with_exit_code_2() {
    let dir = std::env::temp_dir().join(format!("drape-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("bad.drape");
    std::fs::write(&session, "drape 1\nmannequin layers=x\n").unwrap();
    let (code, stderr) = drape(&["check", session.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("bad.drape:2:18: expected a whole number for layers, found 'x'"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn set_needs_a_garment_first() {
    assert_eq!(
        error_of("drape 1\nset waist_girth +0.04\n"),
        "s.drape:2:1: 'set' needs a garment: put a 'garment' step before it"
    );
}

#[test]
fn unknown_dimension_names_the_template_and_the_column() {
    let e = error_of("drape 1\ngarment jumpsuit\nset wasit_girth +0.04\n");
    assert!(
        e.starts_with(
            "s.drape:3:5: unknown dimension 'wasit_girth' for the jumpsuit (did you mean 'waist_girth'?): expected one of "
        ),
        "{e}"
    );
    assert!(e.contains("waist_girth") && e.contains("inseam"), "{e}");
    assert_eq!(
        error_of("drape 1\ngarment gown\n"),
        "s.drape:2:9: unknown template 'gown': expected one of jumpsuit, dress, shirt, or mesh \"FILE\" for a garment from a file"
    );
    assert_eq!(
        error_of("drape 1\ngarment dress fit=baggy\n"),
        "s.drape:2:19: unknown fit 'baggy': expected tight or loose"
    );
}

#[test]
fn set_reads_relative_and_absolute_values() {
    let s = parse_session(
        "drape 1\ngarment jumpsuit\nset waist_girth +0.04\nset hip_girth 1.05\n",
        "s.drape",
        Path::new("."),
    )
    .unwrap();
    let changes: Vec<_> = s
        .steps
        .iter()
        .filter_map(|st| match &st.op {
            Op::Set { name, change } => Some((name.clone(), *change)),
            _ => None,
        })
        .collect();
    use drape::session::Change;
    assert_eq!(
        changes,
        vec![
            ("waist_girth".into(), Change::By(0.04)),
            ("hip_girth".into(), Change::To(1.05))
        ]
    );
}

/// The exit codes tell bad input (2), a failed step (1) and drape's own failure (3) apart.
#[test]
fn exit_codes_tell_bad_input_from_a_failed_step_from_an_internal_failure() {
    let dir = std::env::temp_dir().join(format!("drape-exit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let save = dir.join("out.rrd");
    let save = save.to_str().unwrap();
    // A body file that does not exist: bad input.
    let missing = write("missing.drape", "drape 1\n# the body:\nbody \"no/such/body.obj\"\n");
    let (code, stderr) = drape(&["run", missing.to_str().unwrap(), "--save", save]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("no/such/body.obj: cannot read"), "{stderr}");
    // The failure is placed at the `body` statement, line 3.
    assert!(stderr.contains("missing.drape:3: step 0 (scene) failed"), "{stderr}");
    // A malformed body file: bad input, with its line.
    let obj = write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    let broken = write("broken.drape", "drape 1\nbody \"broken.obj\"\n");
    let (code, stderr) = drape(&["run", broken.to_str().unwrap(), "--save", save]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains(&format!("{}:3", obj.display())), "{stderr}");
    // A section above the body: the step fails.
    let high = write("high.drape", "drape 1\nsection y=5\n");
    let (code, stderr) = drape(&["run", high.to_str().unwrap(), "--save", save]);
    assert_eq!(code, 1, "{stderr}");
    // The recording's folder cannot be made (a file is in the way): drape's own failure.
    let blocker = write("blocker", "a file, not a folder");
    let inside = blocker.join("out.rrd");
    let ok = write("ok.drape", "drape 1\n");
    let (code, stderr) = drape(&["run", ok.to_str().unwrap(), "--save", inside.to_str().unwrap()]);
    assert_eq!(code, 3, "{stderr}");
    assert!(stderr.contains("cannot create"), "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `cargo run --release` and `cargo test --release` build every shared dependency once:
/// cargo's own resolver gives each package the same features with and without the
/// dev-dependencies (`cargo tree`, offline, over the lock file).
#[test]
fn the_run_and_test_builds_share_their_dependency_features() {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    // Package to its feature sets (a package built for the host and the target appears twice).
    type Features = std::collections::BTreeMap<String, std::collections::BTreeSet<String>>;
    let tree = |extra: &[&str]| -> Features {
        let out = Command::new(&cargo)
            .args(["tree", "--offline", "--prefix", "none", "-f", "{p}|{f}"])
            .args(extra)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("cargo tree runs");
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let mut features = Features::new();
        for (p, f) in String::from_utf8_lossy(&out.stdout)
            .lines()
            .filter_map(|l| l.trim_end_matches(" (*)").split_once('|'))
        {
            features.entry(p.to_string()).or_default().insert(f.to_string());
        }
        features
    };
    let run = tree(&["-e", "no-dev"]);
    let test = tree(&[]);
    for (package, features) in &run {
        assert_eq!(
            test.get(package),
            Some(features),
            "{package}: the test build turns on other features, so it would build it again"
        );
    }
}

/// Static mistakes are caught before anything runs, with the place and the nearest valid
/// name: a misspelt control point or curve of the session's garment, a statement.
#[test]
fn check_names_misspelt_points_curves_and_statements_with_a_suggestion() {
    assert_eq!(
        error_of("drape 1\ngarment dress\ndrag hip.frnt by=0,0,0.01\n"),
        "s.drape:3:6: unknown control point 'hip.frnt' for the dress (did you mean 'hip.front'?): expected one of \
         waist.front, waist.left, waist.back, waist.right, hip.front, hip.left, hip.back, hip.right, thigh.front, \
         thigh.left, thigh.back, thigh.right, hem.front, hem.left, hem.back, hem.right"
    );
    let e = error_of("drape 1\ngarment jumpsuit\ndrag left_kne by=0,0.01,0\n");
    assert!(
        e.starts_with("s.drape:3:6: unknown curve 'left_kne' for the jumpsuit (did you mean 'left_knee'?)"),
        "{e}"
    );
    // A curve of the other template: no suggestion, the list.
    let e = error_of("drape 1\ngarment dress\ndrag left_knee by=0,0.01,0\n");
    assert!(
        e.starts_with("s.drape:3:6: unknown curve 'left_knee' for the dress: expected one of waist"),
        "{e}"
    );
    assert!(
        error_of("drape 1\nmannequn\n")
            .starts_with("s.drape:2:1: unknown statement 'mannequn' (did you mean 'mannequin'?)")
    );
    // The binary: exit code 2, the place on stderr.
    let dir = std::env::temp_dir().join(format!("drape-typo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("typo.drape");
    std::fs::write(&session, "drape 1\ngarment jumpsuit\ndrag waist.frnt by=0,0,0.01\n").unwrap();
    let (code, stderr) = drape(&["check", session.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains(
            "typo.drape:3:6: unknown control point 'waist.frnt' for the jumpsuit (did you mean 'waist.front'?)"
        ),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_style_the_template_cannot_take_is_named_at_its_column() {
    assert_eq!(
        error_of("drape 1\ngarment dress sleeves=long\n"),
        "s.drape:2:23: the dress takes no sleeves: it starts at the waist"
    );
    assert_eq!(
        error_of("drape 1\ngarment shirt sleeves=puff\n"),
        "s.drape:2:23: unknown sleeves 'puff': expected none, short or long"
    );
    assert_eq!(
        error_of("drape 1\ngarment jumpsuit collar=mandarin\n"),
        "s.drape:2:25: unknown collar 'mandarin': expected none or stand"
    );
    // A sleeve dimension is known only to a garment with sleeves.
    let e = error_of("drape 1\ngarment jumpsuit\nset cuff_girth 0.2\n");
    assert!(
        e.starts_with("s.drape:3:5: unknown dimension 'cuff_girth' for the jumpsuit"),
        "{e}"
    );
    assert!(
        error_of("drape 1\ngarment jumpsuit sleeves=long\nset cuf_girth 0.2\n").contains("did you mean 'cuff_girth'?"),
        "a sleeved jumpsuit knows its cuffs"
    );
}
