//! Sculpting: Loop's rules against hand-computed positions, uniform and adaptive
//! subdivision checked for manifoldness, orientation and T-junctions by edge counts, the
//! falloff by finite differences and the drag by the test's own formula, and a push into
//! the body judged by ray parity.

use std::collections::BTreeMap;

use drape::mesh::TriMesh;
use drape::sculpt::{
    AdaptiveOptions, Drag, Falloff, SculptOptions, compare, displace, loop_beta, refine, uniform_step,
};
use glam::DVec3;

use super::common::{closed_grid, inside_by_parity, octahedron, real_body, real_jumpsuit};

/// A control point of the shipped jumpsuit.
fn control(name: &str) -> DVec3 {
    real_jumpsuit()
        .control_points()
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no control point {name}"))
        .1
}

fn sphere() -> TriMesh {
    let (rings, around) = (12, 24);
    closed_grid(
        rings,
        around,
        |i, j| {
            let lat = std::f64::consts::PI * (i as f64 + 1.0) / (rings as f64 + 1.0);
            let lon = std::f64::consts::TAU * j as f64 / around as f64;
            0.1 * DVec3::new(lat.sin() * lon.cos(), -lat.cos(), -lat.sin() * lon.sin())
        },
        DVec3::new(0.0, -0.1, 0.0),
        DVec3::new(0.0, 0.1, 0.0),
    )
}

/// Directed edges with their counts.
fn directed(mesh: &TriMesh) -> BTreeMap<(u32, u32), usize> {
    let mut out = BTreeMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            *out.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    out
}

/// A closed mesh is manifold and consistently oriented exactly when every directed edge
/// appears once and its reverse once too (a T-junction leaves an edge without its twin).
fn assert_closed_oriented(mesh: &TriMesh, what: &str) {
    let d = directed(mesh);
    for (&(a, b), &n) in &d {
        assert_eq!(n, 1, "{what}: directed edge {a}->{b} used {n} times");
        assert!(d.contains_key(&(b, a)), "{what}: edge {a}->{b} has no twin");
    }
}

fn near(a: DVec3, b: DVec3) -> bool {
    a.distance(b) < 1e-12
}

#[test]
fn loop_rules_match_hand_computed_positions() {
    // beta_n by hand: n = 3: (5/8 - (3/8 - 1/8)^2) / 3 = (40/64 - 4/64) / 3 = 3/16;
    // n = 6: (5/8 - (3/8 + 1/8)^2) / 6 = (40/64 - 16/64) / 6 = 1/16.
    assert!((loop_beta(3) - 3.0 / 16.0).abs() < 1e-15);
    assert!((loop_beta(6) - 1.0 / 16.0).abs() < 1e-15);
    // Octahedron: valence 4, beta_4 = (5/8 - 9/64) / 4 = 31/256; the vertex (1,0,0) has
    // neighbours summing to zero, so it moves to (1 - 4 * 31/256) = 33/64 along x. The
    // edge (1,0,0)-(0,1,0) has opposite corners (0,0,1) and (0,0,-1): 3/8 (1,1,0).
    let oct = octahedron();
    let step = uniform_step(&oct, 1.0);
    assert!(near(step.mesh.positions[0], DVec3::new(33.0 / 64.0, 0.0, 0.0)));
    let k = step.edges.iter().position(|&e| e == [0, 2]).expect("edge 0-2");
    assert!(near(step.mesh.positions[6 + k], DVec3::new(0.375, 0.375, 0.0)));
    // One triangle: every edge and corner is on the opening. Corner (0,0,0) between
    // (1,0,0) and (0,1,0): 3/4 * 0 + 1/8 (1,1,0). Edge points: midpoints.
    let tri = TriMesh {
        positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        triangles: vec![[0, 1, 2]],
    };
    let step = uniform_step(&tri, 1.0);
    assert!(near(step.mesh.positions[0], DVec3::new(0.125, 0.125, 0.0)));
    assert!(near(step.mesh.positions[1], DVec3::new(0.75, 0.125, 0.0)));
    let k = step.edges.iter().position(|&e| e == [0, 1]).expect("edge 0-1");
    assert!(near(step.mesh.positions[3 + k], DVec3::new(0.5, 0.0, 0.0)));
    // Weight 0 keeps the old vertices; weight 1/2 goes half way.
    let kept = uniform_step(&oct, 0.0);
    assert_eq!(&kept.mesh.positions[..6], &oct.positions[..]);
    let half = uniform_step(&oct, 0.5);
    assert!(near(
        half.mesh.positions[0],
        DVec3::new(1.0 - 2.0 * 31.0 / 256.0, 0.0, 0.0)
    ));
}

#[test]
fn a_uniform_step_gives_four_times_the_faces_manifold_and_consistently_oriented() {
    for (what, mesh) in [("octahedron", octahedron()), ("sphere", sphere())] {
        let step = uniform_step(&mesh, 1.0);
        assert_eq!(step.mesh.triangles.len(), 4 * mesh.triangles.len(), "{what}");
        assert_closed_oriented(&step.mesh, what);
        assert!(step.mesh.signed_volume() > 0.0, "{what}: still outward-facing");
        // Two steps: still closed and oriented.
        assert_closed_oriented(&uniform_step(&step.mesh, 1.0).mesh, what);
    }
    // The garment (open): no directed edge twice, and an edge without a twin only where
    // the input had an opening edge (both of its ends descend from one).
    let m0 = &real_jumpsuit().m0.mesh;
    let step = uniform_step(m0, 1.0);
    assert_eq!(step.mesh.triangles.len(), 4 * m0.triangles.len());
    let before = directed(m0);
    let opening: Vec<(u32, u32)> = before
        .keys()
        .filter(|(a, b)| !before.contains_key(&(*b, *a)))
        .copied()
        .collect();
    let after = directed(&step.mesh);
    let n = m0.positions.len() as u32;
    let mut open_after = 0;
    for (&(a, b), &count) in &after {
        assert_eq!(count, 1, "garment: directed edge {a}->{b} twice");
        if !after.contains_key(&(b, a)) {
            open_after += 1;
            // One end is an old vertex of an opening edge, the other its split point.
            let (old, new) = if a < n { (a, b) } else { (b, a) };
            let [p, q] = step.edges[(new - n) as usize];
            assert!(old == p || old == q);
            assert!(opening.contains(&(p, q)) || opening.contains(&(q, p)));
        }
    }
    assert_eq!(open_after, 2 * opening.len(), "each opening edge becomes two");
}

#[test]
fn adaptive_refinement_ends_below_epsilon_without_t_junctions() {
    let s = sphere();
    let drag = Drag::new(DVec3::new(0.1, 0.0, 0.0), 0.06, 0.05);
    let moved = displace(&s, &s.vertex_normals(), &drag).expect("drag");
    let mut region = vec![false; s.triangles.len()];
    for &t in &moved.region {
        region[t as usize] = true;
    }
    let dragged = TriMesh {
        positions: moved.positions.clone(),
        triangles: s.triangles.clone(),
    };
    for (epsilon, levels) in [(0.02, 6), (0.008, 6), (0.001, 2)] {
        let r = refine(
            &dragged,
            &region,
            &AdaptiveOptions {
                epsilon,
                max_levels: levels,
                weight: 1.0,
            },
        );
        assert_closed_oriented(&r.mesh, &format!("epsilon {epsilon}"));
        assert!(r.mesh.signed_volume() > 0.0);
        // The longest edge of a region face, recomputed here.
        let longest = r
            .mesh
            .triangles
            .iter()
            .zip(&r.region)
            .filter(|(_, inside)| **inside)
            .flat_map(|(t, _)| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .map(|(a, b)| r.mesh.positions[a as usize].distance(r.mesh.positions[b as usize]))
            .fold(0.0, f64::max);
        if r.limited {
            assert_eq!(r.levels.len(), levels, "the limit is reported when reached");
            assert!(longest > epsilon);
        } else {
            assert!(longest <= epsilon, "epsilon {epsilon}: longest region edge {longest}");
        }
        // Faces outside the region, and far from it, are untouched.
        let far: Vec<usize> = (0..s.positions.len())
            .filter(|&v| s.positions[v].distance(moved.pick.point) > 0.1)
            .collect();
        for v in far {
            assert_eq!(r.mesh.positions[v], dragged.positions[v]);
        }
        assert!(r.mesh.triangles.len() < 4usize.pow(r.levels.len() as u32) * s.triangles.len() || r.levels.len() <= 1);
    }
    // The same on the open garment with the interpolating weight: the opening stays where
    // it was (every edge without a twin lies on an edge of the input's openings).
    let m0 = &real_jumpsuit().m0.mesh;
    let at = control("waist.front");
    let moved = displace(m0, &m0.vertex_normals(), &Drag::new(at, 0.08, 0.04)).expect("drag");
    let region: Vec<bool> = (0..m0.triangles.len() as u32)
        .map(|t| moved.region.binary_search(&t).is_ok())
        .collect();
    let dragged = TriMesh {
        positions: moved.positions.clone(),
        triangles: m0.triangles.clone(),
    };
    let r = refine(
        &dragged,
        &region,
        &AdaptiveOptions {
            epsilon: 0.01,
            max_levels: 6,
            weight: 0.0,
        },
    );
    assert!(!r.limited && r.levels.len() >= 2);
    let d = directed(&r.mesh);
    let before = directed(m0);
    let openings: Vec<[DVec3; 2]> = before
        .keys()
        .filter(|(a, b)| !before.contains_key(&(*b, *a)))
        .map(|&(a, b)| [dragged.positions[a as usize], dragged.positions[b as usize]])
        .collect();
    for (&(a, b), &n) in &d {
        assert_eq!(n, 1);
        if !d.contains_key(&(b, a)) {
            let mid = 0.5 * (r.mesh.positions[a as usize] + r.mesh.positions[b as usize]);
            let on_opening = openings
                .iter()
                .any(|[p, q]| super::common::segment_distance(mid, *p, *q) < 1e-9);
            assert!(
                on_opening,
                "edge {a}->{b} without a twin inside the garment: a T-junction"
            );
        }
    }
}

/// The biweight falloff written out here.
fn biweight(t: f64) -> f64 {
    if t >= 1.0 { 0.0 } else { (1.0 - t * t).powi(2) }
}

#[test]
fn the_falloff_is_continuous_with_zero_slope_at_the_radius_and_nothing_beyond_moves() {
    for f in Falloff::ALL {
        assert_eq!(f.value(0.0), 1.0, "{}", f.name());
        assert_eq!(f.value(1.0), 0.0);
        assert_eq!(f.value(1.5), 0.0);
        // Continuous at 1 with zero slope: the one-sided difference quotient vanishes
        // like h (a non-zero slope would leave it at that slope).
        for h in [1e-2, 1e-3, 1e-4] {
            let quotient = (f.value(1.0) - f.value(1.0 - h)) / h;
            assert!(quotient.abs() < 10.0 * h, "{}: slope {quotient} at h = {h}", f.name());
        }
        // Zero slope at the peak too, and the analytic slope agrees with central
        // differences everywhere inside.
        assert!((f.value(1e-4) - 1.0).abs() < 1e-6);
        for k in 1..100 {
            let t = k as f64 / 100.0;
            let h = 1e-6;
            let fd = (f.value(t + h) - f.value(t - h)) / (2.0 * h);
            assert!(
                (fd - f.slope(t)).abs() < 1e-6,
                "{} at {t}: {fd} vs {}",
                f.name(),
                f.slope(t)
            );
            assert!((0.0..=1.0).contains(&f.value(t)));
        }
    }
    // The drag on the garment: within the radius every vertex moves by exactly
    // peak * (1 - (d/r)^2)^2 along the pick's normal; beyond it none moves.
    let m0 = &real_jumpsuit().m0.mesh;
    let at = control("bust.front");
    let (radius, peak) = (0.07, 0.02);
    let moved = displace(m0, &m0.vertex_normals(), &Drag::new(at, radius, peak)).expect("drag");
    let pick = moved.pick.point;
    let mut within = 0;
    for (v, p) in m0.positions.iter().enumerate() {
        let d = p.distance(pick);
        let shift = moved.positions[v] - *p;
        if d >= radius {
            assert_eq!(shift, DVec3::ZERO, "vertex {v} at {d} m moved");
        } else {
            within += 1;
            let want = moved.direction * peak * biweight(d / radius);
            assert!(shift.distance(want) < 1e-15, "vertex {v}: {shift} vs {want}");
        }
    }
    assert!(within > 20, "{within} vertices within the radius");
    assert!((moved.direction.length() - 1.0).abs() < 1e-12);
}

#[test]
fn adaptive_reaches_uniform_loops_longest_edge_with_fewer_faces() {
    let m0 = &real_jumpsuit().m0.mesh;
    let at = control("waist.front");
    let cmp = compare(m0, &Drag::new(at, 0.08, 0.04), &SculptOptions::default()).expect("compare");
    assert_eq!(cmp.none.mesh.triangles.len(), m0.triangles.len());
    assert_eq!(
        cmp.uniform.mesh.triangles.len(),
        m0.triangles.len() * 4usize.pow(cmp.uniform.levels as u32)
    );
    let longest = |v: &drape::sculpt::Variant| {
        v.mesh
            .triangles
            .iter()
            .zip(&v.region)
            .filter(|(_, r)| **r)
            .flat_map(|(t, _)| {
                (0..3).map(move |k| v.mesh.positions[t[k] as usize].distance(v.mesh.positions[t[(k + 1) % 3] as usize]))
            })
            .fold(0.0, f64::max)
    };
    assert!(
        longest(&cmp.none) > cmp.epsilon,
        "the drag stretched the mesh past epsilon"
    );
    assert!(longest(&cmp.uniform) <= cmp.epsilon && longest(&cmp.adaptive) <= cmp.epsilon);
    assert!(longest(&cmp.adaptive_matched) <= longest(&cmp.uniform));
    assert!(cmp.adaptive.mesh.triangles.len() < cmp.uniform.mesh.triangles.len());
    assert!(2 * cmp.adaptive_matched.mesh.triangles.len() < cmp.uniform.mesh.triangles.len());
}

/// A sculpt stage seen: its base, its mesh after, and the vertices stopped at the body.
type SculptSeen = (TriMesh, TriMesh, usize);

/// The sculpt stages of a session: (step, what it made, refused).
#[derive(Default)]
struct Sculpts(Vec<(usize, Option<SculptSeen>, bool)>);

impl drape::session::StageSink for Sculpts {
    fn sculpt(
        &mut self,
        info: &drape::session::StageInfo,
        stage: drape::session::SculptStage<'_>,
    ) -> Result<(), drape::session::SinkError> {
        let seen = stage
            .outcome
            .map(|o| (o.base.clone(), o.mesh(), o.sculpt.displacement.stopped));
        self.0.push((info.step, seen, stage.refused.is_some()));
        Ok(())
    }
}

fn run(text: &str) -> (drape::session::RunReport, Sculpts) {
    let session = drape::session::parse_session(text, "sculpt-test.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = Sculpts::default();
    let report = drape::session::run_session(&session, &drape::session::RunOptions::default(), &mut [&mut sink]);
    (report, sink)
}

#[test]
fn a_sculpt_pushed_into_the_body_ends_with_no_garment_vertex_inside_it() {
    let (report, seen) = run("drape 1\nbody builtin\ngarment jumpsuit fit=tight resolution=6\n\
         sculpt at=waist.front radius=0.1 peak=-0.08\nsculpt at=hip.back radius=0.08 peak=-0.06 weight=0.5\n");
    assert!(report.error.is_none(), "{:?}", report.error);
    let body = &real_body().mesh.mesh;
    assert_eq!(seen.0.len(), 2);
    for (step, outcome, refused) in &seen.0 {
        assert!(!refused);
        let (base, after, stopped) = outcome.as_ref().expect("a sculpt");
        assert!(*stopped > 0, "step {step}: the push reached the body");
        // The push is real: the drag without the body would put vertices inside.
        let normals = base.vertex_normals();
        let (at, r, h) = if *step == 2 {
            ("waist.front", 0.1, -0.08)
        } else {
            ("hip.back", 0.08, -0.06)
        };
        let pick = control(at);
        let free = displace(base, &normals, &Drag::new(pick, r, h)).expect("drag");
        let would = free
            .offsets
            .iter()
            .filter(|(v, _)| inside_by_parity(body, free.positions[*v as usize]))
            .count();
        assert!(would > 0, "step {step}: no vertex would be inside");
        // After the sculpt: no vertex inside, by parity.
        let inside: Vec<usize> = (0..after.positions.len())
            .filter(|&v| inside_by_parity(body, after.positions[v]))
            .collect();
        assert!(inside.is_empty(), "step {step}: vertices inside {inside:?}");
        assert!(after.triangles.len() > base.triangles.len());
    }
}

#[test]
fn a_sculpt_is_undone_and_made_again_after_a_dimension_change() {
    let (report, seen) = run("drape 1\nbody builtin\nm1\ngarment jumpsuit fit=tight resolution=6\n\
         sculpt at=waist.front radius=0.08 peak=0.03\nsculpt at=bust.front radius=0.06 peak=0.02\nundo\n\
         set waist_girth +0.02\nundo\nundo\n");
    assert!(report.error.is_none(), "{:?}", report.error);
    let by_step: Vec<(usize, Option<usize>)> = seen
        .0
        .iter()
        .map(|(s, o, _)| (*s, o.as_ref().map(|(_, m, _)| m.triangles.len())))
        .collect();
    let faces = |step: usize| by_step.iter().rev().find(|(s, _)| *s == step).and_then(|(_, f)| *f);
    // Step 4 undoes the second sculpt: the first sculpt's mesh again.
    assert_eq!(faces(4), faces(2));
    // The set remakes the first sculpt on the new garment; its undo returns to step 2's.
    assert!(faces(5).is_some());
    assert_eq!(faces(6), faces(2));
    // The last undo takes the sculpt away: a cleared stage.
    assert_eq!(by_step.last(), Some(&(7, None)));
}

#[test]
fn bad_sculpt_statements_name_the_problem() {
    for (text, want) in [
        (
            "sculpt at=waist.front radius=0.08 peak=0.03",
            "'sculpt' needs a garment",
        ),
        (
            "garment jumpsuit\nsculpt at=waist.frnt radius=0.08 peak=0.03",
            "unknown control point 'waist.frnt'",
        ),
        (
            "garment jumpsuit\nsculpt at=waist.front radius=0 peak=0.03",
            "the radius must be a positive length",
        ),
        (
            "garment jumpsuit\nsculpt at=waist.front radius=0.08",
            "'sculpt' needs peak=",
        ),
        (
            "garment jumpsuit\nsculpt at=waist.front radius=0.08 peak=0.01 weight=2",
            "the weight must be from 0 to 1",
        ),
        (
            "garment jumpsuit\nsculpt at=waist.front radius=0.08 peak=0.01 dir=0,0,0",
            "dir must not be zero",
        ),
        (
            "garment jumpsuit\nsculpt at=waist.front radius=0.08 peak=0.01 falloff=cosine",
            "unknown falloff 'cosine'",
        ),
        (
            "garment jumpsuit\nsculpt at=1,2 radius=0.08 peak=0.01",
            "expected at=x,y,z",
        ),
    ] {
        let e = drape::session::parse_session(&format!("drape 1\n{text}\n"), "bad.drape", std::path::Path::new("."))
            .expect_err(text);
        assert!(e.message.contains(want), "{text}: {}", e.message);
    }
    // A pick far from the garment fails the step, naming the distance and the nearest point.
    let (report, _) = run("drape 1\ngarment jumpsuit\nsculpt at=0,1.0,0.6 radius=0.05 peak=0.01\n");
    let e = report.error.expect("fails");
    assert!(
        e.message().contains("farther than the radius 0.05 m"),
        "{}",
        e.message()
    );
}
