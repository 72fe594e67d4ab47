//! Shared fixtures: the real body (loaded once) and analytic meshes.

use std::sync::OnceLock;

use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::mesh::TriMesh;
use glam::DVec3;

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
