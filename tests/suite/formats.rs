//! Garments and bodies as PLY (text and binary) and glTF (`.glb`, `.gltf`): a garment drape
//! did not build, written by the hand-made writers of `mesh_files`, repaired by `drape
//! check-garment` and read back by the hand-made readers: clear by brute force, every
//! value the repair did not move bit for bit the input's, the file's structure (header,
//! colours, texture coordinates, faces, materials, extras) kept; bodies in those formats
//! read as their OBJ; hostile files each a named error, never a panic.

use std::path::Path;

use drape::body::{BodyMesh, BodySource};
use drape::mesh::TriMesh;
use glam::DVec3;

use super::common::{real_body, shipped_bodies};
use super::garment_mesh::{last_export, run_session};
use super::import::{brute, check_garment, scratch, text};
use super::mesh_files::{Gltf, gltf_of, read_ply, write_ply};
use super::offset_garment::offset_band;

/// The band with bumps into the built-in body that the import tests use.
fn bumpy_band() -> TriMesh {
    offset_band(&real_body().mesh.mesh, (0.95, 1.25), 0, 0.006, (12, 0.02, 7)).0
}

#[test]
fn a_ply_garment_text_or_binary_is_repaired_clear_and_written_back_in_its_own_encoding() {
    let body = &real_body().mesh.mesh;
    let band = bumpy_band();
    let dir = scratch("ply");
    for (binary, double) in [(true, false), (false, true), (false, false)] {
        let name = format!(
            "band_{}_{}",
            if binary { "binary" } else { "text" },
            if double { "double" } else { "float" }
        );
        let input = dir.join(format!("{name}.ply"));
        let written = write_ply(&band, binary, double);
        std::fs::write(&input, &written).expect("written");
        let read = read_ply(&written);
        let before = brute(body, &read.mesh());
        assert!(
            before[0] > 20 && before[1] > 0,
            "{name}: the fixture must go into the body: {before:?}"
        );
        let out = dir.join(format!("{name}.repaired.ply"));
        let o = check_garment(&input, &["--repair", out.to_str().expect("utf-8")]);
        assert_eq!(o.status.code(), Some(1), "{name}: {}", text(&o));
        let back = read_ply(&std::fs::read(&out).expect("the repaired file"));
        assert_eq!(
            back.header, read.header,
            "{name}: the header (encoding, comment, elements, types) is kept"
        );
        assert_eq!(back.faces, read.faces, "{name}: the faces");
        assert_eq!(brute(body, &back.mesh()), [0, 0, 0], "{name}: {}", text(&o));
        let mut moved = 0;
        for (v, (a, b)) in read.values.iter().zip(&back.values).enumerate() {
            // Texture coordinates and colours never change.
            assert_eq!(
                a[6..].iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                b[6..].iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                "{name}: vertex {v}"
            );
            if a[..3].iter().zip(&b[..3]).all(|(x, y)| x.to_bits() == y.to_bits()) {
                assert_eq!(a[3..6], b[3..6], "{name}: vertex {v} did not move, nor did its normal");
            } else {
                moved += 1;
                let n = DVec3::new(b[3], b[4], b[5]).length();
                assert!(
                    (n - 1.0).abs() < 1e-5,
                    "{name}: vertex {v}: its normal, made again, is {n} long"
                );
            }
        }
        assert!(moved > 0 && moved < band.positions.len() / 2, "{name}: {moved} moved");
        eprintln!(
            "{name}: {before:?} -> [0, 0, 0], {moved} of {} vertices moved",
            band.positions.len()
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_gltf_garment_is_repaired_clear_and_keeps_its_document_as_glb_or_gltf() {
    let body = &real_body().mesh.mesh;
    let band = bumpy_band();
    let lift = 0.25;
    let asset = gltf_of(&band, lift);
    let dir = scratch("gltf");
    let input = dir.join("band.glb");
    std::fs::write(&input, asset.glb()).expect("written");
    let before = brute(body, &asset.world_mesh(lift));
    assert!(
        before[0] > 20 && before[1] > 0,
        "the fixture must go into the body: {before:?}"
    );
    for extension in ["glb", "gltf"] {
        let out = dir.join(format!("band.repaired.{extension}"));
        let o = check_garment(&input, &["--repair", out.to_str().expect("utf-8")]);
        assert_eq!(o.status.code(), Some(1), "{extension}: {}", text(&o));
        let bytes = std::fs::read(&out).expect("the repaired file");
        let back = if extension == "glb" {
            Gltf::from_glb(&bytes)
        } else {
            Gltf::from_gltf(&bytes)
        };
        assert_eq!(
            brute(body, &back.world_mesh(lift)),
            [0, 0, 0],
            "{extension}: {}",
            text(&o)
        );
        // The document is the input's but for the positions' bounds and the buffer.
        let mut a = asset.json.clone();
        let mut b = back.json.clone();
        for j in [&mut a, &mut b] {
            j["accessors"][0]
                .as_object_mut()
                .expect("an accessor")
                .retain(|k, _| k != "min" && k != "max");
            j["buffers"] = serde_json::Value::Null;
        }
        assert_eq!(a, b, "{extension}: the document");
        // The bounds are those of the positions written.
        let p = back.floats(0, 3);
        for k in 0..3 {
            let lo = p.iter().map(|q| q[k]).fold(f32::INFINITY, f32::min);
            let hi = p.iter().map(|q| q[k]).fold(f32::NEG_INFINITY, f32::max);
            assert_eq!(
                back.json["accessors"][0]["min"][k].as_f64(),
                Some(lo.into()),
                "{extension}: min"
            );
            assert_eq!(
                back.json["accessors"][0]["max"][k].as_f64(),
                Some(hi.into()),
                "{extension}: max"
            );
        }
        assert_eq!(
            back.floats(2, 2),
            asset.floats(2, 2),
            "{extension}: the texture coordinates"
        );
        assert_eq!(
            [back.uints(3), back.uints(4)],
            [asset.uints(3), asset.uints(4)],
            "{extension}: the indices"
        );
        let (p0, n0, n1) = (asset.floats(0, 3), asset.floats(1, 3), back.floats(1, 3));
        let mut moved = 0;
        for v in 0..p.len() {
            let bits = |x: &[f32]| x.iter().map(|c| c.to_bits()).collect::<Vec<_>>();
            if bits(&p[v]) == bits(&p0[v]) {
                assert_eq!(
                    bits(&n1[v]),
                    bits(&n0[v]),
                    "{extension}: vertex {v} did not move, nor did its normal"
                );
            } else {
                moved += 1;
                let n = n1[v].iter().map(|c| c * c).sum::<f32>().sqrt();
                assert!((n - 1.0).abs() < 1e-5, "{extension}: vertex {v}: normal {n} long");
            }
        }
        assert!(moved > 0 && moved < p.len() / 2, "{extension}: {moved} moved");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_body_as_ply_or_glb_is_the_body_of_its_obj() {
    let dir = scratch("bodies");
    for path in shipped_bodies() {
        let obj = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("the OBJ body loads");
        let stem = path.file_stem().and_then(|s| s.to_str()).expect("a name").to_string();
        // The OBJ as read by drape's OBJ reader, written in the other formats by hand: the
        // PLY in doubles (exact), the GLB in floats.
        let read = drape::mesh::read_obj(&path, 1.0, u64::MAX).expect("the OBJ reads").mesh;
        let ply = dir.join(format!("{stem}.ply"));
        std::fs::write(&ply, write_ply(&read, true, true)).expect("written");
        let glb = dir.join(format!("{stem}.glb"));
        std::fs::write(&glb, gltf_of(&read, 0.0).glb()).expect("written");
        let from_ply = BodyMesh::load(&BodySource::File(ply), 1.0).expect("the PLY body loads");
        assert_eq!(from_ply.mesh, obj.mesh, "{stem}: PLY");
        let from_glb = BodyMesh::load(&BodySource::File(glb.clone()), 1.0).expect("the GLB body loads");
        // The GLB's primitives put the front faces first: the same triangles, in other order.
        let mut a = obj.mesh.triangles.clone();
        let mut b = from_glb.mesh.triangles.clone();
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b, "{stem}: GLB triangles");
        for (p, q) in obj.mesh.positions.iter().zip(&from_glb.mesh.positions) {
            assert!(p.distance(*q) < 1e-6, "{stem}: GLB vertex {p} read as {q}");
        }
        // And a garment is checked against the GLB as against the OBJ.
        if path == shipped_bodies()[0] {
            let band = dir.join("band.ply");
            let (mesh, _) = offset_band(&obj.mesh, (0.95, 1.25), 0, 0.006, (12, 0.02, 7));
            std::fs::write(&band, write_ply(&mesh, true, true)).expect("written");
            let counts = |body: &Path| {
                let o = check_garment(&band, &["--body", body.to_str().expect("utf-8"), "--json"]);
                let report: serde_json::Value = serde_json::from_slice(&o.stdout).expect("a JSON report");
                // The counts and their regions (the GLB's float coordinates move the
                // distances in their eighth digit).
                let counts = |c: &serde_json::Value| {
                    ["inside_vertices", "crossing_edges", "pierced_faces", "regions"].map(|k| c[k].clone())
                };
                (o.status.code(), counts(&report["before"]), counts(&report["after"]))
            };
            let (on_glb, on_obj) = (counts(&glb), counts(&path));
            assert_eq!(on_obj.0, Some(1), "{stem}: the band needs a repair: {on_obj:?}");
            assert_eq!(on_glb, on_obj, "{stem}: GLB body against OBJ body");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn hostile_ply_and_gltf_files_are_named_errors_never_panics() {
    let dir = scratch("hostile-formats");
    let band = bumpy_band();
    let ply_header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let triangle = |x: f32| -> Vec<u8> {
        let mut b = ply_header.as_bytes().to_vec();
        for p in [[x, 1.0, 0.2], [0.1, 1.0, 0.2], [0.0, 1.1, 0.2]] {
            p.iter().for_each(|c| b.extend(c.to_le_bytes()));
        }
        b.push(3);
        [0i32, 1, 2].iter().for_each(|v| b.extend(v.to_le_bytes()));
        b
    };
    let mut bad_index = triangle(0.0);
    let n = bad_index.len();
    bad_index[n - 4..].copy_from_slice(&9i32.to_le_bytes());
    let mut truncated = triangle(0.0);
    truncated.truncate(truncated.len() - 6);
    let good = gltf_of(&band, 0.0);
    let with = |edit: &dyn Fn(&mut Gltf)| {
        let mut g = Gltf {
            json: good.json.clone(),
            bin: good.bin.clone(),
        };
        edit(&mut g);
        g.glb()
    };
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("empty.ply", Vec::new(), "PLY: the header"),
        (
            "huge_count.ply",
            ply_header.replace("vertex 3", "vertex 4000000000").into_bytes(),
            "element 'vertex' declares 4000000000 items",
        ),
        (
            "nan.ply",
            triangle(f32::NAN),
            "vertex 1 has a coordinate that is not finite",
        ),
        (
            "bad_index.ply",
            bad_index,
            "face 1: vertex index 9 is out of range: 3 vertices",
        ),
        (
            "truncated.ply",
            truncated,
            "element 'face' item 1: a list of 3 values, more than the file holds",
        ),
        (
            "points.ply",
            ply_header
                .replace("element face 1\nproperty list uchar int vertex_indices\n", "")
                .into_bytes(),
            "no 'face' element",
        ),
        (
            "int.ply",
            ply_header.replace("float x", "int x").into_bytes(),
            "vertex property 'x' is Scalar(Int)",
        ),
        ("not_json.gltf", b"{ not json".to_vec(), "glTF: the JSON"),
        (
            "short.glb",
            b"glTF\x02\0\0\0\xff\xff\0\0".to_vec(),
            "glTF: the GLB container",
        ),
        (
            "outside.glb",
            with(&|g| g.json["accessors"][0]["count"] = serde_json::json!(10_000_000)),
            "lies outside buffer 0",
        ),
        (
            "index.glb",
            with(&|g| {
                let at = g.json["bufferViews"][3]["byteOffset"].as_u64().expect("an offset") as usize;
                g.bin[at..at + 4].copy_from_slice(&4_000_000u32.to_le_bytes());
            }),
            "band, primitive 0: index 0 (accessor 3) is 4000000, out of range",
        ),
        (
            "lines.glb",
            with(&|g| g.json["meshes"][0]["primitives"][0]["mode"] = serde_json::json!(1)),
            "draws Lines: drape needs triangles",
        ),
        (
            "quantized.glb",
            with(&|g| g.json["accessors"][0]["componentType"] = serde_json::json!(5123)),
            "accessor 0 (POSITION) is Vec3 U16",
        ),
        (
            "nan.glb",
            with(&|g| g.bin[4..8].copy_from_slice(&f32::NAN.to_le_bytes())),
            "vertex 0 of accessor 0 is not finite",
        ),
        (
            "network.gltf",
            {
                let mut j = good.json.clone();
                j["buffers"][0]["uri"] = serde_json::json!("https://example.com/band.bin");
                serde_json::to_vec(&j).expect("JSON")
            },
            "drape reads buffers from files, not the network",
        ),
        (
            "missing.gltf",
            {
                let mut j = good.json.clone();
                j["buffers"][0]["uri"] = serde_json::json!("no%20such.bin");
                serde_json::to_vec(&j).expect("JSON")
            },
            "no such.bin: cannot read",
        ),
        (
            "band.fbx",
            b"Kaydara FBX Binary".to_vec(),
            "drape reads meshes as OBJ, PLY, glTF or GLB",
        ),
    ];
    for (name, content, expected) in cases {
        let path = dir.join(name);
        std::fs::write(&path, content).expect("written");
        let o = check_garment(&path, &[]);
        let said = text(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {said}");
        assert!(said.contains(expected), "{name}: expected '{expected}' in: {said}");
        assert!(!said.contains("panicked"), "{name}: {said}");
    }
    // A glTF garment written back as PLY is refused before any work, by name.
    let glb = dir.join("band.glb");
    std::fs::write(&glb, good.glb()).expect("written");
    let o = check_garment(&glb, &["--repair", dir.join("out.ply").to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("the garment is GLB, written back as glTF (name the file .gltf or .glb)"),
        "{}",
        text(&o)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_glb_garment_in_a_session_is_exported_as_glb_clear_of_the_body() {
    let body = &real_body().mesh.mesh;
    let band = bumpy_band();
    let dir = scratch("gltf-session");
    std::fs::write(dir.join("band.glb"), gltf_of(&band, 0.1).glb()).expect("written");
    let (o, out) = run_session(&dir, "drape 1\nm1\ngarment mesh \"band.glb\" name=band ease=0.003\n");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let exported = last_export(&out, "_band_m0.glb");
    let back = Gltf::from_glb(&std::fs::read(&exported).expect("M0"));
    assert_eq!(brute(body, &back.world_mesh(0.1)), [0, 0, 0], "{}", text(&o));
    std::fs::remove_dir_all(&dir).ok();
}
