//! Garments drape did not build: a band of the body's own surface offset outward with
//! bumps pushed into the body (made in `offset_garment`), checked and repaired by `drape
//! check-garment`; the result judged by brute force written here (ray parity for every
//! vertex, every garment edge against every body triangle, every body edge against every
//! garment face), the file compared line by line with the input; hostile inputs each a
//! named error or a reported repair; the exit codes 0, 1, 2 and 4.

use std::path::{Path, PathBuf};
use std::process::Output;

use drape::mesh::TriMesh;
use glam::DVec3;

use super::common::{brute_distance, drape_cli, faces_pierced_by, inside_by_parity, real_body};
use super::offset_garment::{offset_band, to_obj};

/// A scratch folder for this test.
pub(super) fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("drape-import-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    dir
}

/// `drape check-garment GARMENT EXTRA...`.
pub(super) fn check_garment(garment: &Path, extra: &[&str]) -> Output {
    drape_cli()
        .arg("check-garment")
        .arg(garment)
        .args(extra)
        .output()
        .expect("drape runs")
}

pub(super) fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// The `v` lines' positions and the faces' vertex triangles (fanned), read here.
pub(super) fn read_back(obj: &str) -> TriMesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for line in obj.lines() {
        let mut t = line.split_whitespace();
        match t.next() {
            Some("v") => {
                let c: Vec<f64> = t.take(3).map(|x| x.parse().expect("a number")).collect();
                positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let ids: Vec<u32> = t
                    .map(|c| c.split('/').next().expect("an index").parse::<u32>().expect("an index") - 1)
                    .collect();
                for k in 1..ids.len() - 1 {
                    triangles.push([ids[0], ids[k], ids[k + 1]]);
                }
            }
            _ => {}
        }
    }
    TriMesh { positions, triangles }
}

/// Brute-force counts: vertices inside (ray parity), body faces a garment edge passes
/// through, garment faces a body edge passes through.
pub(super) fn brute(body: &TriMesh, garment: &TriMesh) -> [usize; 3] {
    let inside = garment.positions.iter().filter(|p| inside_by_parity(body, **p)).count();
    let crossing = faces_pierced_by(garment, &body.positions, &body.triangles).len();
    let pierced = faces_pierced_by(body, &garment.positions, &garment.triangles).len();
    [inside, crossing, pierced]
}

#[test]
fn a_garment_drape_did_not_build_is_repaired_clear_and_keeps_everything_else_of_its_file() {
    let body = &real_body().mesh.mesh;
    let (band, pushed) = offset_band(body, (0.95, 1.25), 0, 0.006, (12, 0.02, 7));
    let dir = scratch("repair");
    let input = dir.join("band.obj");
    let written = to_obj(&band);
    std::fs::write(&input, &written).expect("written");
    let before = brute(body, &band);
    assert!(
        before[0] > 20 && before[1] > 0,
        "the fixture must go into the body: {before:?}"
    );
    let out = dir.join("band.repaired.obj");
    let o = check_garment(&input, &["--repair", out.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let repaired = std::fs::read_to_string(&out).expect("the repaired file");
    let after = read_back(&repaired);
    assert_eq!(brute(body, &after), [0, 0, 0], "{}", text(&o));
    // Every line but `v` and `vn` is the input's, byte for byte; a `v` line either is
    // the input's or holds other coordinates, and the vertices that moved stood, as read,
    // inside the body or within 2 cm of it (a repair does not touch the rest).
    let (a, b): (Vec<&str>, Vec<&str>) = (written.lines().collect(), repaired.lines().collect());
    assert_eq!(a.len(), b.len());
    let mut moved = Vec::new();
    let mut v = 0;
    for (x, y) in a.iter().zip(&b) {
        if x.starts_with("v ") {
            if x != y {
                moved.push(v);
            }
            v += 1;
        } else if !x.starts_with("vn ") {
            assert_eq!(x, y);
        }
    }
    for &v in &moved {
        let p = band.positions[v];
        assert!(
            inside_by_parity(body, p) || brute_distance(body, p) < 0.02,
            "vertex {} moved but stood {:.1} mm off the body",
            v + 1,
            brute_distance(body, p) * 1e3
        );
    }
    let pushed_count = pushed.iter().filter(|p| **p > 0.0).count();
    assert!(
        !moved.is_empty() && moved.len() < band.positions.len() / 2,
        "{} of {} moved",
        moved.len(),
        band.positions.len()
    );
    eprintln!(
        "{}moved {} of {} vertices ({pushed_count} pushed in)",
        text(&o),
        moved.len(),
        band.positions.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_garment_clear_as_read_exits_0_and_is_written_back_byte_for_byte() {
    let body = &real_body().mesh.mesh;
    let (band, _) = offset_band(body, (0.95, 1.25), 0, 0.01, (0, 0.0, 1));
    let dir = scratch("clear");
    let input = dir.join("clear.obj");
    let written = to_obj(&band).replace('\n', "\r\n");
    std::fs::write(&input, &written).expect("written");
    assert_eq!(brute(body, &band), [0, 0, 0], "the fixture must be clear");
    let out = dir.join("out.obj");
    let o = check_garment(&input, &["--repair", out.to_str().expect("utf-8"), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert_eq!(std::fs::read_to_string(&out).expect("written"), written);
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(report["status"], "clear");
    assert_eq!(report["moved_vertices"], 0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_inside_out_garment_with_quads_and_duplicate_seams_is_reported_and_repaired() {
    let body = &real_body().mesh.mesh;
    let (band, _) = offset_band(body, (0.95, 1.25), 0, 0.006, (12, 0.02, 7));
    // Every face reversed, a duplicate of the first vertex used by its faces (a seam
    // written twice), and two triangles joined into a quad where they share an edge.
    let mut m = band.clone();
    for t in &mut m.triangles {
        t.swap(1, 2);
    }
    let first = m.triangles[0][0];
    m.positions.push(m.positions[first as usize]);
    let twin = (m.positions.len() - 1) as u32;
    for t in m.triangles.iter_mut().filter(|t| t.contains(&first)).take(1) {
        for v in t.iter_mut() {
            if *v == first {
                *v = twin;
            }
        }
    }
    let dir = scratch("inside-out");
    let input = dir.join("inside_out.obj");
    let mut obj = to_obj(&m);
    let n = m.positions.len();
    obj.push_str(&format!(
        "v 0.2 1.1 0.2\nv 0.21 1.1 0.2\nv 0.2 1.11 0.2\ng quad\nf {} {} {} {}\n",
        n + 1,
        n + 2,
        n + 3,
        n + 3
    ));
    std::fs::write(&input, obj).expect("written");
    let out = dir.join("out.obj");
    let o = check_garment(&input, &["--repair", out.to_str().expect("utf-8")]);
    let said = text(&o);
    assert_eq!(o.status.code(), Some(1), "{said}");
    assert!(said.contains("inside out"), "{said}");
    assert!(said.contains("duplicate vertex(es) welded"), "{said}");
    assert!(said.contains("repeating a vertex left out"), "{said}");
    assert_eq!(
        brute(body, &read_back(&std::fs::read_to_string(&out).expect("out"))),
        [0, 0, 0]
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn hostile_garment_files_are_named_errors_never_panics() {
    let dir = scratch("hostile");
    let body = &real_body().mesh.mesh;
    let (band, _) = offset_band(body, (0.95, 1.25), 0, 0.006, (0, 0.0, 1));
    let mut huge = band.clone();
    for p in &mut huge.positions {
        *p *= 1000.0;
    }
    let cases: Vec<(&str, String, Vec<&str>, &str)> = vec![
        ("empty", String::new(), vec![], "no vertices"),
        (
            "nan",
            "v 0 1 0\nv nan 1 0\nv 0 1 1\nf 1 2 3\n".into(),
            vec![],
            "nan.obj:2:3: coordinate 'nan' is not finite",
        ),
        (
            "nonmanifold",
            "v 0 1 0.2\nv 0.1 1 0.2\nv 0 1.1 0.2\nv 0 0.9 0.2\nv 0.1 1.1 0.25\nf 1 2 3\nf 2 1 4\nf 1 2 5\n".into(),
            vec![],
            "shared by 3 faces (lines 6, 7, 8)",
        ),
        ("huge", to_obj(&huge), vec![], "likely in mm (give its units: units=mm)"),
        (
            "apart",
            "v 5 1 0\nv 5.1 1 0\nv 5 1.1 0\nf 1 2 3\n".into(),
            vec![],
            "does not overlap the body",
        ),
        (
            "bounded",
            format!("# {}\n", "x".repeat(1_100_000)),
            vec!["--max-input-mb", "1"],
            "more than the limit",
        ),
        (
            "badindex",
            "v 0 1 0\nv 0.1 1 0\nv 0 1.1 0\nf 1 2 7\n".into(),
            vec![],
            ":4:7: vertex index 7",
        ),
    ];
    for (name, content, extra, expected) in cases {
        let path = dir.join(format!("{name}.obj"));
        std::fs::write(&path, content).expect("written");
        let o = check_garment(&path, &extra);
        let said = text(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {said}");
        assert!(said.contains(expected), "{name}: expected '{expected}' in: {said}");
        assert!(!said.contains("panicked"), "{name}: {said}");
    }
    // Zero-area faces are reported and kept; the garment is still checked.
    let path = dir.join("zero_area.obj");
    let mut obj = to_obj(&band);
    obj.push_str("g sliver\nf 1 1 2\n");
    let n = band.positions.len();
    obj.push_str(&format!(
        "v 0.3 1.1 0.3\nv 0.31 1.1 0.3\nv 0.32 1.1 0.3\nf {} {} {}\n",
        n + 1,
        n + 2,
        n + 3
    ));
    std::fs::write(&path, obj).expect("written");
    let o = check_garment(&path, &[]);
    let said = text(&o);
    assert_eq!(o.status.code(), Some(0), "{said}");
    assert!(said.contains("1 zero-area triangle(s) kept"), "{said}");
    assert!(said.contains("1 triangle(s) repeating a vertex left out"), "{said}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_strip_through_the_whole_body_cannot_be_cleared_and_exits_4_naming_the_regions() {
    // A strip 1 m wide and 5 cm high, 100 quads, straight through the torso: its middle
    // inside the body, its ends outside on both sides; there is no way out for it.
    let dir = scratch("strip");
    let path = dir.join("strip.obj");
    let n = 100;
    let mut obj = String::new();
    for j in 0..2 {
        for i in 0..=n {
            obj += &format!("v {} {} 0.02\n", -0.5 + i as f64 / n as f64, 1.1 + 0.05 * j as f64);
        }
    }
    for i in 1..=n {
        obj += &format!("f {} {} {} {}\n", i, i + 1, n + i + 2, n + i + 1);
    }
    std::fs::write(&path, obj).expect("written");
    let o = check_garment(&path, &["--json"]);
    assert_eq!(o.status.code(), Some(4), "{}", text(&o));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(report["status"], "not_clear");
    let after = &report["after"];
    let left = after["inside_vertices"].as_u64().unwrap_or(0)
        + after["crossing_edges"].as_u64().unwrap_or(0)
        + after["pierced_faces"].as_u64().unwrap_or(0);
    assert!(
        left > 0 && !after["regions"].as_object().expect("regions").is_empty(),
        "{report}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A way of turning a body: its name, where drape's (x, y, z) goes in the file, `--up`,
/// `--front`, and what the refusal says.
type Turn = (
    &'static str,
    fn(DVec3) -> DVec3,
    &'static str,
    &'static str,
    &'static str,
);

#[test]
fn a_body_and_garment_in_other_axes_are_refused_by_name_and_checked_alike_once_the_axes_are_given() {
    let body = &real_body().mesh.mesh;
    let (band, _) = offset_band(body, (0.95, 1.25), 0, 0.006, (12, 0.02, 7));
    let dir = scratch("axes");
    let write = |name: &str, mesh: &TriMesh| {
        let path = dir.join(name);
        let mut s = String::new();
        for p in &mesh.positions {
            s += &format!("v {} {} {}\n", p.x, p.y, p.z);
        }
        for t in &mesh.triangles {
            s += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
        }
        std::fs::write(&path, s).expect("written");
        path
    };
    let counts = |o: &Output| -> Vec<serde_json::Value> {
        let r: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
        ["inside_vertices", "crossing_edges", "pierced_faces"]
            .iter()
            .flat_map(|k| [r["before"][k].clone(), r["after"][k].clone()])
            .collect()
    };
    let plain = check_garment(
        &write("band.obj", &band),
        &["--body", write("body.obj", body).to_str().expect("utf-8"), "--json"],
    );
    assert_eq!(plain.status.code(), Some(1), "{}", text(&plain));
    // Each: where drape's (x, y, z) goes in the file, the flags that say so, the hint.
    let turns: [Turn; 4] = [
        ("z_up", |p| DVec3::new(p.x, -p.z, p.y), "z", "-y", "--up z"),
        ("on_its_head", |p| DVec3::new(-p.x, -p.y, p.z), "-y", "z", "--up -y"),
        ("facing_back", |p| DVec3::new(-p.x, p.y, -p.z), "y", "-z", "--front -z"),
        ("facing_x", |p| DVec3::new(p.z, p.y, -p.x), "y", "x", "--front +x"),
    ];
    for (name, turn, up, front, hint) in turns {
        let moved = |m: &TriMesh| TriMesh {
            positions: m.positions.iter().map(|p| turn(*p)).collect(),
            triangles: m.triangles.clone(),
        };
        let (b, g) = (moved(body), moved(&band));
        let body_path = write(&format!("body_{name}.obj"), &b);
        let garment_path = write(&format!("band_{name}.obj"), &g);
        let refused = check_garment(&garment_path, &["--body", body_path.to_str().expect("utf-8")]);
        assert_eq!(refused.status.code(), Some(2), "{name}: {}", text(&refused));
        assert!(
            text(&refused).contains(hint),
            "{name}: expected '{hint}' in {}",
            text(&refused)
        );
        let out = dir.join(format!("out_{name}.obj"));
        let o = check_garment(
            &garment_path,
            &[
                "--body",
                body_path.to_str().expect("utf-8"),
                &format!("--up={up}"),
                &format!("--front={front}"),
                "--json",
                "--repair",
                out.to_str().expect("utf-8"),
            ],
        );
        assert_eq!(o.status.code(), Some(1), "{name}: {}", text(&o));
        assert_eq!(counts(&o), counts(&plain), "{name}");
        let repaired = read_back(&std::fs::read_to_string(&out).expect("out"));
        assert_eq!(brute(&b, &repaired), [0, 0, 0], "{name}: the file's own frame");
    }
    std::fs::remove_dir_all(&dir).ok();
}
