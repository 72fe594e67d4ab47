//! Two layers made by hand: concentric open tubes, the outer (coarser, shorter) pushed into
//! the inner at known places. Judged by a brute force written here: the inner tube's cross
//! section is a regular polygon, so a point is behind it exactly when its distance from the
//! axis is less than the polygon's at its angle; every outer edge is tested against every
//! inner face and every inner edge against every outer face with the test's own
//! segment-triangle test; the gap is the distance to the nearest inner triangle.

use std::f64::consts::{PI, TAU};

use drape::layers::{LayerSurface, PushOptions, certify_layers, push_outside};
use drape::mesh::TriMesh;
use glam::DVec3;

use super::common::{segment_through_triangle, triangle_distance};

/// An open tube about the y axis: `around` vertices a ring at radius `r`, the first at
/// angle `turn`, `rings` rings from `y0` to `y1`, its faces facing away from the axis.
fn tube(r: f64, (around, turn): (usize, f64), rings: usize, (y0, y1): (f64, f64)) -> TriMesh {
    let mut positions = Vec::new();
    for i in 0..rings {
        let y = y0 + (y1 - y0) * i as f64 / (rings - 1) as f64;
        for j in 0..around {
            let a = turn + TAU * j as f64 / around as f64;
            positions.push(DVec3::new(r * a.cos(), y, r * a.sin()));
        }
    }
    let id = |i: usize, j: usize| (i * around + j % around) as u32;
    let mut triangles = Vec::new();
    for i in 0..rings - 1 {
        for j in 0..around {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mesh = TriMesh { positions, triangles };
    // Facing away from the axis: the first face's normal points out.
    let [a, b, c] = mesh.triangles[0].map(|v| mesh.positions[v as usize]);
    assert!(
        (b - a).cross(c - a).dot(DVec3::new(a.x, 0.0, a.z)) > 0.0,
        "the tube faces out"
    );
    mesh
}

/// The inner tube's distance from the axis at the angle of `p` (its section is a regular
/// `around`-gon of radius `r`).
fn section_radius(p: DVec3, r: f64, around: usize) -> f64 {
    let step = TAU / around as f64;
    let angle = p.z.atan2(p.x).rem_euclid(TAU);
    let within = angle - (angle / step).floor() * step;
    r * (PI / around as f64).cos() / (within - step / 2.0).cos()
}

/// The undirected edges of `m`, each once, in order.
fn edges(m: &TriMesh) -> Vec<[u32; 2]> {
    let mut e: Vec<[u32; 2]> = m
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])]))
        .collect();
    e.sort_unstable();
    e.dedup();
    e
}

/// Brute-force counts: outer vertices behind the inner tube (inside its section, within
/// its height), outer edges through inner faces, outer faces pierced by inner edges.
fn brute(inner: &TriMesh, outer: &TriMesh, r: f64, around: usize) -> [usize; 3] {
    let behind = outer
        .positions
        .iter()
        .filter(|p| DVec3::new(p.x, 0.0, p.z).length() < section_radius(**p, r, around))
        .count();
    let corners = |m: &TriMesh, t: &[u32; 3]| t.map(|v| m.positions[v as usize]);
    let crossing = edges(outer)
        .iter()
        .filter(|[a, b]| {
            let (p, q) = (outer.positions[*a as usize], outer.positions[*b as usize]);
            inner
                .triangles
                .iter()
                .any(|t| segment_through_triangle(p, q, corners(inner, t)))
        })
        .count();
    let inner_edges = edges(inner);
    let pierced = outer
        .triangles
        .iter()
        .filter(|t| {
            let c = corners(outer, t);
            inner_edges
                .iter()
                .any(|[a, b]| segment_through_triangle(inner.positions[*a as usize], inner.positions[*b as usize], c))
        })
        .count();
    [behind, crossing, pierced]
}

/// The outer tube (`outer_around` by `outer_rings`) dented into the fine inner one, pushed
/// back, and judged; returns the push's report.
fn dented_and_pushed_back(outer_around: usize, outer_rings: usize, along_radius: bool) -> drape::layers::PushReport {
    let (r, around) = (0.20, 60);
    let inner = tube(r, (around, 0.0), 31, (0.0, 1.0));
    // Turned by an angle no vertex of the inner tube is at, so that no outer edge runs
    // exactly through an inner one (the brute force here is in floating point).
    let mut outer = tube(0.21, (outer_around, 0.0123), outer_rings, (0.05, 0.95));
    // Three dents pushing the outer tube in to 17 cm from the axis at their centres.
    let centres: Vec<DVec3> = [(0.3, 0.3), (2.5, 0.5), (4.4, 0.72)]
        .iter()
        .map(|&(angle, y): &(f64, f64)| DVec3::new(0.21 * angle.cos(), y, 0.21 * angle.sin()))
        .collect();
    for &centre in &centres {
        for p in &mut outer.positions {
            let d = p.distance(centre);
            if d < 0.08 {
                let radial = DVec3::new(p.x, 0.0, p.z);
                let depth = 0.04 * (1.0 - d / 0.08);
                let target = (radial.length() - depth).max(0.05);
                *p = radial.normalize() * target + DVec3::Y * p.y;
            }
        }
    }
    let before = brute(&inner, &outer, r, around);
    assert!(
        before.iter().all(|&n| n > 0),
        "the fixture must cross the inner tube: {before:?}"
    );
    let surface = LayerSurface::new(&inner, "inner").expect("the inner tube");
    let counted = certify_layers(&surface, &LayerSurface::new(&outer, "outer").expect("the outer tube"));
    assert_eq!(
        [
            counted.behind,
            counted.outer_edges_through_inner,
            counted.outer_faces_pierced
        ],
        before,
        "the certificate against the brute force, before"
    );
    let ease = 0.003;
    let untouched = outer.clone();
    let options = PushOptions { ease, rounds: 8 };
    // Along the radius (the "body" is the axis), or along the inner tube's normals.
    let radial = |p: DVec3| Some(DVec3::new(p.x, 0.0, p.z).normalize());
    let report = if along_radius {
        drape::layers::push_outside_along(&surface, &mut outer, &options, &radial)
    } else {
        push_outside(&surface, &mut outer, &options)
    }
    .expect("pushed");
    assert_eq!(brute(&inner, &outer, r, around), [0, 0, 0], "{report:?}");
    assert!(report.after.clear(), "{report:?}");
    // Every outer vertex in front of the inner tube by at least the ease; the ones far
    // from the dents (more than two of the outer's longest edges past a dent's reach: a
    // pushed face moves its corners) stay bit for bit.
    let longest = untouched
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .map(|(a, b)| untouched.positions[a as usize].distance(untouched.positions[b as usize]))
        .fold(0.0, f64::max);
    let far = 0.08 + 2.0 * longest;
    for (v, (p, q)) in outer.positions.iter().zip(&untouched.positions).enumerate() {
        let gap = inner
            .triangles
            .iter()
            .map(|t| triangle_distance(*p, t.map(|i| inner.positions[i as usize])))
            .fold(f64::INFINITY, f64::min);
        assert!(
            gap >= ease * (1.0 - 1e-6),
            "vertex {v}: {:.3} mm from the inner tube",
            gap * 1e3
        );
        if centres.iter().all(|c| c.distance(*q) > far) {
            assert_eq!(p, q, "vertex {v}, far from the dents, moved");
        }
    }
    eprintln!("{before:?} -> [0, 0, 0]: {report:?}");
    report
}

#[test]
fn an_outer_tube_pushed_into_the_inner_is_put_back_in_front_by_the_ease() {
    dented_and_pushed_back(44, 23, false);
}

#[test]
fn pushed_along_the_radius_instead_the_outer_tube_is_put_back_in_front_too() {
    dented_and_pushed_back(44, 23, true);
    let report = dented_and_pushed_back(12, 10, true);
    assert!(report.moved > 0, "{report:?}");
}

#[test]
fn a_coarse_outer_tube_over_a_fine_inner_one_needs_its_faces_pushed_too() {
    // Twelve vertices a ring: a face between a dented vertex, put back 3 mm in front, and
    // its neighbours sags through the inner tube's ridges, so the face rounds must run.
    let report = dented_and_pushed_back(12, 10, false);
    assert!(report.rounds > 0, "{report:?}");
}

/// Outer vertices behind the inner surface, by a second reading written here: the nearest
/// inner triangle by brute force (its nearest point inside the triangle, not on an
/// opening), and the side of its plane. Triangles whose box is farther than the nearest so
/// far are skipped (only saves time: a triangle is never nearer than its box).
pub(super) fn behind_by_brute(inner: &TriMesh, outer: &TriMesh) -> usize {
    let corners = |t: &[u32; 3]| t.map(|i| inner.positions[i as usize]);
    let boxes: Vec<(DVec3, DVec3)> = inner
        .triangles
        .iter()
        .map(|t| {
            let c = corners(t);
            (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]))
        })
        .collect();
    outer
        .positions
        .iter()
        .filter(|p| {
            let mut best = (usize::MAX, f64::INFINITY);
            for (t, tri) in inner.triangles.iter().enumerate() {
                let (lo, hi) = boxes[t];
                if (**p - p.clamp(lo, hi)).length() >= best.1 {
                    continue;
                }
                let d = triangle_distance(**p, corners(tri));
                if d < best.1 {
                    best = (t, d);
                }
            }
            let [a, b, c] = corners(&inner.triangles[best.0]);
            let n = (b - a).cross(c - a);
            // Only where the nearest point is inside the face: beside an edge the plane
            // alone does not tell.
            let foot = **p - n * ((**p - a).dot(n) / n.length_squared());
            let inside = [(a, b), (b, c), (c, a)]
                .iter()
                .all(|(u, v)| (*v - *u).cross(foot - *u).dot(n) > 0.0);
            inside && (**p - a).dot(n) < 0.0
        })
        .count()
}

#[test]
fn on_every_shipped_body_an_outer_band_dented_into_an_inner_one_is_put_back_between_it_and_nothing() {
    use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
    use drape::collision::{BodyIndex, SliceOptions};
    for path in super::common::shipped_bodies() {
        let mesh = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("the body loads");
        let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("analysed");
        let index = BodyIndex::new(&body, &SliceOptions::default());
        let skin = &body.mesh.mesh;
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("?").to_string();
        // The inner band 6 mm out; the outer, narrower, 12 mm out with ten dents up to
        // 15 mm deep: into the inner band, some into the body.
        let inner = super::offset_garment::band_clear_of(&body, &index, (0.62, 0.80), 0.006, (0, 0.0));
        let mut outer = super::offset_garment::band_clear_of(&body, &index, (0.64, 0.78), 0.012, (10, 0.015));
        assert_eq!(
            super::import::brute(skin, &inner),
            [0, 0, 0],
            "{name}: the inner band is clear of the body"
        );
        assert_eq!(
            super::import::brute(skin, &outer),
            [0, 0, 0],
            "{name}: the outer band is clear of the body"
        );
        let before = [
            behind_by_brute(&inner, &outer),
            brute_crossings(&inner, &outer),
            brute_crossings(&outer, &inner),
        ];
        assert!(
            before[0] > 0 && before[1] > 0,
            "{name}: the outer band must be dented into the inner: {before:?}"
        );
        let surface = LayerSurface::new(&inner, "inner").expect("the inner band");
        let report = push_outside(&surface, &mut outer, &PushOptions::default()).expect("pushed");
        let after = [
            behind_by_brute(&inner, &outer),
            brute_crossings(&inner, &outer),
            brute_crossings(&outer, &inner),
        ];
        assert_eq!(after, [0, 0, 0], "{name}: {report:?}");
        assert_eq!(
            super::import::brute(skin, &outer),
            [0, 0, 0],
            "{name}: the outer band after the push, against the body"
        );
        eprintln!(
            "{name}: {before:?} -> {after:?}, {} moved, {} rounds",
            report.moved, report.rounds
        );
    }
}

/// Edges of `a` through faces of `b`, by brute force: every edge against every face whose
/// box its box meets (found through a grid of cells, which only saves time).
pub(super) fn brute_crossings(b: &TriMesh, a: &TriMesh) -> usize {
    let cell = 0.02;
    let key = |p: DVec3| (p / cell).floor().as_ivec3().to_array();
    let corners = |t: &[u32; 3]| t.map(|i| b.positions[i as usize]);
    let mut grid: std::collections::BTreeMap<[i32; 3], Vec<usize>> = std::collections::BTreeMap::new();
    for (f, t) in b.triangles.iter().enumerate() {
        let c = corners(t);
        let (lo, hi) = (key(c[0].min(c[1]).min(c[2])), key(c[0].max(c[1]).max(c[2])));
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    grid.entry([x, y, z]).or_default().push(f);
                }
            }
        }
    }
    edges(a)
        .iter()
        .filter(|[u, v]| {
            let (p, q) = (a.positions[*u as usize], a.positions[*v as usize]);
            let (lo, hi) = (key(p.min(q)), key(p.max(q)));
            let mut near = Vec::new();
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        near.extend(grid.get(&[x, y, z]).into_iter().flatten().copied());
                    }
                }
            }
            near.sort_unstable();
            near.dedup();
            near.iter()
                .any(|&f| segment_through_triangle(p, q, corners(&b.triangles[f])))
        })
        .count()
}

#[test]
fn a_malformed_or_non_manifold_layer_is_named() {
    let inner = tube(0.2, (8, 0.0), 3, (0.0, 1.0));
    let mut broken = inner.clone();
    broken.triangles[5][1] = 99;
    let err = LayerSurface::new(&broken, "inner")
        .expect_err("a face past the vertices")
        .to_string();
    assert_eq!(
        err,
        "the inner garment is malformed: face 5 names a vertex past the 24 there are"
    );
    let mut nan = inner.clone();
    nan.positions[3].y = f64::NAN;
    let err = LayerSurface::new(&nan, "outer").expect_err("a NaN").to_string();
    assert_eq!(err, "the outer garment is malformed: vertex 3 is not finite");
    let mut fin = inner.clone();
    let [a, b, _] = fin.triangles[0];
    fin.positions.push(DVec3::new(0.0, 0.5, 0.0));
    fin.triangles.push([a, b, 24]);
    let err = LayerSurface::new(&fin, "inner")
        .expect_err("an edge of three faces")
        .to_string();
    assert!(err.contains("has 3 faces: a layer must be a manifold surface"), "{err}");
}
