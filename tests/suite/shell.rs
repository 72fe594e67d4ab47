//! Bodies whose surface crosses itself, and gaps the garment bridges, against truths from
//! formulas: two overlapping spheres (inside their union or not, which triangles lie
//! inside the other sphere) and two slabs with a slot between them (where a point in the
//! slot comes out with the ease all round).

use drape::body::index::BodyIndex;
use drape::garment::BodyProbe;
use drape::garment::bridge::{Bridging, bridge, in_gap};
use drape::mesh::TriMesh;
use glam::DVec3;

use super::common::{Lcg, angle, closed_grid};

/// A sphere as a closed, outward-oriented grid (`rings` latitudes of `around` points).
fn sphere(c: DVec3, r: f64, rings: usize, around: usize) -> TriMesh {
    let lat = |i: usize| -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * (i + 1) as f64 / (rings + 1) as f64;
    closed_grid(
        rings,
        around,
        |i, j| {
            let (phi, theta) = (lat(i), angle(j, around));
            c + DVec3::new(phi.cos() * theta.cos(), phi.sin(), phi.cos() * theta.sin()) * r
        },
        c - DVec3::Y * r,
        c + DVec3::Y * r,
    )
}

/// An axis-aligned box, outward-oriented.
fn cuboid(lo: DVec3, hi: DVec3) -> TriMesh {
    let positions = (0..8)
        .map(|k| {
            DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    let triangles = vec![
        [0, 2, 3],
        [0, 3, 1], // z = lo
        [4, 5, 7],
        [4, 7, 6], // z = hi
        [0, 1, 5],
        [0, 5, 4], // y = lo
        [2, 6, 7],
        [2, 7, 3], // y = hi
        [0, 4, 6],
        [0, 6, 2], // x = lo
        [1, 3, 7],
        [1, 7, 5], // x = hi
    ];
    TriMesh { positions, triangles }
}

/// One mesh of several closed parts (which may overlap).
fn union(parts: &[TriMesh]) -> TriMesh {
    let mut out = TriMesh {
        positions: Vec::new(),
        triangles: Vec::new(),
    };
    for p in parts {
        let base = out.positions.len() as u32;
        out.positions.extend(&p.positions);
        out.triangles.extend(p.triangles.iter().map(|t| t.map(|i| i + base)));
    }
    out
}

#[test]
fn a_self_crossing_body_is_measured_by_the_union_of_its_parts() {
    let (ca, cb, r) = (DVec3::ZERO, DVec3::new(1.2, 0.1, 0.0), 1.0);
    let a = sphere(ca, r, 30, 60);
    let b = sphere(cb, r, 30, 60);
    assert!(a.signed_volume() > 0.0 && b.signed_volume() > 0.0, "outward");
    let (na, mesh) = (a.triangles.len(), union(&[a, b]));
    let index = BodyIndex::from_mesh(&mesh).expect("manifold");
    // Buried: a triangle of one sphere whose corners all lie inside the other.
    let inside_other = |t: usize, p: DVec3| {
        let c = if t < na { cb } else { ca };
        p.distance(c) < r
    };
    let mut buried_truth = 0;
    for t in 0..mesh.triangles.len() {
        let corners = mesh.triangles[t].map(|i| mesh.positions[i as usize]);
        let all_in = corners.iter().all(|&p| inside_other(t, p));
        let all_out = corners.iter().all(|&p| !inside_other(t, p));
        if all_in || all_out {
            assert_eq!(index.shell.buried[t], all_in, "triangle {t}");
            buried_truth += usize::from(all_in);
        }
    }
    assert!(buried_truth > 100, "the spheres overlap: {buried_truth}");
    // Inside the union or not, at random points away from either surface (the facets stand
    // at most r (1 - cos(pi / 30)) = 5.5 mm inside the true spheres).
    let mut rng = Lcg(13);
    let mut checked = (0, 0);
    for _ in 0..4000 {
        let p = DVec3::new(
            -1.3 + 3.8 * rng.next(),
            -1.3 + 2.6 * rng.next(),
            -1.3 + 2.6 * rng.next(),
        );
        let (da, db) = (p.distance(ca) - r, p.distance(cb) - r);
        if da.abs() < 0.02 || db.abs() < 0.02 {
            continue;
        }
        let inside = da < 0.0 || db < 0.0;
        let s = index.signed_distance(p, 10.0).expect("near");
        assert_eq!(s < 0.0, inside, "{p}: signed distance {s}");
        if inside {
            checked.0 += 1;
        } else {
            // Outside, the distance to the union is the nearer sphere's.
            assert!((s - da.min(db)).abs() < 0.006, "{p}: {s} vs {}", da.min(db));
            checked.1 += 1;
        }
    }
    assert!(checked.0 > 500 && checked.1 > 500, "{checked:?}");
}

/// Two slabs `x < -w/2` and `x > w/2` (y and z in [-1, 0]), the slot between them open at
/// `z = 0`.
fn slot(w: f64) -> BodyProbe {
    let mesh = union(&[
        cuboid(DVec3::new(-1.0, -1.0, -1.0), DVec3::new(-0.5 * w, 1.0, 0.0)),
        cuboid(DVec3::new(0.5 * w, -1.0, -1.0), DVec3::new(1.0, 1.0, 0.0)),
    ]);
    BodyProbe::from_index(BodyIndex::from_mesh(&mesh).expect("manifold"))
}

#[test]
fn a_point_in_a_gap_narrower_than_twice_the_ease_comes_out_with_the_ease_all_round() {
    let (w, gap) = (0.02, 0.02);
    let probe = slot(w);
    let b = Bridging {
        gap,
        width: 2.0 * gap,
        reach: 1.0,
    };
    let p = DVec3::new(0.0, 0.0, -0.5);
    assert!(in_gap(&probe, p, b.width));
    let q = bridge(&probe, p, DVec3::Z, &b);
    // Out of the slot, the nearest skin is the slabs' top edges at x = -w/2, w/2: the ease
    // all round first at z = sqrt(gap^2 - (w / 2)^2).
    let z = (gap * gap - 0.25 * w * w).sqrt();
    assert!(q.x == 0.0 && q.y == 0.0 && q.z > 0.0, "{q}");
    let has = (0.25 * w * w + q.z * q.z).sqrt();
    assert!((has - gap).abs() <= 1e-6 * gap, "{} vs {z}: {has} m off", q.z);
    // A slot wide enough for the garment is entered: the point stays, bit for bit.
    let wide = slot(0.1);
    assert!(!in_gap(&wide, p, b.width));
    assert_eq!(bridge(&wide, p, DVec3::Z, &b), p);
    // Near one wall only (above a slab, nothing behind): left where it is.
    let above = DVec3::new(0.5, 0.0, 0.005);
    assert!(!in_gap(&probe, above, b.width));
    assert_eq!(bridge(&probe, above, DVec3::Z, &b), above);
    // A slot deeper than the reach: left where it is.
    let short = Bridging { reach: 0.1, ..b };
    assert_eq!(bridge(&probe, p, DVec3::Z, &short), p);
}

/// The generalized winding number of the closed mesh at `p` (van Oosterom and Strackee's
/// solid angle of every triangle, summed over 4 pi), written here: 1 inside one part of
/// the body, 2 where two parts overlap, 0 outside, whatever the surface's self-crossings.
fn solid_angle_winding(mesh: &TriMesh, p: DVec3) -> f64 {
    let mut total = 0.0;
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t).map(|q| q - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let det = a.dot(b.cross(c));
        let div = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * det.atan2(div);
    }
    total / (4.0 * std::f64::consts::PI)
}

/// On every shipped body, around the crotch (where the heavy body's thighs pass through
/// each other) the body index's sign says inside exactly where the winding number is at
/// least one: a box of 0.16 x 0.12 x 0.16 of the height about the crotch point, 12 x 15 x 12
/// points, and points 0.1, 0.3 and 1% of the height either side of every triangle that
/// crosses or lies inside another part, each at least 0.1 mm off the surface (where the
/// sign is a matter of rounding).
#[test]
fn on_every_shipped_body_the_sign_is_the_winding_numbers_at_the_crotch_and_every_self_crossing() {
    use drape::body::{Body, BodyMesh, BodySource, LandmarkKind, LandmarkOptions, PartitionOptions, Side};
    use drape::collision::SliceOptions;
    // Points next to a self-crossing, outside and inside, over all bodies.
    let mut near_crossing = [0usize; 2];
    for path in super::common::shipped_bodies() {
        let mesh = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("loads");
        let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("analyses");
        let index = BodyIndex::new(&body, &SliceOptions::default());
        let h = index.height;
        let crotch = DVec3::from(
            body.landmarks
                .get(LandmarkKind::Crotch, Side::Centre)
                .expect("crotch")
                .point,
        );
        let (nx, ny, nz) = (12, 15, 12);
        let at = |i: usize, n: usize, half: f64| (i as f64 + 0.5) / n as f64 * 2.0 * half - half;
        let mut points: Vec<DVec3> = (0..nx * ny * nz)
            .map(|k| {
                let (i, j, l) = (k % nx, (k / nx) % ny, k / (nx * ny));
                crotch + DVec3::new(at(i, nx, 0.08 * h), at(j, ny, 0.06 * h), at(l, nz, 0.08 * h))
            })
            .collect();
        let mesh = &body.mesh.mesh;
        let shell = &index.shell;
        let grid = points.len();
        for t in (0..mesh.triangles.len()).filter(|&t| shell.crossing_at[t] || shell.buried[t]) {
            let [a, b, c] = mesh.corners(t);
            let n = (b - a).cross(c - a).normalize();
            for d in [-0.01, -0.003, -0.001, 0.001, 0.003, 0.01] {
                points.push((a + b + c) / 3.0 + n * d * h);
            }
        }
        let verdicts = drape::par::par_map(points.len(), |k| {
            let p = points[k];
            let s = index.signed_distance(p, 2.0 * h).expect("near");
            (s.abs() > 1e-4).then(|| (s < 0.0, solid_angle_winding(mesh, p)))
        });
        let mut wrong = Vec::new();
        for (k, v) in verdicts.iter().enumerate() {
            if let Some((inside, w)) = *v {
                if k >= grid {
                    near_crossing[usize::from(inside)] += 1;
                }
                if inside != (w > 0.5) {
                    wrong.push((points[k], w));
                }
            }
        }
        assert!(
            wrong.is_empty(),
            "{}: {} of {} points, e.g. {:?}",
            path.display(),
            wrong.len(),
            points.len(),
            &wrong[..wrong.len().min(5)]
        );
    }
    // The test does reach the self-crossings, on both sides.
    assert!(near_crossing[0] > 100 && near_crossing[1] > 100, "{near_crossing:?}");
}
