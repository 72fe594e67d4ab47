//! A dress worn over a jumpsuit, on every shipped body, with drags on both and a dimension
//! of the inner changed, then undone. Judged on the meshes the session exports after every
//! step, by brute forces written in the tests: the body against each garment (ray parity
//! for the vertices, every edge against every face both ways), and the two garments
//! against each other (every edge against every face both ways, and outer vertices behind
//! the inner surface by its nearest triangle, the inner turned away from the body by a vote
//! of its faces against the nearest body vertex). Undo is judged byte for byte against the
//! files of the steps it goes back to.

use std::path::{Path, PathBuf};

use drape::mesh::TriMesh;
use glam::DVec3;

use super::common::{drape_cli, shipped_bodies};
use super::import::{brute, read_back, scratch};
use super::layers::{behind_by_brute, brute_crossings};

/// The session: inner and outer, a drag of each, a dimension of the inner, two undos.
fn session(body: &Path) -> String {
    format!(
        "drape 1\nbody \"{}\"\ngarment jumpsuit name=inner\ngarment dress name=outer over=inner fit=loose\n\
         drag inner:waist.front by=0,0,0.03\ndrag outer:waist.front by=0,0,-0.05\nset inner:waist_girth +0.03\n\
         undo\nundo\n",
        body.display()
    )
}

/// `mesh` with its faces turned, all together, to face away from the body: the area-weighted
/// vote of its faces against the direction from the nearest body vertex.
fn away_from(body: &TriMesh, mut mesh: TriMesh) -> TriMesh {
    let vote: f64 = mesh
        .triangles
        .iter()
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

/// The file of `garment`'s M0 the session holds after `step`: the last one written at or
/// before it.
fn current(dir: &Path, garment: &str, step: usize) -> Option<PathBuf> {
    (1..=step)
        .rev()
        .map(|s| dir.join(format!("step{s:02}_{garment}_m0.obj")))
        .find(|p| p.exists())
}

fn read(path: &Path) -> TriMesh {
    read_back(&std::fs::read_to_string(path).expect("an exported mesh"))
}

#[test]
fn a_dress_over_a_jumpsuit_stays_in_front_of_it_and_clear_of_the_body_through_every_edit_on_every_body() {
    for path in shipped_bodies() {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("?").to_string();
        let dir = scratch(&format!("layered-{name}"));
        let file = dir.join("layered.drape");
        std::fs::write(&file, session(&std::fs::canonicalize(&path).expect("the body"))).expect("written");
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
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{name}: {stderr}");
        let steps: Vec<serde_json::Value> =
            serde_json::from_str(&std::fs::read_to_string(&metrics).expect("metrics")).expect("JSON");
        let body = read(&export.join("step00_body.obj"));
        // The outer as first built went through the inner: the push had work to do.
        let first = &steps[2]["outer"]["over"]["inner"]["m0"]["before"];
        assert!(
            first["outer_edges_through_inner"].as_u64().unwrap_or(0) > 0,
            "{name}: the loose dress must cross the jumpsuit before its push: {first}"
        );
        for step in 2..steps.len() {
            let refused = steps[step].get("refused").is_some()
                || steps[step].get("outer").and_then(|o| o.get("refused")).is_some();
            let (Some(i), Some(o)) = (current(&export, "inner", step), current(&export, "outer", step)) else {
                panic!("{name}: step {step}: both garments exported");
            };
            let (inner, outer) = (away_from(&body, read(&i)), read(&o));
            let counts = [
                brute(&body, &inner),
                brute(&body, &outer),
                [
                    behind_by_brute(&inner, &outer),
                    brute_crossings(&inner, &outer),
                    brute_crossings(&outer, &inner),
                ],
            ];
            eprintln!(
                "{name}: step {step} ({}){}: body-inner, body-outer, inner-outer {counts:?}",
                steps[step]["op"],
                if refused { " refused" } else { "" }
            );
            assert_eq!(counts, [[0; 3]; 3], "{name}: step {step}");
        }
        // The two undos: step 6 takes back the change of the inner (and the push of the
        // outer it made), step 7 the drag of the outer.
        // Byte for byte but the header comment (which names the step).
        let body_of = |p: &Path| -> Vec<String> {
            std::fs::read_to_string(p)
                .expect("an exported mesh")
                .lines()
                .filter(|l| !l.starts_with('#'))
                .map(str::to_string)
                .collect()
        };
        let same = |a: PathBuf, b: PathBuf| body_of(&a) == body_of(&b);
        for (undo, back_to) in [(6, 4), (7, 3)] {
            for garment in ["inner", "outer"] {
                let (Some(a), Some(b)) = (current(&export, garment, undo), current(&export, garment, back_to)) else {
                    panic!("{name}: {garment} exported");
                };
                assert!(
                    same(a.clone(), b.clone()),
                    "{name}: undo at step {undo}: {} is not {}",
                    a.display(),
                    b.display()
                );
            }
        }
    }
}
