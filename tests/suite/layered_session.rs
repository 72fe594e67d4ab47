//! A dress worn over a jumpsuit, and a shirt under a loose, larger shirt with sleeves (M1
//! made for both), on every shipped body, with drags on both and a dimension changed, then
//! undone. Judged on the meshes the session exports after every
//! step, by brute forces written in the tests: the body against each garment (ray parity
//! for the vertices, every edge against every face both ways), and the two garments
//! against each other (every edge against every face both ways, and outer vertices behind
//! the inner surface by its nearest triangle, the inner turned away from the body by a vote
//! of its faces against the nearest body vertex). Undo is judged byte for byte against the
//! files of the steps it goes back to.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use drape::mesh::TriMesh;
use glam::DVec3;

use super::common::{drape_cli, shipped_bodies};
use super::import::{brute, read_back, scratch};
use super::layers::{behind_by_brute, brute_crossings};

/// `mesh` with its faces turned, all together, to face away from the body: the area-weighted
/// vote of its faces against the direction from the nearest body vertex.
fn away_from(body: &TriMesh, mut mesh: TriMesh) -> TriMesh {
    // Every 16th face votes: the orientation is the whole mesh's, one way or the other.
    let vote: f64 = mesh
        .triangles
        .iter()
        .step_by(16)
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let centre = (a + b + c) / 3.0;
            let nearest = body
                .positions
                .iter()
                .min_by(|p, q| p.distance_squared(centre).total_cmp(&q.distance_squared(centre)))
                .copied()
                .unwrap_or(DVec3::ZERO);
            (b - a).cross(c - a).dot(centre - nearest)
        })
        .sum();
    if vote < 0.0 {
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
    }
    mesh
}

/// The dress over the jumpsuit: a drag of each, a dimension of the inner, two undos (step
/// 6 takes back the change of the inner and the push of the outer it made, step 7 the drag
/// of the outer).
const DRESS: &str = "garment jumpsuit name=inner\ngarment dress name=outer over=inner fit=loose\n\
     drag inner:waist.front by=0,0,0.03\ndrag outer:waist.front by=0,0,-0.05\nset inner:waist_girth +0.03\n\
     undo\nundo\n";

/// The shirt under a jacket-like shirt, M1 made for both: the outer made larger, a drag of
/// each, then the drag of the outer undone (step 6 back to step 4).
const SHIRTS: &str = "garment shirt sleeves=long name=inner\ngarment shirt sleeves=long fit=loose name=outer over=inner\n\
     set outer:waist_girth +0.06\ndrag inner:waist.front by=0,0,0.03\ndrag outer:waist.front by=0,0,-0.05\nundo\n";

/// The file of `garment`'s `mesh` (`m0`, `m1`) the session holds after `step`: the last one
/// written at or before it.
fn current(dir: &Path, (garment, mesh): (&str, &str), step: usize) -> Option<PathBuf> {
    (1..=step)
        .rev()
        .map(|s| dir.join(format!("step{s:02}_{garment}_{mesh}.obj")))
        .find(|p| p.exists())
}

fn read(path: &Path) -> TriMesh {
    read_back(&std::fs::read_to_string(path).expect("an exported mesh"))
}

/// Lines of an exported mesh but its header comment (which names the step).
fn lines_of(p: &Path) -> Vec<String> {
    std::fs::read_to_string(p)
        .expect("an exported mesh")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(str::to_string)
        .collect()
}

/// Runs the session `file` with the binary (metrics only in the recording), exporting its
/// meshes into `dir/export`; returns that folder and the steps' metrics.
fn run_exported(file: &Path, dir: &Path, name: &str) -> (PathBuf, Vec<serde_json::Value>) {
    let (export, metrics) = (dir.join("export"), dir.join("metrics.json"));
    let o = drape_cli()
        .args([
            "run",
            file.to_str().expect("utf-8"),
            "--log-detail",
            "metrics",
            "--save",
        ])
        .arg(dir.join("layered.rrd"))
        .arg("--export")
        .arg(&export)
        .arg("--metrics")
        .arg(&metrics)
        .output()
        .expect("drape runs");
    assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
    let figures = serde_json::from_str(&std::fs::read_to_string(&metrics).expect("metrics")).expect("JSON");
    (export, figures)
}

/// Runs `steps` (with `m1` in the scene when `meshes` has it) on every shipped body and
/// judges every step's `meshes` of the two garments; `undos` pairs a step with the one
/// whose garments it must give back, byte for byte.
fn judge(label: &str, steps: &str, meshes: &[&str], undos: &[(usize, usize)]) {
    for path in shipped_bodies() {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("?").to_string();
        let dir = scratch(&format!("layered-{label}-{name}"));
        let file = dir.join("layered.drape");
        let scene = format!(
            "drape 1\nbody \"{}\"\n{}",
            std::fs::canonicalize(&path).expect("the body").display(),
            if meshes.contains(&"m1") { "m1\n" } else { "" }
        );
        std::fs::write(&file, format!("{scene}{steps}")).expect("written");
        let (export, figures) = run_exported(&file, &dir, &name);
        let body = read(&export.join("step00_body.obj"));
        // The outer as first built went through the inner: the push had work to do.
        let first = &figures[2]["outer"]["over"]["inner"]["m0"]["before"];
        assert!(
            first["outer_edges_through_inner"].as_u64().unwrap_or(0) > 0,
            "{name}: the outer must cross the inner before its push: {first}"
        );
        // Counts by file (a garment a step did not change keeps its file from before).
        let mut on_body: BTreeMap<PathBuf, [usize; 3]> = BTreeMap::new();
        let mut between: BTreeMap<(PathBuf, PathBuf), [usize; 3]> = BTreeMap::new();
        for (step, figure) in figures.iter().enumerate().skip(2) {
            for mesh in meshes {
                let (Some(i), Some(o)) = (
                    current(&export, ("inner", mesh), step),
                    current(&export, ("outer", mesh), step),
                ) else {
                    panic!("{name}: step {step}: both garments' {mesh} exported");
                };
                let (inner, outer) = (away_from(&body, read(&i)), read(&o));
                let mut against_body =
                    |p: &PathBuf, m: &TriMesh| *on_body.entry(p.clone()).or_insert_with(|| brute(&body, m));
                let counts = [
                    against_body(&i, &inner),
                    against_body(&o, &outer),
                    *between.entry((i.clone(), o.clone())).or_insert_with(|| {
                        [
                            behind_by_brute(&inner, &outer),
                            brute_crossings(&inner, &outer),
                            brute_crossings(&outer, &inner),
                        ]
                    }),
                ];
                eprintln!(
                    "{name}: step {step} ({}{}), {mesh}: body-inner, body-outer, inner-outer {counts:?}",
                    figure["op"],
                    if figure.get("refused").is_some() {
                        ", refused"
                    } else {
                        ""
                    }
                );
                assert_eq!(counts, [[0; 3]; 3], "{name}: step {step}, {mesh}");
            }
        }
        for &(undo, back_to) in undos {
            for garment in ["inner", "outer"] {
                for mesh in meshes {
                    let (Some(a), Some(b)) = (
                        current(&export, (garment, mesh), undo),
                        current(&export, (garment, mesh), back_to),
                    ) else {
                        panic!("{name}: {garment} exported");
                    };
                    assert!(
                        lines_of(&a) == lines_of(&b),
                        "{name}: undo at step {undo}: {} is not {}",
                        a.display(),
                        b.display()
                    );
                }
            }
        }
    }
}

#[test]
fn a_dress_over_a_jumpsuit_stays_in_front_of_it_and_clear_of_the_body_through_every_edit_on_every_body() {
    judge("dress", DRESS, &["m0"], &[(6, 4), (7, 3)]);
}

#[test]
fn a_shirt_under_a_larger_loose_shirt_stays_behind_it_on_m0_and_m1_through_every_edit_on_every_body() {
    judge("shirts", SHIRTS, &["m0", "m1"], &[(6, 4)]);
}

/// The parse error of `steps` after a scene with the built-in body.
fn error_of(steps: &str) -> String {
    match drape::session::parse_session(&format!("drape 1\n{steps}"), "s.drape", Path::new(".")) {
        Ok(s) => panic!("accepted {steps:?}: {:?}", s.steps),
        Err(e) => e.to_string(),
    }
}

#[test]
fn layers_that_cannot_be_worn_or_garments_that_are_not_worn_are_named_at_their_place() {
    for (steps, at, message) in [
        (
            "garment dress over=inner\n",
            "s.drape:2:",
            "over=inner needs a garment to be worn over: put a 'garment' step before this one",
        ),
        (
            "garment jumpsuit name=inner\ngarment dress over=coat\n",
            "s.drape:3:",
            "no garment 'coat' to wear this over: the garments worn are inner",
        ),
        (
            "garment jumpsuit name=a\ngarment dress name=b over=a\ngarment shirt over=a\n",
            "s.drape:4:",
            "'a' is under 'b' already: a garment goes over the outermost one (over=b)",
        ),
        (
            "garment jumpsuit\ngarment jumpsuit over=jumpsuit\n",
            "s.drape:3:",
            "a garment named 'jumpsuit' is worn already: give this one another name (name=...)",
        ),
        (
            "garment jumpsuit name=inner\ndrag outer:waist.front by=0,0,0.01\n",
            "s.drape:3:",
            "no garment 'outer': the garments worn are inner",
        ),
        (
            "garment jumpsuit name=inner\ngarment shirt name=top over=inner\ndrag left_knee by=0,0,0.01\n",
            "s.drape:4:",
            "unknown curve 'left_knee' for the shirt",
        ),
        (
            "garment jumpsuit name=inner\nsculpt at=coat:waist.front radius=0.08 peak=0.02\n",
            "s.drape:3:",
            "no garment 'coat': the garments worn are inner",
        ),
    ] {
        let e = error_of(steps);
        assert!(e.starts_with(at) && e.contains(message), "{steps:?}: {e}");
    }
    // A garment replaced by one not worn over it takes its name with it.
    let e = error_of("garment jumpsuit name=inner\ngarment dress\nset inner:waist_girth +0.01\n");
    assert!(e.contains("no garment 'inner': the garments worn are dress"), "{e}");
}

#[test]
fn an_edit_naming_its_garment_is_checked_against_that_garment_and_the_bare_one_works_on_the_outermost() {
    use drape::constraint::Edit;
    use drape::session::Op;
    let session = drape::session::parse_session(
        "drape 1\ngarment jumpsuit name=inner\ngarment shirt name=top over=inner\n\
         drag inner:left_knee by=0,0,0.01\nset inner:waist_girth +0.02\ndrag waist.front by=0,0,0.01\n\
         sculpt at=inner:waist.front radius=0.08 peak=0.02\n",
        "s.drape",
        Path::new("."),
    )
    .expect("parses");
    let named: Vec<(Option<&str>, &Op)> = session.steps.iter().map(|s| (s.garment.as_deref(), &s.op)).collect();
    assert!(matches!(named[2], (Some("inner"), Op::Drag(Edit::Curve { name, .. })) if name == "left_knee"));
    assert!(matches!(named[3], (Some("inner"), Op::Set { name, .. }) if name == "waist_girth"));
    assert!(matches!(named[4], (None, Op::Drag(Edit::Point { name, .. })) if name == "waist.front"));
    assert!(
        matches!(named[5], (Some("inner"), Op::Sculpt { at: drape::session::SculptAt::Control(c), .. }) if c == "waist.front")
    );
    match &session.steps[1].op {
        Op::Garment { layer, .. } => {
            assert_eq!((layer.name.as_str(), layer.over.as_deref()), ("top", Some("inner")));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn sculpts_of_either_layer_keep_them_in_order_on_the_heavy_older_body() {
    // The dress sculpted in towards the jumpsuit, then the jumpsuit sculpted out into the
    // dress: the sculpted meshes (each garment's latest) judged as the others are.
    let path = std::fs::canonicalize("assets/bodies/female-old-heavy.obj").expect("the body");
    let dir = scratch("layered-sculpts");
    let file = dir.join("sculpts.drape");
    std::fs::write(
        &file,
        format!(
            "drape 1\nbody \"{}\"\nm1\n{}sculpt at=outer:waist.front radius=0.1 peak=-0.04\n\
             sculpt at=inner:waist.front radius=0.1 peak=0.04\n",
            path.display(),
            "garment jumpsuit name=inner\ngarment dress name=outer over=inner fit=loose\n"
        ),
    )
    .expect("written");
    let (export, figures) = run_exported(&file, &dir, "female-old-heavy");
    for step in [3, 4] {
        assert!(figures[step].get("refused").is_none(), "step {step}: {}", figures[step]);
    }
    // The dress's sculpt went into the jumpsuit before its push.
    let before = &figures[3]["outer"]["over"]["inner"]["latest"]["before"];
    assert!(before["behind"].as_u64().unwrap_or(0) > 0, "{before}");
    let body = read(&export.join("step00_body.obj"));
    let inner = away_from(&body, read(&export.join("step04_garment_sculpt.obj")));
    let outer = read(&current(&export, ("outer", "sculpt"), 4).expect("the dress's sculpt"));
    assert_eq!(
        [
            brute(&body, &inner),
            brute(&body, &outer),
            [
                behind_by_brute(&inner, &outer),
                brute_crossings(&inner, &outer),
                brute_crossings(&outer, &inner)
            ]
        ],
        [[0; 3]; 3]
    );
}
