//! Shared fixtures: the real body (loaded once) and analytic meshes.

use std::sync::OnceLock;

use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::mesh::TriMesh;
use glam::DVec3;

/// The user cache folder the binary sees in tests (`XDG_CACHE_HOME`): one under the test
/// target folder, so that a test run never reads or fills the user's own index cache.
pub fn cache_home() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cache-home")
}

/// The `drape` binary, with [`cache_home`] for its cache folder.
pub fn drape_cli() -> std::process::Command {
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_drape"));
    command.env("XDG_CACHE_HOME", cache_home());
    command
}

/// The shipped real body, analysed once per test run.
pub fn real_body() -> &'static Body {
    static BODY: OnceLock<Body> = OnceLock::new();
    BODY.get_or_init(|| {
        let mesh = BodyMesh::load(&BodySource::Builtin, 1.0).expect("builtin body loads");
        Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("builtin body analyses")
    })
}

/// A closed surface of revolution-like grid: `rings` latitude rings of `around` points
/// from `point(i, j)`, capped by two poles. Rings run counter-clockwise seen from above.
pub fn closed_grid(
    rings: usize,
    around: usize,
    point: impl Fn(usize, usize) -> DVec3,
    bottom: DVec3,
    top: DVec3,
) -> TriMesh {
    let mut positions = Vec::with_capacity(rings * around + 2);
    for i in 0..rings {
        for j in 0..around {
            positions.push(point(i, j));
        }
    }
    let south = positions.len() as u32;
    positions.push(bottom);
    let north = positions.len() as u32;
    positions.push(top);
    let id = |i: usize, j: usize| (i * around + j % around) as u32;
    let mut triangles = Vec::new();
    for i in 0..rings - 1 {
        for j in 0..around {
            triangles.push([id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i + 1, j)]);
        }
    }
    for j in 0..around {
        triangles.push([south, id(0, j + 1), id(0, j)]);
        triangles.push([north, id(rings - 1, j), id(rings - 1, j + 1)]);
    }
    TriMesh { positions, triangles }
}

/// Angle of point `j` of `n`, running counter-clockwise seen from above (front to left).
pub fn angle(j: usize, n: usize) -> f64 {
    std::f64::consts::FRAC_PI_2 - std::f64::consts::TAU * j as f64 / n as f64
}

/// `(a cos t, y, b sin t)`.
pub fn ellipse_point(a: f64, b: f64, y: f64, t: f64) -> DVec3 {
    DVec3::new(a * t.cos(), y, b * t.sin())
}

/// Ramanujan's second approximation of an ellipse's perimeter (relative error below 1e-9
/// for axis ratios up to 3): an independent reference for section girths.
pub fn ellipse_perimeter(a: f64, b: f64) -> f64 {
    let h = ((a - b) / (a + b)).powi(2);
    std::f64::consts::PI * (a + b) * (1.0 + 3.0 * h / (10.0 + (4.0 - 3.0 * h).sqrt()))
}

/// The body probe of the shipped body, built once.
pub fn real_probe() -> &'static drape::garment::BodyProbe {
    static PROBE: OnceLock<drape::garment::BodyProbe> = OnceLock::new();
    PROBE.get_or_init(|| drape::garment::BodyProbe::new(real_body()))
}

/// The default jumpsuit on the shipped body, built once.
pub fn real_jumpsuit() -> &'static drape::garment::Framework {
    static FW: OnceLock<drape::garment::Framework> = OnceLock::new();
    FW.get_or_init(|| {
        drape::garment::build_framework(
            real_body(),
            real_probe(),
            drape::garment::TemplateKind::Jumpsuit,
            &drape::garment::Dimensions::default(),
            &drape::garment::FrameworkOptions::default(),
        )
        .expect("the jumpsuit builds")
    })
}

/// A small deterministic generator (64-bit LCG), so failures reproduce.
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number in `[0, 1)`.
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Distance from `p` to the segment `a..b`, written here independently of the library.
pub fn segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t - p).length()
}

/// Distance from `p` to the triangle `abc`: to its plane when `p` projects inside it (by
/// barycentric signs), else to the nearest edge. Written here independently of the
/// library's Voronoi-region closest point.
pub fn triangle_distance(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let n = (b - a).cross(c - a);
    let area2 = n.length_squared();
    if area2 > 0.0 {
        let q = p - n * ((p - a).dot(n) / area2);
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| (v - u).cross(q - u).dot(n) >= 0.0);
        if inside {
            return (p - q).length();
        }
    }
    segment_distance(p, a, b)
        .min(segment_distance(p, b, c))
        .min(segment_distance(p, c, a))
}

/// Distance from `p` to the mesh, every triangle tried.
pub fn brute_distance(mesh: &TriMesh, p: DVec3) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| triangle_distance(p, mesh.corners(t)))
        .fold(f64::INFINITY, f64::min)
}

/// The distances `t > 0` at which the ray `p + t d` meets the mesh's triangles
/// (Möller-Trumbore per triangle, written here).
pub fn ray_hits(mesh: &TriMesh, p: DVec3, d: DVec3) -> impl Iterator<Item = f64> + '_ {
    (0..mesh.triangles.len()).filter_map(move |t| {
        let [a, b, c] = mesh.corners(t);
        let (e1, e2) = (b - a, c - a);
        let h = d.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-15 {
            return None;
        }
        let s = p - a;
        let u = s.dot(h) / det;
        let q = s.cross(e1);
        let v = d.dot(q) / det;
        let dist = e2.dot(q) / det;
        ((0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && dist > 0.0).then_some(dist)
    })
}

/// The nearest hit of the ray `p + t d`, `t > 0`, with the mesh, if any.
pub fn ray_hit(mesh: &TriMesh, p: DVec3, d: DVec3) -> Option<f64> {
    ray_hits(mesh, p, d).min_by(f64::total_cmp)
}

/// Whether `p` is inside the closed mesh by ray parity: the ray from `p` along a fixed
/// oblique direction crosses the surface an odd number of times. The direction is
/// irrational enough that no test point's ray grazes an edge of the shipped body.
pub fn inside_by_parity(mesh: &TriMesh, p: DVec3) -> bool {
    let d = DVec3::new(0.5773, 0.0071, 0.8165).normalize();
    ray_hits(mesh, p, d).count() % 2 == 1
}

/// The five shipped bodies, `assets/bodies/*.obj`, sorted.
pub fn shipped_bodies() -> Vec<std::path::PathBuf> {
    let mut out: Vec<std::path::PathBuf> = std::fs::read_dir("assets/bodies")
        .expect("assets/bodies")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    out.sort();
    assert_eq!(out.len(), 5, "{out:?}");
    out
}

/// The last collided M0 of a session: positions after the response, and the edges.
#[derive(Default)]
pub struct LastGarment(pub Option<Garment>);

/// A collided garment: its positions after the response, its edges and its faces.
pub type Garment = (Vec<DVec3>, Vec<[u32; 2]>, Vec<[u32; 3]>);

/// The garment a collision stage ends with, for the response's stage (`None` for others).
fn responded(stage: &drape::session::CollisionStage<'_>) -> Option<Garment> {
    (stage.part == drape::session::CollisionPart::Respond).then(|| {
        (
            stage.outcome.collision.mesh.positions.clone(),
            stage.outcome.garment.edges.to_vec(),
            stage.outcome.collision.mesh.triangles.clone(),
        )
    })
}

impl drape::session::StageSink for LastGarment {
    fn collision(
        &mut self,
        _: &drape::session::StageInfo,
        stage: drape::session::CollisionStage<'_>,
    ) -> Result<(), drape::session::SinkError> {
        if let Some(garment) = responded(&stage) {
            self.0 = Some(garment);
        }
        Ok(())
    }
}

/// Every garment a session's collisions end with (the response's M0), in order.
#[derive(Default)]
pub struct EveryGarment(pub Vec<Garment>);

impl drape::session::StageSink for EveryGarment {
    fn collision(
        &mut self,
        _: &drape::session::StageInfo,
        stage: drape::session::CollisionStage<'_>,
    ) -> Result<(), drape::session::SinkError> {
        self.0.extend(responded(&stage));
        Ok(())
    }
}

/// Girth of every triangle's own crossing segment with the plane `y`, summed: an
/// independent section with no chaining.
pub fn soup_girth(mesh: &TriMesh, y: f64) -> f64 {
    let mut soup = 0.0;
    for t in 0..mesh.triangles.len() {
        let p = mesh.corners(t);
        let mut pts = Vec::new();
        for k in 0..3 {
            let (a, b) = (p[k], p[(k + 1) % 3]);
            if (a.y >= y) != (b.y >= y) {
                pts.push(a + (b - a) * ((y - a.y) / (b.y - a.y)));
            }
        }
        if pts.len() == 2 {
            soup += pts[0].distance(pts[1]);
        }
    }
    soup
}

/// The regular octahedron with unit vertices on the axes, outward-facing (valence 4
/// everywhere: subdivision rules are easy to work out by hand on it).
pub fn octahedron() -> TriMesh {
    let positions = vec![DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z];
    // One face per octant, counter-clockwise seen from outside.
    let triangles = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    TriMesh { positions, triangles }
}

/// Whether the segment `p..q` passes through the triangle `[a, b, c]` (Möller and Trumbore,
/// in plain `f64`): the crossing strictly between the ends, in the closed triangle.
pub fn segment_through_triangle(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let d = q - p;
    let (e1, e2) = (b - a, c - a);
    let h = d.cross(e2);
    let det = e1.dot(h);
    if det.abs() < 1e-300 {
        return false;
    }
    let s = p - a;
    let u = s.dot(h) / det;
    let qv = s.cross(e1);
    let v = d.dot(qv) / det;
    let t = e2.dot(qv) / det;
    t > 0.0 && t < 1.0 && u >= 0.0 && v >= 0.0 && u + v <= 1.0
}

/// The faces of `triangles` (at `positions`) that an edge of `body` passes through, by
/// brute force: every body edge against every face whose box its box meets (found
/// through a grid of cells, which only saves time), each tested by
/// [`segment_through_triangle`].
pub fn faces_pierced_by(body: &TriMesh, positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<usize> {
    use std::collections::BTreeMap;
    let cell = 0.02;
    let key = |p: DVec3| (p / cell).floor().as_ivec3().to_array();
    // Each undirected edge once (a set of its sorted ends).
    let mut set = std::collections::BTreeSet::new();
    for t in &body.triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            set.insert((a.min(b), a.max(b)));
        }
    }
    let edges: Vec<[u32; 2]> = set.into_iter().map(|(a, b)| [a, b]).collect();
    let mut grid: BTreeMap<[i32; 3], Vec<usize>> = BTreeMap::new();
    for (e, &[a, b]) in edges.iter().enumerate() {
        let (p, q) = (body.positions[a as usize], body.positions[b as usize]);
        let (lo, hi) = (key(p.min(q)), key(p.max(q)));
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    grid.entry([x, y, z]).or_default().push(e);
                }
            }
        }
    }
    let mut pierced = Vec::new();
    for (f, t) in triangles.iter().enumerate() {
        let tri = t.map(|v| positions[v as usize]);
        let (lo, hi) = (key(tri[0].min(tri[1]).min(tri[2])), key(tri[0].max(tri[1]).max(tri[2])));
        let mut near: Vec<usize> = Vec::new();
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    near.extend(grid.get(&[x, y, z]).into_iter().flatten());
                }
            }
        }
        near.sort_unstable();
        near.dedup();
        let hit = near.iter().any(|&e| {
            let [a, b] = edges[e];
            segment_through_triangle(body.positions[a as usize], body.positions[b as usize], tri)
        });
        if hit {
            pierced.push(f);
        }
    }
    pierced
}

/// The vertex roles of a plain point set: none on an opening or a garment ring, none pinned.
pub struct PlainRoles {
    boundary: Vec<bool>,
    rings: Vec<Option<DVec3>>,
}

impl PlainRoles {
    /// For `n` vertices.
    pub fn new(n: usize) -> Self {
        Self {
            boundary: vec![false; n],
            rings: vec![None; n],
        }
    }

    /// The roles, with `normals` for the vertex normals.
    pub fn with<'a>(&'a self, normals: &'a [DVec3]) -> drape::collision::VertexRoles<'a> {
        drape::collision::VertexRoles {
            normals,
            boundary: &self.boundary,
            ring_normal: &self.rings,
            pinned: &[],
        }
    }
}

/// The private tools venv that the README's test command prepares (`scripts/setup-browser`):
/// `DRAPE_TOOLS_VENV`, else `~/.cache/drape-tools/venv`.
pub fn tools_venv() -> std::path::PathBuf {
    std::env::var_os("DRAPE_TOOLS_VENV").map_or_else(
        || std::path::Path::new(&std::env::var_os("HOME").unwrap_or_default()).join(".cache/drape-tools/venv"),
        std::path::PathBuf::from,
    )
}

/// Rerun's own command (`rerun`, rerun-sdk 0.36.3) from the private tools venv that the
/// README's test command prepares (`scripts/setup-browser`; `DRAPE_TOOLS_VENV` moves it).
/// Missing, the test fails: a check that skips itself on a fresh machine proves nothing.
pub fn rerun_cli() -> std::process::Command {
    let cli = tools_venv().join("bin/rerun");
    assert!(
        cli.exists(),
        "{} is missing: run scripts/setup-browser (the README's test command does), which installs rerun-sdk==0.36.3",
        cli.display()
    );
    std::process::Command::new(cli)
}

/// Cases for a property test: `default` (what keeps the suite quick), or `PROPTEST_CASES`
/// when set, for a long sweep (`PROPTEST_CASES=100000 cargo test --release convexify`).
/// Proptest reads that variable only for configurations that leave `cases` at its default,
/// which every property test here sets.
pub fn proptest_cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
