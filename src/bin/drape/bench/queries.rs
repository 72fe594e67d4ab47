//! The collision's queries, measured in this process (run pinned by `drape bench`): cold
//! detection and the exact signed distance of the demo's tight jumpsuit at each resolution,
//! the exact query against the body split into more triangles, and the points, the body and
//! drape's answers written out for the peers to answer the same question.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context as _, anyhow};
use drape::bench::{answers_differing, demo_jumpsuit, median_ms, signed_distances};
use drape::body::{BUILTIN_BODY_OBJ, Body, BodyMesh, LandmarkOptions, PartitionOptions};
use drape::collision::{BodyIndex, DetectOptions, DetectState, SliceOptions, detect};
use drape::garment::BodyProbe;
use drape::mesh::TriMesh;

/// One resolution's figures.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct GarmentQueries {
    pub(crate) resolution: usize,
    pub(crate) vertices: usize,
    /// Cold detection (a fresh state: every vertex tested by its partition's test), us per vertex.
    pub(crate) detect_us: f64,
    /// The exact signed distance over the whole body, us per vertex.
    pub(crate) signed_us: f64,
    /// Vertices detection found inside.
    pub(crate) inside: usize,
}

/// The exact query against the body split flat into `triangles`.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct BodyQueries {
    pub(crate) triangles: usize,
    pub(crate) index_ms: f64,
    pub(crate) signed_us: f64,
    /// Answers (sign, or distance by more than 1 nm) differing from the body as it is.
    pub(crate) differing: usize,
}

/// Everything the queries child reports.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct Queries {
    pub(crate) threads: usize,
    pub(crate) body_triangles: usize,
    pub(crate) index_ms: f64,
    pub(crate) ease: f64,
    pub(crate) garments: Vec<GarmentQueries>,
    pub(crate) bodies: Vec<BodyQueries>,
}

/// The built-in body as its file holds it.
pub(crate) fn builtin_body() -> anyhow::Result<BodyMesh> {
    BodyMesh::from_obj_text(BUILTIN_BODY_OBJ, "builtin", 1.0).map_err(|e| anyhow!("the built-in body: {e}"))
}

/// Writes `values` (each already in little-endian bytes) to `path`.
fn write_le<const N: usize>(path: &Path, values: impl Iterator<Item = [u8; N]>) -> anyhow::Result<()> {
    let out: Vec<u8> = values.flatten().collect();
    std::fs::write(path, out).with_context(|| format!("cannot write {}", path.display()))
}

/// Measures (each figure the median of `runs`), writes the peers' inputs into `export`
/// (body.vertices.f64, body.triangles.u32, resN.points.f64, resN.signed.f64) and returns
/// the figures.
pub(crate) fn measure(resolutions: &[usize], factors: &[usize], runs: usize, export: &Path) -> anyhow::Result<Queries> {
    let body = Body::analyse(
        builtin_body()?,
        &LandmarkOptions::default(),
        &PartitionOptions::default(),
    )
    .map_err(|e| anyhow!("the built-in body: {e}"))?;
    let mut built = None;
    let index_ms = median_ms(runs.min(5), || {
        built = Some(BodyIndex::new(&body, &SliceOptions::default()))
    });
    let probe = BodyProbe::from_index(built.context("the index was built")?);
    let index = probe.index();
    let body_mesh = &body.mesh.mesh;
    std::fs::create_dir_all(export).with_context(|| format!("cannot create {}", export.display()))?;
    write_le(
        &export.join("body.vertices.f64"),
        body_mesh
            .positions
            .iter()
            .flat_map(|p| p.to_array())
            .map(f64::to_le_bytes),
    )?;
    write_le(
        &export.join("body.triangles.u32"),
        body_mesh.triangles.iter().flatten().map(|v| v.to_le_bytes()),
    )?;
    let mut garments = Vec::new();
    let mut ease = 0.0;
    let mut largest = Vec::new();
    for &resolution in resolutions {
        let (g, e) = demo_jumpsuit(&body, &probe, resolution)
            .map_err(|e| anyhow!("the jumpsuit at resolution {resolution}: {e}"))?;
        ease = e;
        let points = &g.mesh.positions;
        let n = points.len().max(1) as f64;
        let input = g.input();
        let options = DetectOptions::default();
        let mut hits = 0;
        let detect_us = median_ms(runs, || {
            hits = detect(index, &input, &options, &mut DetectState::default()).hits.len();
        }) * 1e3
            / n;
        let mut signed = Vec::new();
        let signed_us = median_ms(runs, || signed = signed_distances(index, points)) * 1e3 / n;
        let tag = format!("res{resolution}");
        write_le(
            &export.join(format!("{tag}.points.f64")),
            points.iter().flat_map(|p| p.to_array()).map(f64::to_le_bytes),
        )?;
        write_le(
            &export.join(format!("{tag}.signed.f64")),
            signed.iter().map(|v| v.to_le_bytes()),
        )?;
        garments.push(GarmentQueries {
            resolution,
            vertices: points.len(),
            detect_us,
            signed_us,
            inside: hits,
        });
        largest = points.clone();
    }
    let bodies = body_scaling(body_mesh, factors, &largest, runs)?;
    Ok(Queries {
        threads: drape::par::threads(),
        body_triangles: body_mesh.triangles.len(),
        index_ms,
        ease,
        garments,
        bodies,
    })
}

/// The exact signed distance of `points` against the body split flat into `factors` times
/// its triangles (1, 4, 16, ...: the same surface, so the same answers), one partition.
fn body_scaling(
    mesh: &TriMesh,
    factors: &[usize],
    points: &[glam::DVec3],
    runs: usize,
) -> anyhow::Result<Vec<BodyQueries>> {
    let mut out = Vec::new();
    let mut base: Option<Vec<f64>> = None;
    for &factor in factors {
        let split = split_by(mesh, factor);
        let start = Instant::now();
        let flat =
            BodyIndex::from_mesh(&split).map_err(|e| anyhow!("the body split {factor}x is not manifold: {e:?}"))?;
        let index_ms = start.elapsed().as_secs_f64() * 1e3;
        let mut answers = Vec::new();
        let signed_us =
            median_ms(runs, || answers = signed_distances(&flat, points)) * 1e3 / points.len().max(1) as f64;
        let differing = base.as_ref().map_or(0, |b| answers_differing(b, &answers));
        base.get_or_insert(answers);
        black_box(&flat);
        out.push(BodyQueries {
            triangles: split.triangles.len(),
            index_ms,
            signed_us,
            differing,
        });
    }
    Ok(out)
}

/// `mesh` with each triangle split in four as often as `factor` is a power of 4 (1: as it is).
pub(crate) fn split_by(mesh: &TriMesh, factor: usize) -> TriMesh {
    let mut out = mesh.clone();
    let mut f = factor;
    while f >= 4 {
        out = out.split_in_four();
        f /= 4;
    }
    out
}
