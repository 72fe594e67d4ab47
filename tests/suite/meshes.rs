//! Mesh validation repairs, checked against meshes whose answer is known.

use drape::mesh::{Adjacency, TriMesh, validate_and_repair};
use glam::DVec3;

/// Validates and repairs; checks the returned adjacency against one rebuilt from scratch.
fn repaired(mesh: &mut TriMesh) -> drape::mesh::MeshReport {
    let (report, adjacency) = validate_and_repair(mesh, "cube", &[]).unwrap();
    assert_eq!(
        adjacency,
        Adjacency::try_new(mesh).unwrap(),
        "adjacency out of step with the repaired winding"
    );
    report
}

fn cube() -> TriMesh {
    let positions = (0..8)
        .map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from((i >> 2) & 1)))
        .collect();
    // Outward-facing (counter-clockwise seen from outside).
    let triangles = vec![
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    TriMesh { positions, triangles }
}

#[test]
fn a_clean_cube_needs_no_repair() {
    let mut mesh = cube();
    let report = repaired(&mut mesh);
    assert_eq!(report.flipped, 0);
    assert_eq!(report.boundary_edges, 0);
    assert_eq!(report.components, 1);
    assert!((mesh.signed_volume() - 1.0).abs() < 1e-15);
    assert!(report.notes().is_empty());
}

#[test]
fn an_inside_out_cube_is_turned_outward() {
    let mut mesh = cube();
    for t in &mut mesh.triangles {
        t.swap(1, 2);
    }
    let report = repaired(&mut mesh);
    assert_eq!(report.flipped, 12);
    assert!((mesh.signed_volume() - 1.0).abs() < 1e-15);
}

#[test]
fn one_flipped_face_is_flipped_back() {
    let mut mesh = cube();
    mesh.triangles[5].swap(0, 1);
    let report = repaired(&mut mesh);
    assert_eq!(report.flipped, 1);
    // Repaired to the original winding, up to a cyclic shift of its corners.
    let original = cube().triangles[5];
    let repaired = mesh.triangles[5];
    assert!(
        (0..3).any(|k| [0, 1, 2].map(|i| repaired[(i + k) % 3]) == original),
        "{repaired:?} vs {original:?}"
    );
    assert!((mesh.signed_volume() - 1.0).abs() < 1e-15);
}

#[test]
fn duplicates_and_repeated_vertices_are_dropped_and_open_edges_reported() {
    let mut mesh = cube();
    mesh.triangles.push([0, 2, 1]); // duplicate
    mesh.triangles.push([3, 3, 7]); // repeats a vertex
    mesh.triangles.remove(11); // opens the mesh
    let report = repaired(&mut mesh);
    assert_eq!(report.dropped_duplicates, 1);
    assert_eq!(report.dropped_repeated_vertex, 1);
    assert_eq!(report.boundary_edges, 3);
    // The hole (one triangle's worth) is closed by a fan of three about its centroid, which
    // lies in the cube's face: the cube is whole again, volume 1.
    assert_eq!(report.holes_filled, 1);
    assert_eq!(mesh.triangles.len(), 11 + 3);
    assert_eq!(mesh.positions.len(), 8 + 1);
    assert!((mesh.signed_volume() - 1.0).abs() < 1e-12, "{}", mesh.signed_volume());
    assert_eq!(Adjacency::try_new(&mesh).unwrap().boundary_edges, 0);
    assert!(
        report
            .notes()
            .iter()
            .any(|n| n.contains("boundary edge") && n.contains("1 hole(s) filled"))
    );
}

#[test]
fn the_real_body_is_closed_and_clean() {
    let body = super::common::real_body();
    let report = &body.mesh.report;
    assert_eq!((report.vertices, report.triangles), (13_380, 26_756));
    assert_eq!((report.boundary_edges, report.flipped, report.components), (0, 0, 1));
    assert_eq!(body.mesh.polygons_triangulated, 13_378);
    // Euler characteristic of a closed genus-0 surface: V - E + F = 2, E = 3F / 2.
    let (v, f) = (report.vertices as i64, report.triangles as i64);
    assert_eq!(v - 3 * f / 2 + f, 2);
}
