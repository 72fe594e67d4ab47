//! A garment from a file as a session's garment (`garment mesh`): on every shipped body, a
//! band of the body's surface with bumps pushed into it, collided, refined into M1,
//! sculpted and cut in a session run by `drape run`; the exported files judged by the brute
//! force of `import` (ray parity, every edge against every face both ways) and compared
//! line by line with the input; the steps a file garment cannot take refused by name.

use std::path::{Path, PathBuf};

use drape::body::{BodyMesh, BodySource};

use super::common::{drape_cli, real_body, shipped_bodies};
use super::import::{brute, read_back, scratch, text};
use super::offset_garment::{offset_band, to_obj};

/// The newest file in `dir` whose name ends with `suffix` (files are `stepNN_...`).
pub(super) fn last_export(dir: &Path, suffix: &str) -> PathBuf {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("the export folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_str().is_some_and(|s| s.ends_with(suffix)))
        .collect();
    found.sort();
    found
        .pop()
        .unwrap_or_else(|| panic!("no *{suffix} in {}", dir.display()))
}

/// Runs `SESSION` (written to `dir/band.drape`) with `drape run --strict`, its recording
/// saved to `dir/band.rrd` and its meshes exported to `dir/out` (returned).
pub(super) fn run_session(dir: &Path, session: &str) -> (std::process::Output, PathBuf) {
    std::fs::write(dir.join("band.drape"), session).expect("written");
    let out = dir.join("out");
    let o = drape_cli()
        .arg("run")
        .arg(dir.join("band.drape"))
        .args(["--strict", "--log-detail", "metrics", "--save"])
        .arg(dir.join("band.rrd"))
        .arg("--export")
        .arg(&out)
        .output()
        .expect("drape runs");
    (o, out)
}

#[test]
fn a_garment_mesh_step_is_collided_refined_sculpted_and_cut_and_exported_as_its_file_on_every_body() {
    for (k, path) in shipped_bodies().iter().enumerate() {
        let loaded = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("the body loads");
        let body = &loaded.mesh;
        let (lo, hi) = body.bounds().expect("a body");
        let h = hi.y - lo.y;
        // The band of the body's surface from 62% to 80% of its height (above the hands of
        // an A pose), 6 mm out, twelve bumps up to 2 cm into the body.
        let (band, _) = offset_band(body, (lo.y + 0.62 * h, lo.y + 0.80 * h), 0, 0.006, (12, 0.02, 7));
        let dir = scratch(&format!("session{k}"));
        let written = to_obj(&band);
        std::fs::write(dir.join("band.obj"), &written).expect("written");
        // The sculpt pushes the band's frontmost vertex 1 cm towards the body.
        let front = band
            .positions
            .iter()
            .copied()
            .max_by(|a, b| a.z.total_cmp(&b.z))
            .expect("a vertex");
        let session = format!(
            "drape 1\nbody \"{}\"\nm1\ngarment mesh \"band.obj\" name=band ease=0.003\n\
             cut chest at=0,{:.3},0 normal=0,1,0\nsculpt at={:.4},{:.4},{:.4} radius=0.05 peak=0.01 dir=0,0,-1\n",
            std::fs::canonicalize(path).expect("the body's path").display(),
            front.y + 0.03,
            front.x,
            front.y,
            front.z
        );
        let (o, out) = run_session(&dir, &session);
        let name = path.display();
        assert_eq!(o.status.code(), Some(0), "{name}: {}", text(&o));
        // M0 is the file written back: every line but `v` and `vn` the input's, the `v`
        // lines of the vertices the collision did not move the input's, byte for byte.
        let m0_text = std::fs::read_to_string(last_export(&out, "_band_m0.obj")).expect("M0");
        let (a, b): (Vec<&str>, Vec<&str>) = (written.lines().collect(), m0_text.lines().collect());
        assert_eq!(a.len(), b.len());
        let mut moved = 0;
        for (x, y) in a.iter().zip(&b) {
            if x.starts_with("v ") {
                moved += usize::from(x != y);
            } else if !x.starts_with("vn ") {
                assert_eq!(x, y, "{name}");
            }
        }
        assert!(moved > 0 && moved < band.positions.len() / 2, "{name}: {moved} moved");
        let m0 = read_back(&m0_text);
        assert_eq!(brute(body, &m0), [0, 0, 0], "{name}: M0 after the step");
        // M1 refines M0 where the selection rules say, and is clear too.
        let m1 = read_back(&std::fs::read_to_string(last_export(&out, "_band_m1.obj")).expect("M1"));
        assert!(
            m1.positions.len() > m0.positions.len(),
            "{name}: M1 refines some region: {} against {} vertices",
            m1.positions.len(),
            m0.positions.len()
        );
        assert_eq!(brute(body, &m1), [0, 0, 0], "{name}: M1");
        // The sculpt pushed into the body and was stopped there, clear.
        let sculpted = read_back(&std::fs::read_to_string(last_export(&out, "_sculpt.obj")).expect("the sculpt"));
        let nearest = sculpted
            .positions
            .iter()
            .map(|p| p.distance(front))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest > 1e-4, "{name}: the sculpt moved the picked point");
        assert_eq!(brute(body, &sculpted), [0, 0, 0], "{name}: the sculpted mesh");
        eprintln!(
            "{name}: {} vertices, {moved} moved; M1 {} vertices",
            band.positions.len(),
            m1.positions.len()
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}

#[test]
fn a_garment_mesh_refuses_drags_and_sets_and_names_a_bad_file() {
    let dir = scratch("session-errors");
    let cases = [
        (
            "garment mesh \"band.obj\"\ndrag waist.front by=0,0,0.01\n",
            "5:1: 'drag' needs a garment built from a template: the garment of line 4 is a mesh from a file",
        ),
        (
            "garment mesh \"band.obj\"\nset waist_girth +0.02\n",
            "'set' needs a garment built from a template",
        ),
        (
            "garment mesh \"band.obj\"\nsculpt at=waist.front radius=0.05 peak=0.01\n",
            "has no control point 'waist.front'",
        ),
        ("garment mesh \"missing.obj\"\n", "garment 'missing' from"),
        ("garment mesh \"band.obj\" units=ft\n", "unknown units 'ft'"),
        (
            "garment mesh \"band.obj\" ease=0.5\n",
            "ease must be between 0 and 0.1 m",
        ),
        ("garment mesh \"band.obj\" units=mm\n", "likely in m"),
    ];
    let body = &real_body().mesh.mesh;
    let (band, _) = offset_band(body, (0.95, 1.25), 0, 0.006, (0, 0.0, 1));
    std::fs::write(dir.join("band.obj"), to_obj(&band)).expect("written");
    for (k, (steps, expected)) in cases.iter().enumerate() {
        let path = dir.join(format!("case{k}.drape"));
        std::fs::write(&path, format!("drape 1\nbody builtin\nm1\n{steps}")).expect("written");
        let o = drape_cli()
            .arg("run")
            .arg(&path)
            .args(["--log-detail", "metrics", "--save"])
            .arg(dir.join(format!("case{k}.rrd")))
            .output()
            .expect("drape runs");
        let said = text(&o);
        assert_eq!(o.status.code(), Some(2), "{steps}: {said}");
        assert!(said.contains(expected), "{steps}: expected '{expected}' in: {said}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
