//! Broken OBJ files: each gets a clear error naming the place, never a panic.

use drape::body::BodyMesh;

fn error_of(text: &str) -> String {
    match BodyMesh::from_obj_text(text, "bad.obj", 1.0) {
        Ok(_) => panic!("accepted a broken file:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn nan_coordinate() {
    assert_eq!(
        error_of("v 0 0 0\nv 1 nan 0\n"),
        "bad.obj:2:5: coordinate 'nan' is not finite"
    );
}

#[test]
fn infinite_coordinate() {
    assert_eq!(error_of("v 0 0 -inf\n"), "bad.obj:1:7: coordinate '-inf' is not finite");
}

#[test]
fn missing_coordinate() {
    assert_eq!(
        error_of("v 0 0\n"),
        "bad.obj:1:6: expected 3 coordinates after 'v', found 2"
    );
}

#[test]
fn not_a_number() {
    assert_eq!(error_of("v 0 0 0,5\n"), "bad.obj:1:7: '0,5' is not a number");
}

#[test]
fn index_out_of_range() {
    assert_eq!(
        error_of(&format!("{TRIANGLE}f 1 2 9\n")),
        "bad.obj:4:7: vertex index 9 is out of range: the file has 3 vertices"
    );
}

#[test]
fn index_zero() {
    assert_eq!(
        error_of(&format!("{TRIANGLE}f 0 1 2\n")),
        "bad.obj:4:3: vertex index 0 is invalid (OBJ indices start at 1)"
    );
}

#[test]
fn relative_index_before_the_first_vertex() {
    assert_eq!(
        error_of(&format!("{TRIANGLE}f -1 -2 -4\n")),
        "bad.obj:4:9: relative index -4 reaches before the first vertex"
    );
}

#[test]
fn face_with_two_corners() {
    assert_eq!(
        error_of(&format!("{TRIANGLE}f 1 2  # a line?\n")),
        "bad.obj:4:6: a face needs at least 3 vertices, found 2"
    );
}

#[test]
fn no_faces() {
    assert_eq!(error_of(TRIANGLE), "bad.obj: no faces ('f' lines)");
}

#[test]
fn no_vertices() {
    assert_eq!(error_of("# nothing\n"), "bad.obj: no vertices ('v' lines)");
}

#[test]
fn only_degenerate_faces() {
    assert_eq!(
        error_of(&format!("{TRIANGLE}f 1 1 2\n")),
        "bad.obj: no usable triangles: all 1 repeat a vertex"
    );
}

#[test]
fn non_manifold_edge() {
    // Three triangles on the edge 1-2 (a fin).
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
    assert_eq!(
        error_of(text),
        "bad.obj: edge between vertices 1 and 2 is shared by 3 faces (lines 6, 7, 8): the mesh is not manifold"
    );
}

#[test]
fn unreadable_file() {
    let e = BodyMesh::load(&drape::body::BodySource::File("no/such/body.obj".into()), 1.0)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("no/such/body.obj: cannot read: "), "{e}");
}

/// A 2 GB file (sparse zeros) is refused from its size, a device, a folder and a pipe as not
/// regular files. None is read: the pipe has no writer, so reading it would wait for ever.
#[test]
fn huge_files_devices_folders_and_pipes_are_refused_before_reading() {
    let dir = std::env::temp_dir().join(format!("drape-bounded-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let huge = dir.join("zeros.obj");
    let file = std::fs::File::create(&huge).unwrap();
    file.set_len(2 * 1024 * 1024 * 1024).unwrap();
    let pipe = dir.join("pipe.obj");
    let made = std::process::Command::new("mkfifo")
        .arg(&pipe)
        .status()
        .is_ok_and(|s| s.success());
    let limit = drape::input::DEFAULT_MAX_INPUT_BYTES;
    let mut cases = vec![
        (huge.clone(), "2147483648 bytes, more than the limit of 268435456 bytes"),
        (std::path::PathBuf::from("/dev/zero"), "not a regular file (a device)"),
        (dir.clone(), "not a regular file (a folder)"),
    ];
    if made {
        cases.push((pipe, "not a regular file (a pipe)"));
    }
    for (path, expected) in cases {
        let err = drape::mesh::read_obj(&path, 1.0, limit).expect_err("refused");
        assert!(err.to_string().contains(expected), "{err}");
    }
    // Within the limit once raised past the size, the same file is read (and its zeros are
    // not text an OBJ reader accepts).
    let small = dir.join("small.obj");
    std::fs::write(&small, "v 0 0 0\n".repeat(1000)).unwrap();
    let err = drape::mesh::read_obj(&small, 1.0, 100).expect_err("over a 100-byte limit");
    assert!(
        err.to_string().contains("8000 bytes, more than the limit of 100 bytes"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
