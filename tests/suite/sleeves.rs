//! Sleeves and collars, the type-I parts: the reference-plane interpolation against the
//! paper's linear blend written here, the cap and cuff rings in their planes after edits
//! (by a plane through their own points, Newell's normal computed here), one welded mesh
//! per garment open only at the hem, the cuffs and the collar's top (by an edge count
//! written here), and the three-sided patches meeting their neighbours without T-junctions.

use std::collections::BTreeMap;
use std::path::Path;

use drape::garment::template::sleeve::{RingFrame, interpolate};
use drape::garment::{Collar, Dimensions, Framework, FrameworkOptions, Sleeves, Style, TemplateKind, build_framework};
use drape::geom::{Plane, section_mesh};
use drape::session::{
    GarmentPart, GarmentStage, RunOptions, SinkError, StageInfo, StageSink, parse_session, run_session,
};
use glam::{DVec2, DVec3};

use super::common::{real_body, real_probe};

/// The shirt (long sleeves, stand collar) on the shipped body.
fn shirt(style: Style, kind: TemplateKind) -> Framework {
    build_framework(
        real_body(),
        real_probe(),
        kind,
        &Dimensions::default(),
        &FrameworkOptions::default().with_style(style),
    )
    .expect("builds")
}

const LONG: Style = Style {
    sleeves: Sleeves::Long,
    collar: Collar::Stand,
};

/// The sleeve's axis as the test reads it: the arm's centre line from the shoulder point to
/// the elbow and on to the wrist, and the point `s` metres along it.
struct Axis {
    shoulder: DVec3,
    elbow: DVec3,
    wrist: DVec3,
}

impl Axis {
    fn left() -> Self {
        let arm = &real_body().landmarks.arm_axis[0];
        Self {
            shoulder: arm.points[0],
            elbow: arm.points[arm.elbow],
            wrist: *arm.points.last().expect("an arm"),
        }
    }

    fn upper(&self) -> f64 {
        self.shoulder.distance(self.elbow)
    }

    fn point(&self, s: f64) -> DVec3 {
        if s <= self.upper() {
            self.shoulder + (self.elbow - self.shoulder).normalize() * s
        } else {
            self.elbow + (self.wrist - self.elbow).normalize() * (s - self.upper())
        }
    }

    /// The unit normal up the sleeve at `s`.
    fn up(&self, s: f64) -> DVec3 {
        if s < self.upper() {
            (self.shoulder - self.elbow).normalize()
        } else {
            (self.elbow - self.wrist).normalize()
        }
    }
}

/// `p` inside the closed polygon `ring` (both in `plane`), and its distance to the
/// polygon's edges.
fn inside_by(plane: &Plane, ring: &[DVec3], p: DVec3) -> (bool, f64) {
    let flat: Vec<DVec2> = ring.iter().map(|q| plane.project(*q)).collect();
    let q = plane.project(p);
    let n = flat.len();
    let mut inside = false;
    let mut nearest = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (flat[i], flat[(i + 1) % n]);
        if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
        let t = ((q - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
        nearest = nearest.min(q.distance(a + (b - a) * t));
    }
    (inside, nearest)
}

#[test]
fn the_reference_plane_interpolation_is_the_papers_linear_blend() {
    let fw = shirt(LONG, TemplateKind::Shirt);
    let axis = Axis::left();
    let cap = fw.dimension("cap_height").expect("cap_height");
    let length = fw.dimension("sleeve_length").expect("sleeve_length");
    let ring = |n: &str| fw.ring(n).expect(n);
    let (c1, c2, elbow) = (ring("left_bicep"), ring("left_cuff"), ring("left_elbow"));
    // C1 and C2 are across the axis at their stations.
    let (o1, n1, o2, n2) = (axis.point(cap), axis.up(cap), axis.point(length), axis.up(length));
    for (r, o, n) in [(c1, o1, n1), (c2, o2, n2)] {
        assert!(
            r.plane.normal.distance(n) < 1e-12,
            "{}: normal {:?} vs {n:?}",
            r.name,
            r.plane.normal
        );
        assert!(
            r.plane.signed_distance(o).abs() < 1e-12,
            "{} passes its axis point",
            r.name
        );
    }
    // Plane II at the elbow: the normals blended linearly, through the elbow.
    let s = axis.upper();
    let t = (s - cap) / (length - cap);
    let n_ii = (n1 + (n2 - n1) * t).normalize();
    assert!(elbow.plane.normal.distance(n_ii) < 1e-12, "plane II's normal");
    assert!(
        elbow.plane.signed_distance(axis.elbow).abs() < 1e-12,
        "plane II through the elbow"
    );
    // C4: each point the linear blend of C1's and C2's about their origins, in plane II.
    let expected: Vec<DVec3> = c1
        .stages
        .fitted
        .iter()
        .zip(&c2.stages.fitted)
        .map(|(a, b)| {
            let d = (*a - o1) * (1.0 - t) + (*b - o2) * t;
            axis.elbow + d - n_ii * d.dot(n_ii)
        })
        .collect();
    let (frame, c4) = interpolate(
        (&c1.stages.fitted, RingFrame { origin: o1, normal: n1 }),
        (&c2.stages.fitted, RingFrame { origin: o2, normal: n2 }),
        t,
        axis.elbow,
    );
    assert!(frame.normal.distance(n_ii) < 1e-12);
    assert_eq!(c4.len(), expected.len());
    let worst = c4
        .iter()
        .zip(&expected)
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "C4 off the paper's blend by {worst:e} m");
    // C3, the elbow ring, holds C4 and clears the arm's section in plane II by the ease.
    let plane = elbow.plane;
    for p in &c4 {
        let (inside, off) = inside_by(&plane, &elbow.stages.fitted, *p);
        assert!(inside || off < 2e-3, "a C4 point {off:.4} m outside the elbow ring");
    }
    let body = real_body();
    let arm = section_mesh(&body.mesh.mesh, &body.mesh.adjacency, &plane)
        .into_iter()
        .filter(|l| l.closed)
        .min_by(|a, b| {
            let c = |l: &[DVec3]| (l.iter().sum::<DVec3>() / l.len() as f64).distance(axis.elbow);
            c(&a.points).total_cmp(&c(&b.points))
        })
        .expect("the arm's section");
    let ease = fw.dimension("left_elbow_ease").expect("the elbow's ease");
    for p in &arm.points {
        let (inside, off) = inside_by(&plane, &elbow.stages.fitted, *p);
        assert!(
            inside && off > 0.8 * ease,
            "the arm {off:.4} m from the elbow ring (ease {ease:.4})"
        );
    }
}

/// Newell's normal of a closed polygon, and the largest distance of its points from the
/// plane through their centroid with that normal.
fn off_plane(points: &[DVec3]) -> f64 {
    let n = points.len();
    let mut normal = DVec3::ZERO;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        normal += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    let normal = normal.normalize();
    let c = points.iter().sum::<DVec3>() / n as f64;
    points.iter().map(|p| (*p - c).dot(normal).abs()).fold(0.0, f64::max)
}

/// Every framework a session's steps solve, by step.
#[derive(Default)]
struct Frameworks(BTreeMap<usize, Framework>);

impl StageSink for Frameworks {
    fn garment(&mut self, info: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        if let GarmentStage::Part(fw, GarmentPart::Mesh) = stage {
            self.0.insert(info.step, fw.clone());
        }
        Ok(())
    }
}

#[test]
fn cap_and_cuff_rings_stay_in_their_planes_through_the_shirt_session() {
    let text = std::fs::read_to_string("assets/sessions/shirt.drape").expect("session");
    let parsed = parse_session(&text, "shirt", Path::new(".")).expect("parses");
    let mut sink = Frameworks::default();
    let report = run_session(&parsed, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    // The garment, two dimension edits, two drags, the lift, the collar: each solved.
    assert!(
        sink.0.len() >= 7,
        "steps solved: {:?}",
        sink.0.keys().collect::<Vec<_>>()
    );
    let first = sink.0.values().next().expect("a garment");
    let tolerance = 1e-6 * first.layout.height;
    let mut moved = 0;
    for (step, fw) in &sink.0 {
        for name in ["left_bicep", "left_cuff", "right_bicep", "right_cuff"] {
            let r = fw.ring(name).expect(name);
            let off = off_plane(&r.stages.control);
            assert!(off < tolerance, "step {step}: {name} {off:e} m off its own plane");
            if r.stages.control != first.ring(name).expect(name).stages.control {
                moved += 1;
            }
        }
    }
    assert!(moved > 0, "the edits never moved a cap or cuff ring");
}

/// The undirected edges of `triangles` with their face counts, and whether any directed
/// edge is used twice (the faces disagree in orientation).
fn edge_counts(triangles: &[[u32; 3]]) -> (BTreeMap<(u32, u32), usize>, bool) {
    let mut undirected = BTreeMap::new();
    let mut directed = BTreeMap::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *undirected.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            *directed.entry((a, b)).or_insert(0) += 1;
        }
    }
    let twice = directed.values().any(|&c| c > 1);
    (undirected, twice)
}

/// The boundary loops of a mesh (edges used by one face), each as its vertices.
fn boundary_loops(edges: &BTreeMap<(u32, u32), usize>) -> Vec<Vec<u32>> {
    let mut next: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for (&(a, b), &c) in edges {
        if c == 1 {
            next.entry(a).or_default().push(b);
            next.entry(b).or_default().push(a);
        }
    }
    let mut seen = std::collections::BTreeSet::new();
    let mut loops = Vec::new();
    for &start in next.keys() {
        if seen.contains(&start) {
            continue;
        }
        let mut stack = vec![start];
        let mut comp = Vec::new();
        while let Some(v) = stack.pop() {
            if seen.insert(v) {
                comp.push(v);
                stack.extend(next[&v].iter().copied());
            }
        }
        loops.push(comp);
    }
    loops
}

#[test]
fn a_sleeved_garment_is_one_mesh_open_only_at_its_hems_cuffs_and_collar() {
    let cases = [
        (TemplateKind::Shirt, LONG, ["hip"].as_slice(), true),
        (
            TemplateKind::Shirt,
            Style {
                sleeves: Sleeves::Short,
                collar: Collar::None,
            },
            ["hip"].as_slice(),
            false,
        ),
        (
            TemplateKind::Jumpsuit,
            Style {
                sleeves: Sleeves::Long,
                collar: Collar::None,
            },
            ["left_hem", "right_hem"].as_slice(),
            false,
        ),
        (
            TemplateKind::Jumpsuit,
            Style {
                sleeves: Sleeves::Short,
                collar: Collar::Stand,
            },
            ["left_hem", "right_hem"].as_slice(),
            true,
        ),
    ];
    for (kind, style, hems, collar) in cases {
        let fw = shirt(style, kind);
        let mesh = &fw.m0.mesh;
        let (edges, twice) = edge_counts(&mesh.triangles);
        let name = format!("{kind:?} {style:?}");
        assert!(!twice, "{name}: faces disagree in orientation");
        assert!(
            edges.values().all(|&c| c <= 2),
            "{name}: an edge of more than two faces"
        );
        // The openings: each hem ring, each cuff, and the collar's top or the neckline.
        let top = if collar { "collar" } else { "neckline" };
        let mut openings: Vec<&str> = hems.to_vec();
        openings.extend(["left_cuff", "right_cuff", top]);
        let loops = boundary_loops(&edges);
        assert_eq!(loops.len(), openings.len(), "{name}: boundary loops");
        // Each loop lies on one opening's ring, every vertex in that ring's plane.
        let mut matched: Vec<&str> = Vec::new();
        for l in &loops {
            let centre = l.iter().map(|&v| mesh.positions[v as usize]).sum::<DVec3>() / l.len() as f64;
            let on = openings
                .iter()
                .filter(|o| {
                    let plane = fw.ring(o).expect("ring").plane;
                    l.iter()
                        .all(|&v| plane.signed_distance(mesh.positions[v as usize]).abs() < 1e-6 * fw.layout.height)
                })
                .min_by(|a, b| {
                    let d = |o: &str| {
                        let f = &fw.ring(o).expect("ring").stages.fitted;
                        (f.iter().sum::<DVec3>() / f.len() as f64).distance(centre)
                    };
                    d(a).total_cmp(&d(b))
                });
            let on = on.unwrap_or_else(|| panic!("{name}: a boundary loop of {} vertices on no opening", l.len()));
            matched.push(on);
        }
        matched.sort_unstable();
        openings.sort_unstable();
        assert_eq!(matched, openings, "{name}: one loop per opening");
    }
}

#[test]
fn three_sided_patches_sit_under_the_armholes_and_meet_their_neighbours() {
    let fw = shirt(LONG, TemplateKind::Shirt);
    let triangles: Vec<_> = fw.patches.iter().filter(|p| p.triangular).collect();
    assert_eq!(triangles.len(), 4, "one in front and one behind each arm");
    let mesh = &fw.m0.mesh;
    let (edges, _) = edge_counts(&mesh.triangles);
    // Every edge of a three-sided patch's faces has its twin: none lies on an opening.
    let mut faces = 0;
    for (f, t) in mesh.triangles.iter().enumerate() {
        let patch = &fw.m0.patch_names[fw.m0.face_patch[f] as usize];
        if !patch.starts_with("underarm.") {
            continue;
        }
        faces += 1;
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        let area = 0.5 * (b - a).cross(c - a).length();
        assert!(area > 1e-8, "{patch}: a degenerate face ({area:e} m2)");
        for k in 0..3 {
            let (p, q) = (t[k], t[(k + 1) % 3]);
            assert_eq!(edges[&(p.min(q), p.max(q))], 2, "{patch}: an edge without its twin");
        }
    }
    let n = fw.layout.k;
    assert_eq!(faces, 4 * n * n, "n^2 faces each");
}

/// The armhole is the bodice's: a wider chest ring moves it, and the sleeve's cap follows,
/// still welded to the bodice (the same topology, the same openings).
#[test]
fn the_cap_follows_a_bodice_edit() {
    let base = shirt(LONG, TemplateKind::Shirt);
    let chest = base.ring("chest").expect("chest").girth;
    let mut dims = Dimensions::default();
    dims.values.insert("chest_girth".into(), chest + 0.06);
    let wider = build_framework(
        real_body(),
        real_probe(),
        TemplateKind::Shirt,
        &dims,
        &FrameworkOptions::default().with_style(LONG),
    )
    .expect("builds");
    let line = |fw: &Framework| {
        fw.lines
            .iter()
            .find(|l| l.name == "left_armhole")
            .expect("armhole")
            .points
            .clone()
    };
    let moved = line(&base)
        .iter()
        .zip(line(&wider))
        .map(|(a, b)| a.distance(b))
        .fold(0.0, f64::max);
    assert!(moved > 1e-3, "the armhole moved {moved:e} m");
    assert_eq!(
        base.m0.mesh.positions.len(),
        wider.m0.mesh.positions.len(),
        "the same topology"
    );
    let (edges, twice) = edge_counts(&wider.m0.mesh.triangles);
    assert!(!twice);
    assert_eq!(boundary_loops(&edges).len(), 4, "hem, two cuffs, the collar's top");
    // The cap's top row is the armhole's samples: every armhole point of the bodice's
    // boundary is a vertex the cap's faces use.
    let cap_vertices: std::collections::BTreeSet<u32> = wider
        .m0
        .mesh
        .triangles
        .iter()
        .enumerate()
        .filter(|(f, _)| wider.m0.patch_names[wider.m0.face_patch[*f] as usize].starts_with("sleeve.left.cap"))
        .flat_map(|(_, t)| t.iter().copied())
        .collect();
    let strap = wider
        .open_curves
        .iter()
        .find(|c| c.name == "left_strap")
        .expect("strap");
    let top = wider
        .m0
        .mesh
        .positions
        .iter()
        .position(|p| *p == strap.apex)
        .expect("the strap's top is a vertex") as u32;
    assert!(cap_vertices.contains(&top), "the cap meets the strap's top");
}
