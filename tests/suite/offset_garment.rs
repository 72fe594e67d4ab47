//! Garments drape did not build, made here: a band of the body's own surface between two
//! heights, offset outward along its vertex normals, optionally split finer, with a random
//! field pushing parts of it into the body; written as an OBJ with texture coordinates,
//! normals, groups and materials, as a garment tool would. Shared by the import tests and
//! the check-garment benchmark (`#[path]`).

use drape::mesh::TriMesh;

/// A small deterministic generator (64-bit LCG, the high bits), so that every run makes the
/// same garment.
pub struct Lcg(pub u64);

impl Lcg {
    /// A number in `[0, 1)`.
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The band of `body` whose triangles lie between heights `y0` and `y1`, every triangle
/// split into four `splits` times, moved `offset` m out along the band's vertex normals,
/// then `pushes` bumps (random centres on the band, radius 3-8 cm) pushing it in by up to
/// `depth` m. Returns the garment and, per vertex, how far it was pushed in.
pub fn offset_band(
    body: &TriMesh,
    (y0, y1): (f64, f64),
    splits: usize,
    offset: f64,
    (pushes, depth, seed): (usize, f64, u64),
) -> (TriMesh, Vec<f64>) {
    let mut ids = vec![u32::MAX; body.positions.len()];
    let mut mesh = TriMesh {
        positions: Vec::new(),
        triangles: Vec::new(),
    };
    for t in &body.triangles {
        if t.iter().all(|&v| (y0..=y1).contains(&body.positions[v as usize].y)) {
            let tri = t.map(|v| {
                if ids[v as usize] == u32::MAX {
                    ids[v as usize] = mesh.positions.len() as u32;
                    mesh.positions.push(body.positions[v as usize]);
                }
                ids[v as usize]
            });
            mesh.triangles.push(tri);
        }
    }
    for _ in 0..splits {
        mesh = mesh.split_in_four();
    }
    let normals = mesh.vertex_normals();
    for (p, n) in mesh.positions.iter_mut().zip(&normals) {
        *p += offset * *n;
    }
    let mut rng = Lcg(seed);
    let mut pushed = vec![0.0; mesh.positions.len()];
    for _ in 0..pushes {
        let centre = mesh.positions[(rng.next() * mesh.positions.len() as f64) as usize];
        let radius = 0.03 + 0.05 * rng.next();
        let amount = depth * (0.5 + 0.5 * rng.next());
        for ((p, n), pushed) in mesh.positions.iter_mut().zip(&normals).zip(&mut pushed) {
            let d = p.distance(centre);
            if d < radius {
                let w = (1.0 - d / radius).powi(2);
                *p -= amount * w * *n;
                *pushed += amount * w;
            }
        }
    }
    (mesh, pushed)
}

/// The garment as a garment tool writes it: a header, `mtllib`, `v` lines, one `vt` and one
/// `vn` per vertex, then the faces in two groups (front `z >= 0` and back) with a material
/// each, corners `v/vt/vn`.
pub fn to_obj(mesh: &TriMesh) -> String {
    let mut s = String::from("# a garment made by another tool\nmtllib garment.mtl\n");
    for p in &mesh.positions {
        s += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    for p in &mesh.positions {
        s += &format!("vt {} {}\n", p.x.atan2(p.z), p.y);
    }
    for n in mesh.vertex_normals() {
        s += &format!("vn {} {} {}\n", n.x, n.y, n.z);
    }
    for (name, front) in [("front", true), ("back", false)] {
        s += &format!("g {name}\nusemtl {name}_fabric\ns 1\n");
        for t in &mesh.triangles {
            let z = t.iter().map(|&v| mesh.positions[v as usize].z).sum::<f64>();
            if (z >= 0.0) == front {
                let [a, b, c] = t.map(|v| v + 1);
                s += &format!("f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}\n");
            }
        }
    }
    s
}

/// A band of `body` between fractions `span` of its height, `offset` m out, with `bumps`
/// (count, depth) pushed in, made clear of the body by `check-garment`'s repair.
pub fn band_clear_of(
    body: &drape::body::Body,
    index: &drape::collision::BodyIndex,
    span: (f64, f64),
    offset: f64,
    bumps: (usize, f64),
) -> TriMesh {
    let mesh = &body.mesh.mesh;
    let (lo, hi) = mesh.bounds().expect("a body");
    let h = hi.y - lo.y;
    let (band, _) = offset_band(
        mesh,
        (lo.y + span.0 * h, lo.y + span.1 * h),
        0,
        offset,
        (bumps.0, bumps.1, 11),
    );
    let doc = drape::mesh::MeshDocument::parse_obj(&to_obj(&band), "band.obj", 1.0).expect("the band reads");
    let imported = drape::import::ImportedGarment::new(doc, mesh, index).expect("the band imports");
    let checked = drape::import::check(&imported, index, &drape::import::CheckOptions::default());
    TriMesh {
        positions: checked.positions,
        triangles: band.triangles,
    }
}
