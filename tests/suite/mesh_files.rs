//! PLY and glTF files written and read here, byte by byte, from the formats' published
//! descriptions (PLY: the Stanford polygon file format; glTF 2.0: the Khronos
//! specification, its GLB container and accessors), independently of drape's readers and
//! writers, to judge what drape reads and writes back.

use drape::mesh::TriMesh;
use glam::DVec3;
use serde_json::{Value, json};

/// The vertex properties the test PLY files carry, in order: position, normal, texture
/// coordinate, colour.
const PLY_VERTEX: [&str; 11] = ["x", "y", "z", "nx", "ny", "nz", "s", "t", "red", "green", "blue"];

/// `mesh` as a PLY file: `binary` little endian or text, coordinates `double` or float,
/// with normals, texture coordinates and a colour per vertex, one comment and the faces
/// as `list uchar int vertex_indices`.
pub fn write_ply(mesh: &TriMesh, binary: bool, double: bool) -> Vec<u8> {
    let xyz = if double { "double" } else { "float" };
    let mut out = format!(
        "ply\nformat {} 1.0\ncomment made by another tool\nelement vertex {}\nproperty {xyz} x\nproperty {xyz} y\nproperty {xyz} z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        if binary { "binary_little_endian" } else { "ascii" },
        mesh.positions.len(),
        mesh.triangles.len()
    )
    .into_bytes();
    let normals = mesh.vertex_normals();
    for (v, (p, n)) in mesh.positions.iter().zip(&normals).enumerate() {
        let floats = [n.x as f32, n.y as f32, n.z as f32, p.x.atan2(p.z) as f32, p.y as f32];
        let colour = [(v % 256) as u8, 128, 255];
        if binary {
            for c in p.to_array() {
                if double {
                    out.extend(c.to_le_bytes());
                } else {
                    out.extend((c as f32).to_le_bytes());
                }
            }
            floats.iter().for_each(|f| out.extend(f.to_le_bytes()));
            out.extend(colour);
        } else {
            let c: Vec<String> = p
                .to_array()
                .iter()
                .map(|&c| if double { c.to_string() } else { (c as f32).to_string() })
                .collect();
            let f: Vec<String> = floats.iter().map(ToString::to_string).collect();
            out.extend(
                format!(
                    "{} {} {} {} {}\n",
                    c.join(" "),
                    f.join(" "),
                    colour[0],
                    colour[1],
                    colour[2]
                )
                .bytes(),
            );
        }
    }
    for t in &mesh.triangles {
        if binary {
            out.push(3);
            t.iter().for_each(|&v| out.extend((v as i32).to_le_bytes()));
        } else {
            out.extend(format!("3 {} {} {}\n", t[0], t[1], t[2]).bytes());
        }
    }
    out
}

/// A PLY file of [`write_ply`]'s layout, read back.
pub struct PlyRead {
    /// The header, up to and with `end_header\n`.
    pub header: String,
    /// Per vertex, its [`PLY_VERTEX`] values (coordinates as read: f32 widened when float).
    pub values: Vec<[f64; 11]>,
    /// The faces.
    pub faces: Vec<Vec<u32>>,
}

impl PlyRead {
    /// The positions and triangles.
    pub fn mesh(&self) -> TriMesh {
        TriMesh {
            positions: self.values.iter().map(|v| DVec3::new(v[0], v[1], v[2])).collect(),
            triangles: self.faces.iter().map(|f| [f[0], f[1], f[2]]).collect(),
        }
    }
}

/// Reads a PLY file of [`write_ply`]'s layout (binary little endian or text).
pub fn read_ply(bytes: &[u8]) -> PlyRead {
    let end = bytes.windows(11).position(|w| w == b"end_header\n").expect("a header") + 11;
    let header = String::from_utf8(bytes[..end].to_vec()).expect("a text header");
    let count = |element: &str| -> usize {
        let line = header
            .lines()
            .find(|l| l.starts_with(&format!("element {element} ")))
            .expect("the element");
        line.rsplit(' ').next().expect("a count").parse().expect("a count")
    };
    let (vertices, faces) = (count("vertex"), count("face"));
    let props: Vec<(String, String)> = header
        .lines()
        .skip_while(|l| !l.starts_with("element vertex"))
        .skip(1)
        .take_while(|l| l.starts_with("property"))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w[1].to_string(), w[2].to_string())
        })
        .collect();
    assert_eq!(
        props.iter().map(|p| p.1.as_str()).collect::<Vec<_>>(),
        PLY_VERTEX,
        "the vertex layout"
    );
    let mut values = Vec::with_capacity(vertices);
    let mut faces_out = Vec::with_capacity(faces);
    if header.contains("format ascii") {
        let mut lines = std::str::from_utf8(&bytes[end..]).expect("text").lines();
        for _ in 0..vertices {
            let line = lines.next().expect("a vertex");
            let mut row = [0.0; 11];
            for (k, ((t, _), x)) in props.iter().zip(line.split_whitespace()).enumerate() {
                // A float's text is read as the f32 its writer meant.
                row[k] = match t.as_str() {
                    "float" => f64::from(x.parse::<f32>().expect("a float")),
                    _ => x.parse().expect("a number"),
                };
            }
            values.push(row);
        }
        for _ in 0..faces {
            let f: Vec<u32> = lines
                .next()
                .expect("a face")
                .split_whitespace()
                .map(|x| x.parse().expect("an index"))
                .collect();
            faces_out.push(f[1..].to_vec());
        }
    } else {
        let mut at = end;
        let mut take = |n: usize| {
            let s = &bytes[at..at + n];
            at += n;
            s
        };
        for _ in 0..vertices {
            let mut row = [0.0; 11];
            for (k, (t, _)) in props.iter().enumerate() {
                row[k] = match t.as_str() {
                    "double" => f64::from_le_bytes(take(8).try_into().expect("8 bytes")),
                    "float" => f64::from(f32::from_le_bytes(take(4).try_into().expect("4 bytes"))),
                    "uchar" => f64::from(take(1)[0]),
                    other => panic!("type {other}"),
                };
            }
            values.push(row);
        }
        for _ in 0..faces {
            let n = take(1)[0] as usize;
            faces_out.push(
                (0..n)
                    .map(|_| i32::from_le_bytes(take(4).try_into().expect("4 bytes")) as u32)
                    .collect(),
            );
        }
    }
    PlyRead {
        header,
        values,
        faces: faces_out,
    }
}

/// A glTF asset as the test writes it: the JSON and one binary buffer.
pub struct Gltf {
    /// The document.
    pub json: Value,
    /// Buffer 0.
    pub bin: Vec<u8>,
}

/// `mesh` as a glTF asset: one mesh of two primitives (the faces in front, `z >= 0`, and
/// behind, each with its material), sharing one position, normal and texture-coordinate
/// accessor; the positions stored `lift` m lower than they stand, a node's translation
/// putting them back. Extras on the mesh and an asset generator, to be kept.
pub fn gltf_of(mesh: &TriMesh, lift: f64) -> Gltf {
    let mut bin = Vec::new();
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in &mesh.positions {
        let q = [p.x as f32, (p.y - lift) as f32, p.z as f32];
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
            bin.extend(q[k].to_le_bytes());
        }
    }
    let normals_at = bin.len();
    for n in mesh.vertex_normals() {
        n.to_array().iter().for_each(|&c| bin.extend((c as f32).to_le_bytes()));
    }
    let uv_at = bin.len();
    for p in &mesh.positions {
        bin.extend((p.x.atan2(p.z) as f32).to_le_bytes());
        bin.extend((p.y as f32).to_le_bytes());
    }
    let n = mesh.positions.len();
    let mut views = vec![
        json!({"buffer": 0, "byteOffset": 0, "byteLength": 12 * n, "target": 34962}),
        json!({"buffer": 0, "byteOffset": normals_at, "byteLength": 12 * n, "target": 34962}),
        json!({"buffer": 0, "byteOffset": uv_at, "byteLength": 8 * n, "target": 34962}),
    ];
    let mut accessors = vec![
        json!({"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi}),
        json!({"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"}),
        json!({"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"}),
    ];
    let mut primitives = Vec::new();
    for (k, front) in [true, false].into_iter().enumerate() {
        let at = bin.len();
        let mut count = 0;
        for t in &mesh.triangles {
            let z: f64 = t.iter().map(|&v| mesh.positions[v as usize].z).sum();
            if (z >= 0.0) == front {
                t.iter().for_each(|&v| bin.extend(v.to_le_bytes()));
                count += 3;
            }
        }
        views.push(json!({"buffer": 0, "byteOffset": at, "byteLength": bin.len() - at, "target": 34963}));
        accessors.push(json!({"bufferView": views.len() - 1, "componentType": 5125, "count": count, "type": "SCALAR"}));
        primitives.push(json!({
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
            "indices": accessors.len() - 1,
            "material": k,
        }));
    }
    let json = json!({
        "asset": {"version": "2.0", "generator": "another tool"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "garment", "translation": [0.0, lift, 0.0]}],
        "meshes": [{"name": "band", "primitives": primitives, "extras": {"fabric": "jersey"}}],
        "materials": [{"name": "front_fabric"}, {"name": "back_fabric"}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}],
    });
    Gltf { json, bin }
}

impl Gltf {
    /// As a GLB file.
    pub fn glb(&self) -> Vec<u8> {
        let mut json = serde_json::to_vec(&self.json).expect("JSON");
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let mut out = Vec::new();
        out.extend(b"glTF");
        out.extend(2u32.to_le_bytes());
        out.extend(((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
        out.extend((json.len() as u32).to_le_bytes());
        out.extend(b"JSON");
        out.extend(json);
        out.extend((bin.len() as u32).to_le_bytes());
        out.extend(b"BIN\0");
        out.extend(bin);
        out
    }

    /// Reads a GLB file's two chunks.
    pub fn from_glb(bytes: &[u8]) -> Self {
        assert_eq!(&bytes[..4], b"glTF", "the GLB magic");
        let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes")) as usize;
        assert_eq!(word(8), bytes.len(), "the GLB length");
        let json_len = word(12);
        assert_eq!(&bytes[16..20], b"JSON");
        let json = serde_json::from_slice(&bytes[20..20 + json_len]).expect("the JSON chunk");
        let at = 20 + json_len;
        let bin_len = word(at);
        assert_eq!(&bytes[at + 4..at + 8], b"BIN\0");
        Self {
            json,
            bin: bytes[at + 8..at + 8 + bin_len].to_vec(),
        }
    }

    /// Reads a `.gltf` whose one buffer is a base64 `data:` URI.
    pub fn from_gltf(bytes: &[u8]) -> Self {
        use base64::Engine as _;
        let json: Value = serde_json::from_slice(bytes).expect("JSON");
        let uri = json["buffers"][0]["uri"].as_str().expect("a data URI");
        let data = uri.split_once(";base64,").expect("base64").1;
        let bin = base64::engine::general_purpose::STANDARD
            .decode(data)
            .expect("base64 data");
        Self { json, bin }
    }

    /// The mesh as [`gltf_of`] lays it out, placed `lift` m up as its node does.
    pub fn world_mesh(&self, lift: f64) -> TriMesh {
        TriMesh {
            positions: self
                .floats(0, 3)
                .iter()
                .map(|p| DVec3::new(p[0].into(), f64::from(p[1]) + lift, p[2].into()))
                .collect(),
            triangles: [self.uints(3), self.uints(4)]
                .concat()
                .chunks(3)
                .map(|t| [t[0], t[1], t[2]])
                .collect(),
        }
    }

    /// The elements of accessor `k` (`width` floats each), from its view, offset and stride.
    pub fn floats(&self, k: usize, width: usize) -> Vec<Vec<f32>> {
        self.elements(k, width, |b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
    }

    /// The elements of an unsigned-int accessor.
    pub fn uints(&self, k: usize) -> Vec<u32> {
        self.elements(k, 1, |b| u32::from_le_bytes(b.try_into().expect("4 bytes")))
            .concat()
    }

    fn elements<T>(&self, k: usize, width: usize, read: impl Fn(&[u8]) -> T) -> Vec<Vec<T>> {
        let a = &self.json["accessors"][k];
        let view = &self.json["bufferViews"][a["bufferView"].as_u64().expect("a view") as usize];
        let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize + a["byteOffset"].as_u64().unwrap_or(0) as usize;
        let stride = view["byteStride"].as_u64().map_or(4 * width, |s| s as usize);
        (0..a["count"].as_u64().expect("a count") as usize)
            .map(|i| {
                (0..width)
                    .map(|c| read(&self.bin[offset + i * stride + 4 * c..][..4]))
                    .collect()
            })
            .collect()
    }
}
