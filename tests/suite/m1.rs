//! M1: sqrt(3) subdivision against counts and positions computed here (faces tripled,
//! manifold, consistently oriented, old vertices unmoved, Kobbelt's smoothing by hand on an
//! octahedron), no T-junction at a refined/unrefined border, two steps nine times the faces,
//! and cut lines: stored on M0 and rebuilt on the same M1 to 1e-9 m, and on the surface of
//! a new M1 after a dimension edit (distance to M1's triangles measured here).

use std::collections::BTreeMap;

use drape::m1::{Smoothing, kobbelt_alpha, sqrt3_step};
use drape::mesh::TriMesh;
use drape::session::{M1Outcome, M1Stage, RunOptions, SinkError, StageInfo, StageSink, parse_session, run_session};
use glam::DVec3;

use super::common::{angle, closed_grid, triangle_distance};

/// Directed edges of a mesh with how often each appears.
fn directed(mesh: &TriMesh) -> BTreeMap<[u32; 2], usize> {
    let mut out = BTreeMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            *out.entry([t[k], t[(k + 1) % 3]]).or_insert(0) += 1;
        }
    }
    out
}

/// A closed ellipsoid-like mesh.
fn blob() -> TriMesh {
    closed_grid(
        8,
        12,
        |i, j| {
            let lat = -1.2 + 2.4 * i as f64 / 7.0;
            let t = angle(j, 12);
            DVec3::new(0.3 * lat.cos() * t.cos(), 0.5 * lat.sin(), 0.2 * lat.cos() * t.sin())
        },
        DVec3::new(0.0, -0.5, 0.0),
        DVec3::new(0.0, 0.5, 0.0),
    )
}

#[test]
fn one_step_on_a_closed_mesh_triples_the_faces_keeps_it_manifold_and_oriented_and_moves_no_old_vertex() {
    let mesh = blob();
    let patch = vec![0u32; mesh.triangles.len()];
    let step = sqrt3_step(&mesh, &patch, &[true], Smoothing::None);
    assert_eq!(step.mesh.triangles.len(), 3 * mesh.triangles.len());
    assert_eq!(step.mesh.positions.len(), mesh.positions.len() + mesh.triangles.len());
    // Old vertices unmoved, bit for bit; each new vertex the centroid of its face.
    assert_eq!(step.mesh.positions[..mesh.positions.len()], mesh.positions[..]);
    for (f, t) in mesh.triangles.iter().enumerate() {
        let m = step.centroid_of[f].expect("every face split") as usize;
        let c = t.iter().map(|&v| mesh.positions[v as usize]).sum::<DVec3>() / 3.0;
        assert!(step.mesh.positions[m].distance(c) < 1e-15);
    }
    // Closed, manifold, consistently oriented: every directed edge once, with its twin.
    let d = directed(&step.mesh);
    for (&[a, b], &n) in &d {
        assert_eq!(n, 1, "directed edge {a}->{b} {n} times");
        assert_eq!(d.get(&[b, a]), Some(&1), "edge {a}-{b} has one face");
    }
    // Every old edge flipped: no old-old edge is left.
    let n0 = mesh.positions.len() as u32;
    assert!(d.keys().all(|&[a, b]| a >= n0 || b >= n0));
    // The same volume sign (outward orientation kept).
    assert!(step.mesh.signed_volume() > 0.0 && mesh.signed_volume() > 0.0);
}

#[test]
fn kobbelt_smoothing_on_an_octahedron_matches_the_hand_computed_positions() {
    // Valence 4 everywhere: alpha_4 = (4 - 2 cos(pi / 2)) / 9 = 4 / 9; the four neighbours
    // of (1, 0, 0) sum to zero, so it moves to (1 - 4/9) (1, 0, 0) = (5/9, 0, 0).
    assert!((kobbelt_alpha(4) - 4.0 / 9.0).abs() < 1e-15);
    assert!(
        (kobbelt_alpha(6) / 6.0 - 1.0 / 18.0).abs() < 1e-15,
        "beta = 1/18 at valence 6"
    );
    let mesh = super::common::octahedron();
    assert!(mesh.signed_volume() > 0.0);
    let step = sqrt3_step(&mesh, &[0; 8], &[true], Smoothing::Kobbelt);
    for v in 0..6 {
        let expected = mesh.positions[v] * (5.0 / 9.0);
        assert!(step.mesh.positions[v].distance(expected) < 1e-15, "vertex {v}");
    }
    // The new vertices are the centroids of the faces before smoothing: (1, 1, 1) / 3.
    let m = step.centroid_of[0].expect("split") as usize;
    assert!(step.mesh.positions[m].distance(DVec3::ONE / 3.0) < 1e-15);
}

#[test]
fn a_refined_patch_meets_its_unrefined_neighbour_without_t_junctions() {
    // A flat 6 x 6 grid, two patches: the left half refined (one and two steps).
    let n = 7;
    let positions: Vec<DVec3> = (0..n * n)
        .map(|k| DVec3::new((k % n) as f64, (k / n) as f64, 0.0))
        .collect();
    let mut triangles = Vec::new();
    let mut patch = Vec::new();
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            let v = |a: usize, b: usize| (a * n + b) as u32;
            triangles.push([v(i, j), v(i, j + 1), v(i + 1, j + 1)]);
            triangles.push([v(i, j), v(i + 1, j + 1), v(i + 1, j)]);
            let p = u32::from(j >= 3);
            patch.extend([p, p]);
        }
    }
    let mesh = TriMesh { positions, triangles };
    let boundary_edges = |m: &TriMesh| {
        let d = directed(m);
        d.keys().filter(|&&[a, b]| !d.contains_key(&[b, a])).count()
    };
    assert_eq!(boundary_edges(&mesh), 24, "the grid's outline");
    let left = patch.iter().filter(|&&p| p == 0).count();
    let one = sqrt3_step(&mesh, &patch, &[true, false], Smoothing::None);
    assert_eq!(one.mesh.triangles.len(), mesh.triangles.len() + 2 * left);
    let two = sqrt3_step(&one.mesh, &one.face_patch, &[true, false], Smoothing::None);
    assert_eq!(
        two.mesh.triangles.len(),
        mesh.triangles.len() - left + 9 * left,
        "two steps: nine times"
    );
    for m in [&one.mesh, &two.mesh] {
        // Every directed edge once; an edge with one face only lies on the grid's own
        // outline (the count of outline edges is what it was, and none lies inside).
        let d = directed(m);
        assert!(d.values().all(|&k| k == 1));
        for &[a, b] in d.keys().filter(|&&[a, b]| !d.contains_key(&[b, a])) {
            let (pa, pb) = (m.positions[a as usize], m.positions[b as usize]);
            let on_outline = |p: DVec3| p.x == 0.0 || p.y == 0.0 || p.x == 6.0 || p.y == 6.0;
            assert!(
                on_outline(pa) && on_outline(pb),
                "open edge {pa} - {pb} inside the grid"
            );
        }
        assert_eq!(boundary_edges(m), 24, "the outline is not split (its edges never flip)");
        // The border between the patches keeps every one of its old edges.
        for y in 0..6u32 {
            let (a, b) = (y * 7 + 3, (y + 1) * 7 + 3);
            assert!(
                d.contains_key(&[a, b]) || d.contains_key(&[b, a]),
                "border edge {a}-{b} kept"
            );
        }
    }
}

/// The M1 of every step, as emitted, with M0 (collided) beside it.
#[derive(Default)]
struct M1s(Vec<(usize, M1Outcome, TriMesh)>);

impl StageSink for M1s {
    fn m1(&mut self, info: &StageInfo, stage: M1Stage<'_>) -> Result<(), SinkError> {
        self.0
            .push((info.step, stage.outcome.clone(), stage.m0.collision.mesh.clone()));
        Ok(())
    }
}

fn run(text: &str) -> M1s {
    let session = parse_session(text, "m1.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = M1s::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    sink
}

/// Distance from `p` to the nearest triangle of `mesh` (brute force, written here).
fn to_surface(mesh: &TriMesh, p: DVec3) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| triangle_distance(p, mesh.corners(t)))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn a_cut_line_stored_on_m0_is_rebuilt_on_its_m1_and_follows_a_dimension_edit() {
    let m1s = run("drape 1\nm1\ngarment jumpsuit fit=tight resolution=4\nset ease 0.004\n\
         cut yoke at=0,1.0,0 normal=0,1,0.25\ncut side at=0.05,1.0,0 normal=1,0,0\nset waist_girth +0.06\n");
    // The cut step: the drawn line (the plane's section of M1, computed here from M1's
    // first layer) against its stored form rebuilt on the same M1.
    let (_, at_cut, _) = m1s.0.iter().find(|(s, _, _)| *s == 4).expect("the second cut step");
    assert_eq!(at_cut.stored.len(), 2);
    let m1 = &at_cut.m1;
    let positions = &at_cut.collision.positions;
    let mut flipped = 0;
    for (k, stored) in at_cut.stored.iter().enumerate() {
        let drawn = drape::m1::cut::draw(m1, positions, &stored.plane);
        assert_eq!(drawn.pieces.len(), stored.pieces.len());
        for ((points, _), (rebuilt, _)) in drawn.pieces.iter().zip(&at_cut.cuts[k]) {
            assert_eq!(points.len(), rebuilt.len());
            for (p, q) in points.iter().zip(rebuilt) {
                // On its plane (the test's own check of the drawing) and rebuilt to 1e-9 m.
                let off = (p.position - stored.plane.point).dot(stored.plane.normal.normalize());
                assert!(off.abs() < 1e-12, "{off}");
                assert!(p.position.distance(*q) < 1e-9, "{} vs {q}", p.position);
            }
        }
        flipped += stored
            .pieces
            .iter()
            .flat_map(|(p, _)| p)
            .filter(|p| matches!(p, drape::m1::StoredPoint::Flipped { .. }))
            .count();
    }
    assert!(flipped > 10, "the cuts cross flipped edges ({flipped})");
    // After the waist grows 6 cm: every rebuilt point lies on the new M1's surface.
    let (_, last, m0) = m1s.0.last().expect("the set step");
    let mesh = TriMesh {
        positions: last.collision.positions.clone(),
        triangles: last.m1.mesh.triangles.clone(),
    };
    let mut worst: f64 = 0.0;
    for line in &last.cuts {
        for (points, _) in line {
            for p in points {
                worst = worst.max(to_surface(&mesh, *p));
            }
        }
    }
    assert!(worst < 1e-9, "a rebuilt point {worst} m off M1");
    // Placed on M0 instead (as the recording shows it there), every point lies on M0's
    // surface too: a point on a flipped edge runs over the two faces, not between them.
    let (_, _, m0_at_cut) = m1s.0.iter().find(|(s, _, _)| *s == 4).expect("the second cut step");
    for (stored, m0) in [(&at_cut.stored, m0_at_cut), (&last.stored, m0)] {
        for line in stored {
            for (points, _) in drape::m1::cut::rebuild(None, &m0.triangles, &m0.positions, line) {
                for p in points {
                    let off = to_surface(m0, p);
                    assert!(off < 1e-9, "a point placed {off} m off M0");
                }
            }
        }
    }
    // And the line moved with the garment: the waist cut is not where it was.
    let moved = at_cut.cuts[0][0]
        .0
        .iter()
        .zip(&last.cuts[0][0].0)
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    assert!(moved > 1e-3, "the yoke line did not follow the edit ({moved} m)");
}

/// Without `m1` in the scene, no M1 stage is emitted and no M1 figure or timing is recorded.
#[test]
fn a_scene_without_m1_does_none_of_its_work() {
    let text = "drape 1\ngarment jumpsuit fit=tight resolution=3\nset ease 0.004\n";
    let session = parse_session(text, "plain.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = M1s::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none());
    assert!(sink.0.is_empty(), "an M1 stage was emitted");
    for step in &report.steps {
        let names: Vec<&String> = step.figures.keys().chain(step.timings_ms.keys()).collect();
        assert!(
            names.iter().all(|k| !k.starts_with("m1")),
            "step {}: {names:?}",
            step.step
        );
    }
    // With it, the same session has M1 at both collision steps.
    let with = run(&format!("drape 1\nm1\n{}", &text["drape 1\n".len()..]));
    assert_eq!(with.0.iter().map(|(s, _, _)| *s).collect::<Vec<_>>(), vec![1, 2]);
}

/// A cut whose plane misses the garment is refused with its message; the session goes on,
/// and an `undo` of it changes nothing.
#[test]
fn a_cut_that_misses_the_garment_is_refused_and_the_session_goes_on() {
    let text = "drape 1\nm1\ngarment jumpsuit resolution=3\ncut high at=0,5,0 normal=0,1,0\n\
                cut waist at=0,1.0,0 normal=0,1,0\nundo\nundo\n";
    let session = parse_session(text, "cut.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = M1s::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    let refused: Vec<&String> = report
        .shortfalls
        .iter()
        .filter_map(|(step, s)| match s {
            drape::session::Shortfall::Refused(m) if *step == 2 => Some(m),
            _ => None,
        })
        .collect();
    assert_eq!(
        refused,
        vec!["cut 'high': the plane through (0.0000, 5.0000, 0.0000) m misses the garment: edit refused"]
    );
    // Step 3 drew the waist line; the first undo takes it back, the second the refused cut.
    let cut_lines = |step: usize| {
        sink.0
            .iter()
            .rev()
            .find(|(s, _, _)| *s == step)
            .map(|(_, o, _)| o.stored.len())
    };
    assert_eq!(cut_lines(3), Some(1));
    assert_eq!(cut_lines(4), Some(0));
    assert_eq!(cut_lines(5), Some(0));
}

/// `undirected_edges` and `sorted_edges` (grouped per smaller vertex) against a sort of every
/// face's edges, written here, and `repeated_triangles` against a set of the corners seen
/// so far: random soups with repeated, degenerate and unused vertices, and M1 itself.
#[test]
fn undirected_edges_equal_a_plain_sort_of_every_faces_edges() {
    let reference = |mesh: &TriMesh| {
        let mut all: Vec<[u32; 2]> = Vec::new();
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                all.push([a.min(b), a.max(b)]);
            }
        }
        all.sort();
        all.dedup();
        all
    };
    let mut rng = super::common::Lcg(3);
    for n in [1usize, 2, 5, 40, 300] {
        let triangles: Vec<[u32; 3]> = (0..2 * n)
            .map(|_| std::array::from_fn(|_| (rng.next() * n as f64) as u32))
            .collect();
        let mesh = TriMesh {
            positions: vec![DVec3::ZERO; n + 3],
            triangles,
        };
        assert_eq!(
            drape::mesh::topology::undirected_edges(&mesh),
            reference(&mesh),
            "{n} vertices"
        );
        // The edge records they come from, against a plain sort of them.
        let mut records: Vec<(u32, u32, u32, u8)> = Vec::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3u8 {
                let (a, b) = (tri[k as usize], tri[(k as usize + 1) % 3]);
                records.push((a.min(b), a.max(b), t as u32, k));
            }
        }
        records.sort();
        assert_eq!(drape::mesh::topology::sorted_edges(&mesh), records, "{n} vertices");
        let mut seen = std::collections::BTreeSet::new();
        let repeated: Vec<bool> = mesh
            .triangles
            .iter()
            .map(|t| {
                let mut key = *t;
                key.sort_unstable();
                !seen.insert(key)
            })
            .collect();
        assert_eq!(
            drape::mesh::topology::repeated_triangles(&mesh.triangles),
            repeated,
            "{n} vertices"
        );
        assert!(n > 5 || repeated.contains(&true), "{n} vertices: no repeat tested");
    }
    let empty = TriMesh {
        positions: Vec::new(),
        triangles: Vec::new(),
    };
    assert!(drape::mesh::topology::undirected_edges(&empty).is_empty());
    let m0 = &super::common::real_jumpsuit().m0.mesh;
    assert_eq!(drape::mesh::topology::undirected_edges(m0), reference(m0));
}
