//! The constraint layer on the real body: every kind's residual on the built jumpsuit, the
//! solver restoring each kind after random perturbations, a drag into the body, closed
//! chains (converging and not), a refused self-crossing drag, undo, and the re-surfacing
//! of changed patches only.

use std::collections::BTreeSet;

use drape::constraint::{
    Chains, ConstraintNet, Edit, EditError, Kind, NetworkOptions, SolverOptions, Target, curves, self_crossings, solve,
};
use drape::garment::assemble::assemble;
use drape::garment::{Ease, Framework, ease_ring};
use drape::mesh::TriMesh;
use drape::session::{
    CollisionPart, CollisionStage, ConstraintStage, GarmentPart, GarmentStage, RunOptions, SinkError, StageInfo,
    StageSink, parse_session, run_session,
};
use glam::{DVec2, DVec3};
use proptest::prelude::*;

use super::common::{Lcg, real_jumpsuit, real_probe};

fn net() -> &'static ConstraintNet {
    static NET: std::sync::OnceLock<ConstraintNet> = std::sync::OnceLock::new();
    NET.get_or_init(|| ConstraintNet::for_framework(real_jumpsuit(), real_probe(), &NetworkOptions::default()))
}

const TOL: f64 = 1e-6;
/// Cases per property test (a sweep of 20 000 per test, perturbations up to 5 cm, passed
/// on the real body; this bound keeps the suite quick).
const CASES: u32 = 256;

fn kinds_of(net: &ConstraintNet, name: &str) -> Vec<usize> {
    (0..net.constraints.len())
        .filter(|&k| net.constraints[k].kind.name() == name)
        .collect()
}

#[test]
fn every_constraint_holds_on_the_built_jumpsuit_and_every_kind_is_there() {
    let fw = real_jumpsuit();
    let net = net();
    let r = net.residuals(fw);
    for kind in [
        "symmetry",
        "coplanar",
        "inside_polygon",
        "outside_body",
        "no_self_crossing",
        "coincident",
        "tangent",
    ] {
        let ks = kinds_of(net, kind);
        assert!(!ks.is_empty(), "no {kind} constraint");
        for k in ks {
            assert!(r[k] <= 1e-9, "#{k} {kind} residual {:e} on the built framework", r[k]);
        }
    }
    // Independent checks of two kinds: contour points are the ring anchors they name, and
    // each princess contour leaves in its strap's end direction.
    for c in &fw.contours {
        for (name, p) in c.through.iter().zip(&c.points) {
            let (ring, anchor) = name.split_once('.').expect("ring.anchor");
            if let Some(a) = fw.ring(ring).and_then(|r| r.anchor(anchor)) {
                assert_eq!(a.point, *p, "{name} on {}", c.name);
            }
        }
    }
    let strap = fw.open_curves.iter().find(|c| c.name == "left_strap").expect("strap");
    let contour = fw.contours.iter().find(|c| c.name == "front_left").expect("contour");
    let n = contour.points.len() - 1;
    let l = contour.spline.knots()[n];
    let h = 1e-6;
    let numeric = (contour.spline.sample(l) - contour.spline.sample(l - h)) / h;
    let s0 = strap.spline.sample(0.0);
    let strap_dir = (strap.spline.sample(h) - s0) / h;
    assert!(numeric.normalize().angle_between(strap_dir.normalize()) < 1e-4);
}

/// A copy of the framework with control point `p` of curve `c` moved by `d` (no refit of
/// anything else: the constraints around it are broken).
fn perturbed(fw: &Framework, net: &ConstraintNet, c: usize, moves: &[(usize, DVec3)]) -> Framework {
    let mut out = fw.clone();
    let node = &net.curves[c];
    let mut pts = curves::points(&out, node).to_vec();
    for &(p, d) in moves {
        pts[p] += d;
    }
    curves::set_points(&mut out, node, pts, &drape::garment::RingOptions::default()).expect("refits");
    out
}

fn touch(name: &str) -> Edit {
    Edit::Curve {
        name: name.into(),
        by: DVec3::ZERO,
    }
}

fn residual_of(net: &ConstraintNet, fw: &Framework, kind: &str, curve: usize) -> f64 {
    kinds_of(net, kind)
        .into_iter()
        .filter(|&k| net.constraints[k].i == curve || net.constraints[k].j == curve)
        .map(|k| net.constraints[k].residual(fw, &net.curves))
        .fold(0.0, f64::max)
}

fn unit(a: f64, b: f64) -> DVec3 {
    let (t, z) = (a * std::f64::consts::TAU, 2.0 * b - 1.0);
    let r = (1.0 - z * z).sqrt();
    DVec3::new(r * t.cos(), z, r * t.sin())
}

/// Knocks anchor `anchor` of ring `ring` by `size` m in direction `unit(a, b)` and solves
/// the ring: coplanarity, symmetry, region and coincident points must be restored (an
/// edit refused as a self-crossing fails too). `Ok(false)` when the knock broke nothing.
fn knock_and_restore(ring: usize, anchor: usize, a: f64, b: f64, size: f64) -> Result<bool, String> {
    let (fw, net) = (real_jumpsuit(), net());
    let ring = ["chest", "bust", "waist", "hip", "neckline"][ring];
    let c = net.curve(ring).expect("ring");
    let r = &fw.rings[net.curves[c].index];
    let p = r.anchors[anchor % r.anchors.len()].control;
    let broken = perturbed(fw, net, c, &[(p, unit(a, b) * size)]);
    let before = residual_of(net, &broken, "coplanar", c).max(residual_of(net, &broken, "symmetry", c));
    if before <= TOL {
        return Ok(false);
    }
    let s = solve(&broken, net, &touch(ring), real_probe(), &SolverOptions::default())
        .map_err(|e| format!("{ring} anchor {anchor}: {e}"))?;
    for kind in ["coplanar", "symmetry", "inside_polygon", "coincident"] {
        let after = residual_of(net, &s.framework, kind, c);
        if after > TOL {
            return Err(format!("{ring} anchor {anchor} {kind}: {before:e} -> {after:e}"));
        }
    }
    Ok(true)
}

/// The knocks the property test below once found unrestored (the chest next to the arms:
/// collision pushes that broke its symmetry and ease, a strap end pushed off the chest; the
/// neckline: a symmetry choice that kept the knocked side and crossed the ring), kept as
/// fixed cases whatever the strategy draws.
#[test]
fn the_knocks_once_left_unrestored_are_restored() {
    for (ring, anchor, a, b, size) in [
        (0, 1, 0.0, 0.5173985699790832, 0.0263866662357317),
        (0, 7, 0.0, 0.5173985699790832, 0.0263866662357317),
        (0, 2, 0.6870935474950624, 0.4590379132909488, 0.027230126160614064),
        (0, 2, 0.6997558834510809, 0.2876862727868686, 0.018887805791993284),
        (0, 6, 0.42452722267309034, 0.09057087539950076, 0.02695562717375281),
        (4, 3, 0.8822124221329846, 0.42170091412184, 0.04161126367188566),
    ] {
        assert_eq!(knock_and_restore(ring, anchor, a, b, size), Ok(true));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(super::common::proptest_cases(CASES)))]

    /// Coplanarity, symmetry and the design region of a ring: its anchors knocked off the
    /// plane, asymmetric and far out (up to 5 cm); solving the ring puts them back.
    #[test]
    fn the_solver_restores_a_rings_plane_symmetry_and_region(
        ring in 0usize..5, anchor in 0usize..8, a in 0.0f64..1.0, b in 0.0f64..1.0, size in 0.002f64..0.05,
    ) {
        let broke = knock_and_restore(ring, anchor, a, b, size).map_err(TestCaseError::fail)?;
        prop_assume!(broke);
    }

    /// Coincident points and tangents: a contour point (or a strap's end direction) moved
    /// off its ring; solving from the ring (or the strap) brings the contour back.
    #[test]
    fn the_solver_restores_coincident_points_and_tangents(
        contour in 0usize..10, point in 0usize..7, a in 0.0f64..1.0, b in 0.0f64..1.0, size in 0.001f64..0.02,
    ) {
        let (fw, net) = (real_jumpsuit(), net());
        let contours: Vec<usize> = (0..net.curves.len()).filter(|&c| net.curves[c].kind == drape::constraint::CurveKind::Contour).collect();
        let c = contours[contour % contours.len()];
        let n = curves::points(fw, &net.curves[c]).len();
        let p = point % n;
        let mut broken = perturbed(fw, net, c, &[(p, unit(a, b) * size)]);
        // Knock the end tangent of a princess contour too.
        let k = net.curves[c].index;
        if broken.contours[k].tangents[1].is_some() {
            broken.contours[k].tangents[1] = Some(unit(b, a));
            let pts = broken.contours[k].points.clone();
            let t = broken.contours[k].tangents;
            broken.contours[k].refit(pts, t).expect("refits");
        }
        // The curve on the other side of the broken joint drives.
        let driver = net.touching(c).into_iter().map(|k| &net.constraints[k]).find(|con| match con.kind {
            Kind::Coincident { a, b } => (con.j == c && b == p) || (con.i == c && a == p),
            _ => false,
        }).map(|con| con.other(c)).expect("every contour point is shared");
        let before = residual_of(net, &broken, "coincident", c).max(residual_of(net, &broken, "tangent", c));
        prop_assume!(before > TOL);
        let s = solve(&broken, net, &touch(&net.curves[driver].name), real_probe(), &SolverOptions::default()).expect("solves");
        // Tangents are solved from their strap, which the ring's solve reaches when the
        // strap shares the point; otherwise solve from the strap as well.
        let mut fw2 = s.framework;
        if residual_of(net, &fw2, "tangent", c) > TOL {
            let strap = net.touching(c).into_iter().map(|k| &net.constraints[k]).find(|con| matches!(con.kind, Kind::Tangent { .. })).map(|con| con.i).expect("tangent");
            fw2 = solve(&fw2, net, &touch(&net.curves[strap].name), real_probe(), &SolverOptions::default()).expect("solves").framework;
        }
        for kind in ["coincident", "tangent"] {
            let after = residual_of(net, &fw2, kind, c);
            prop_assert!(after <= 1e-9, "{} {kind}: {before:e} -> {after:e}", net.curves[c].name);
        }
    }

    /// The ease against the section: ring control points pushed into the body section come
    /// back out to their gap.
    #[test]
    fn the_solver_restores_a_ring_outside_its_section(ring in 0usize..6, point in 0usize..12, depth in 0.005f64..0.04) {
        let (fw, net) = (real_jumpsuit(), net());
        let ring = ["bust", "waist", "hip", "left_knee", "right_thigh", "left_hem"][ring];
        let c = net.curve(ring).expect("ring");
        let r = &fw.rings[net.curves[c].index];
        let p = point % r.stages.control.len();
        // Towards the ring's centre, in its plane.
        let centre = r.stages.control.iter().sum::<DVec3>() / r.stages.control.len() as f64;
        let inward = (centre - r.stages.control[p]).with_y(0.0).normalize();
        let broken = perturbed(fw, net, c, &[(p, inward * depth)]);
        let before = residual_of(net, &broken, "outside_body", c);
        prop_assume!(before > TOL);
        let s = solve(&broken, net, &touch(ring), real_probe(), &SolverOptions::default()).expect("solves");
        let after = residual_of(net, &s.framework, "outside_body", c);
        prop_assert!(after <= TOL, "{ring}: {before:e} -> {after:e}");
    }

    /// The box-swept self-crossing check finds exactly the crossings this test finds by
    /// its own parametric segment intersection over every pair of non-neighbouring segments,
    /// at the same points.
    #[test]
    fn the_crossing_check_finds_every_crossing(seed in 0u64..10_000, n in 4usize..60, closed in proptest::bool::ANY) {
        let mut g = Lcg(seed);
        let pts: Vec<DVec2> = (0..n).map(|_| DVec2::new(g.next(), g.next())).collect();
        let found = self_crossings(&pts, closed);
        let truth = crossings_by_hand(&pts, closed);
        let pairs: Vec<(usize, usize)> = found.iter().map(|c| (c.i, c.j)).collect();
        let truth_pairs: Vec<(usize, usize)> = truth.iter().map(|t| t.0).collect();
        prop_assert_eq!(pairs, truth_pairs);
        for (c, (_, at)) in found.iter().zip(&truth) {
            prop_assert!(c.at.distance(*at) < 1e-9, "{:?} vs {:?}", c.at, at);
        }
    }
}

/// Every crossing of a polyline by parametric segment intersection: segments `p + t r` and
/// `q + u s` meet where `t = (q - p) x s / (r x s)` and `u = (q - p) x r / (r x s)` both lie
/// in `0..=1`. Segments sharing a point (neighbours, and the last and first of a closed
/// one) are skipped. Sorted by segment pair, with the meeting point.
fn crossings_by_hand(p: &[DVec2], closed: bool) -> Vec<((usize, usize), DVec2)> {
    let n = p.len();
    let m = if closed { n } else { n - 1 };
    let mut out = Vec::new();
    for i in 0..m {
        for j in i + 2..m {
            if closed && i == 0 && j == m - 1 {
                continue;
            }
            let (a, r) = (p[i], p[(i + 1) % n] - p[i]);
            let (b, s) = (p[j], p[(j + 1) % n] - p[j]);
            let denom = r.x * s.y - r.y * s.x;
            if denom == 0.0 {
                continue;
            }
            let w = b - a;
            let t = (w.x * s.y - w.y * s.x) / denom;
            let u = (w.x * r.y - w.y * r.x) / denom;
            if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u) {
                out.push(((i, j), a + r * t));
            }
        }
    }
    out
}

#[test]
fn no_self_crossing_is_met_by_refusal_and_the_framework_stays() {
    let (fw, net) = (real_jumpsuit(), net());
    let err = solve(
        fw,
        net,
        &Edit::Point {
            name: "waist.back".into(),
            target: Target::By(DVec3::new(0.0, 0.0, 0.35)),
        },
        real_probe(),
        &SolverOptions::default(),
    )
    .expect_err("a ring pulled through itself is refused");
    match &err {
        EditError::SelfCrossing { curve, loop_length, .. } => {
            assert_eq!(curve, "waist");
            assert!(*loop_length > 0.0);
        }
        other => panic!("expected a self-crossing, got {other}"),
    }
    assert!(err.to_string().contains("'waist'"), "{err}");
    let c = net.curve("waist").expect("waist");
    assert_eq!(residual_of(net, fw, "no_self_crossing", c), 0.0);
}

#[test]
fn a_drag_into_the_body_ends_outside_by_the_ease_with_its_joints_exact() {
    let (fw, net) = (real_jumpsuit(), net());
    let probe = real_probe();
    let name = "waist.front";
    let c = net.curve("waist").expect("waist");
    let r = &fw.rings[net.curves[c].index];
    let p = r.anchor("front").expect("front").control;
    let start = r.stages.control[p];
    let s = solve(
        fw,
        net,
        &Edit::Point {
            name: name.into(),
            target: Target::By(DVec3::new(0.0, 0.0, -0.06)),
        },
        probe,
        &SolverOptions::default(),
    )
    .expect("solves");
    assert!(
        probe.signed_distance(start + DVec3::new(0.0, 0.0, -0.06)) < 0.0,
        "the drag goes inside"
    );
    let end = s.framework.rings[net.curves[c].index].stages.control[p];
    // Outside by the ease: the section gap (the ring's own ease, computed here with the
    // easing code on the section) and at least the collision gap off the 3D body.
    let ring = &s.framework.rings[net.curves[c].index];
    let Ease::Uniform(e) = ring.ease else {
        panic!("the waist's ease is uniform here")
    };
    let eased = ease_ring(&[end], &ring.stages.convex, &ring.plane, Ease::Uniform(e)).expect("eases")[0];
    assert!(end.distance(eased) < 2e-4, "{end} vs eased {eased}");
    assert!(probe.signed_distance(end) >= s.gap - 1e-9);
    assert!(
        end.distance(start) < 2e-4,
        "back where the ease puts it: {:e}",
        end.distance(start)
    );
    for k in net.touching(c) {
        if matches!(net.constraints[k].kind, Kind::Coincident { .. }) {
            let res = net.constraints[k].residual(&s.framework, &net.curves);
            assert!(res <= 1e-9, "#{k} {res:e}");
        }
    }
    assert!(s.violations.is_empty(), "{:?}", s.violations);
    assert_eq!(s.path.len(), 4, "start, asked, after the first pass, final");
}

/// Unit tangent of a sampled curve at parameter `t`, one-sided second-order differences
/// (`h` forward when `forward`, else backward), written here independently of the splines'
/// own derivatives.
fn tangent_by_differences(sample: impl Fn(f64) -> DVec3, t: f64, forward: bool) -> DVec3 {
    let h = if forward { 1e-5 } else { -1e-5 };
    ((sample(t + h) * 4.0 - sample(t) * 3.0 - sample(t + 2.0 * h)) / (2.0 * h)).normalize()
}

/// The mirror image of `p` about the plane `x = mid`.
fn mirrored(p: DVec3, mid: f64) -> DVec3 {
    DVec3::new(2.0 * mid - p.x, p.y, p.z)
}

/// The jumpsuit's joints and symmetries as its description states them, measured on `fw`
/// by this test alone: every contour point equals the ring anchor it names, every strap
/// end and crotch end its ring anchor, every princess contour leaves its top in its strap's
/// end direction, and the right straps, leg rings and torso anchors mirror the left ones
/// about the crotch plane as they did when built (the body is not symmetric, so the built
/// offsets are kept; mirrored points are compared in the partner's plane). Returns
/// `(joint, residual in m or rad)` for every joint.
fn joints(fw: &Framework) -> Vec<(String, f64)> {
    let built = real_jumpsuit();
    let mid_of = |f: &Framework| {
        let c = f.open_curves.iter().find(|c| c.name == "crotch").expect("crotch");
        c.plane.offset * c.plane.normal.x.signum()
    };
    let (mid, mid0) = (mid_of(fw), mid_of(built));
    let mut out = Vec::new();
    // Pairs of points that mirror each other: (label, left point, right point, right plane).
    let mut pairs: Vec<(String, [DVec3; 2], [DVec3; 2], drape::geom::Plane)> = Vec::new();
    for side_pair in [("left_strap", "right_strap")] {
        let curve = |f: &Framework, n: &str| f.open_curves.iter().find(|c| c.name == n).expect("strap").clone();
        let (l, r, l0, r0) = (
            curve(fw, side_pair.0),
            curve(fw, side_pair.1),
            curve(built, side_pair.0),
            curve(built, side_pair.1),
        );
        let n = l.stages.control.len();
        for i in 1..n - 1 {
            pairs.push((
                "straps".to_string(),
                [l.stages.control[i], r.stages.control[i]],
                [l0.stages.control[i], r0.stages.control[i]],
                r.plane,
            ));
        }
    }
    for level in ["thigh", "knee", "hem"] {
        let (ln, rn) = (format!("left_{level}"), format!("right_{level}"));
        let (l, r, l0, r0) = (
            fw.ring(&ln).expect("ring"),
            fw.ring(&rn).expect("ring"),
            built.ring(&ln).expect("ring"),
            built.ring(&rn).expect("ring"),
        );
        for a in ["front", "back", "inner", "outer"] {
            let p = |x: &drape::garment::GarmentRing| x.anchor(a).expect("anchor").point;
            pairs.push((format!("{level} rings"), [p(l), p(r)], [p(l0), p(r0)], r.plane));
        }
    }
    for ring in ["chest", "bust", "waist", "hip"] {
        let (r, r0) = (fw.ring(ring).expect("ring"), built.ring(ring).expect("ring"));
        for (a, b) in [
            ("front_left", "front_right"),
            ("left", "right"),
            ("back_left", "back_right"),
        ] {
            let p = |x: &drape::garment::GarmentRing, n: &str| x.anchor(n).expect("anchor").point;
            pairs.push((ring.to_string(), [p(r, a), p(r, b)], [p(r0, a), p(r0, b)], r.plane));
        }
    }
    // One symmetry per pair of curves (or centred ring): its worst point.
    let mut symmetry: std::collections::BTreeMap<String, f64> = std::collections::BTreeMap::new();
    for (label, [l, r], [l0, r0], plane) in pairs {
        let rest = r0 - mirrored(l0, mid0);
        let want = mirrored(l, mid) + rest;
        let want = want - plane.normal * plane.signed_distance(want);
        let worst = symmetry.entry(format!("symmetry of {label}")).or_insert(0.0);
        *worst = worst.max(r.distance(want));
    }
    out.extend(symmetry);
    let anchor = |ring: &str, a: &str| fw.ring(ring).and_then(|r| r.anchor(a)).map(|x| x.point);
    for c in &fw.contours {
        for (name, p) in c.through.iter().zip(&c.points) {
            let (ring, a) = name.split_once('.').expect("ring.anchor");
            if let Some(q) = anchor(ring, a) {
                out.push((format!("{} at {name}", c.name), p.distance(q)));
            }
        }
    }
    for (curve, ring, ends) in [
        ("crotch", "hip", ["front", "back"]),
        ("left_strap", "chest", ["front_left", "back_left"]),
        ("right_strap", "chest", ["front_right", "back_right"]),
    ] {
        let c = fw.open_curves.iter().find(|c| c.name == curve).expect("open curve");
        let control = &c.stages.control;
        for (end, a) in [control[0], control[control.len() - 1]].into_iter().zip(ends) {
            out.push((
                format!("{curve} end at {ring}.{a}"),
                end.distance(anchor(ring, a).expect("anchor")),
            ));
        }
    }
    for side in ["left", "right"] {
        let strap = fw
            .open_curves
            .iter()
            .find(|c| c.name == format!("{side}_strap"))
            .expect("strap");
        let l = strap.spline.length();
        for (part, front) in [("front", true), ("back", false)] {
            let contour = fw
                .contours
                .iter()
                .find(|c| c.name == format!("{part}_{side}"))
                .expect("contour");
            let top = tangent_by_differences(|t| contour.spline.sample(t), contour.spline.length(), false);
            // Into the strap from its end: forward from the front end, backward from the back end.
            let into = if front {
                tangent_by_differences(|t| strap.spline.sample(t), 0.0, true)
            } else {
                -tangent_by_differences(|t| strap.spline.sample(t), l, false)
            };
            out.push((format!("{part}_{side} top along {side}_strap"), top.angle_between(into)));
        }
    }
    out
}

#[test]
fn a_closed_chain_converges_and_the_split_alternative_reports_what_is_left() {
    let (fw, net) = (real_jumpsuit(), net());
    let edit = Edit::Point {
        name: "chest.front_left".into(),
        target: Target::By(DVec3::new(0.0, 0.0, -0.04)),
    };
    let iterate = solve(fw, net, &edit, real_probe(), &SolverOptions::default()).expect("solves");
    let limit = SolverOptions::default().passes;
    assert!(iterate.converged, "{:?}", iterate.violations);
    assert!(
        iterate.passes > 1 && iterate.passes <= limit,
        "{} passes",
        iterate.passes
    );
    // The chain closed at least once: a curve broke a joint with one solved before it.
    assert!(iterate.iterations.iter().any(|it| !it.broken.is_empty()));
    // Every joint holds, by the test's own measure.
    for (joint, r) in joints(&iterate.framework) {
        assert!(r <= 1e-6, "iterate leaves {joint} at {r:e}");
    }
    let split = solve(
        fw,
        net,
        &edit,
        real_probe(),
        &SolverOptions {
            chains: Chains::Split,
            ..SolverOptions::default()
        },
    )
    .expect("solves");
    assert_eq!(split.passes, 1);
    // One way only, the chain is left open somewhere: the test's own measure finds the
    // joints split leaves broken, and the solver reports exactly those, with their size.
    let broken: Vec<(String, f64)> = joints(&split.framework).into_iter().filter(|(_, r)| *r > TOL).collect();
    assert!(!broken.is_empty(), "split left nothing open on this drag");
    assert!(!split.converged);
    let reported: Vec<f64> = split
        .violations
        .iter()
        .filter(|(k, _)| {
            matches!(
                net.constraints[*k].kind,
                Kind::Coincident { .. } | Kind::Tangent { .. } | Kind::Symmetry { .. }
            )
        })
        .map(|(_, r)| *r)
        .collect();
    assert_eq!(
        reported.len(),
        broken.len(),
        "reported {:?}, measured {broken:?}",
        split.violations
    );
    let mut measured: Vec<f64> = broken.iter().map(|(_, r)| *r).collect();
    let mut reported = reported;
    measured.sort_by(f64::total_cmp);
    reported.sort_by(f64::total_cmp);
    for (m, r) in measured.iter().zip(&reported) {
        assert!((m - r).abs() <= 1e-6 * m.max(1e-3), "measured {m:e}, reported {r:e}");
    }
}

#[test]
fn a_chain_that_cannot_converge_reports_the_violation_at_the_limit() {
    let (fw, base) = (real_jumpsuit(), net());
    // A design region for the waist whose front edge lies 3 cm inside the body: the region
    // pulls the ring's front in, the collision pushes it out, for ever.
    let mut net = base.clone();
    let c = net.curve("waist").expect("waist");
    let plane = curves::plane(fw, &net.curves[c]).expect("planar");
    let flat: Vec<DVec2> = curves::points(fw, &net.curves[c])
        .iter()
        .map(|p| plane.project(*p))
        .collect();
    let front = plane.project(fw.ring("waist").and_then(|r| r.anchor("front")).expect("front").point);
    let (lo, hi) = flat.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(a, b), q| (a.min(*q), b.max(*q)),
    );
    let (lo, mut hi) = (lo - 0.05, hi + 0.05);
    // The plane's first axis is z here (horizontal plane): cut the front.
    assert!(
        (front.x - (hi.x - 0.05)).abs() < 1e-9,
        "the front is the largest first coordinate"
    );
    hi.x = front.x - 0.03;
    for con in &mut net.constraints {
        if con.i == c
            && con.j == c
            && let Kind::InsidePolygon { polygon } = &mut con.kind
        {
            *polygon = vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
        }
    }
    let options = SolverOptions {
        passes: 5,
        ..SolverOptions::default()
    };
    let s = solve(
        fw,
        &net,
        &Edit::Point {
            name: "waist.front".into(),
            target: Target::By(DVec3::new(0.0, 0.0, 0.01)),
        },
        real_probe(),
        &options,
    )
    .expect("returns, does not loop");
    assert!(!s.converged);
    assert_eq!(s.passes, 5);
    let region: BTreeSet<usize> = kinds_of(&net, "inside_polygon").into_iter().collect();
    let left: Vec<_> = s.violations.iter().filter(|(k, _)| region.contains(k)).collect();
    assert_eq!(left.len(), 1, "{:?}", s.violations);
    assert_eq!(net.constraints[left[0].0].i, c);
    assert!(
        left[0].1 > 0.01,
        "the ring's front stays outside the region: {:e}",
        left[0].1
    );
}

#[test]
fn only_patches_next_to_changed_curves_are_resurfaced_and_they_match_a_full_rebuild() {
    let (fw, net) = (real_jumpsuit(), net());
    let s = solve(
        fw,
        net,
        &Edit::Point {
            name: "left_knee.outer".into(),
            target: Target::By(DVec3::new(0.02, 0.0, 0.0)),
        },
        real_probe(),
        &SolverOptions::default(),
    )
    .expect("solves");
    let partial = assemble(&s.framework, real_probe(), Some(fw)).expect("assembles");
    let full = assemble(&s.framework, real_probe(), None).expect("assembles");
    assert_eq!(full.resurfaced.len(), fw.patches.len());
    // The knees and the contours through them changed (the contours run from the hems to
    // the chest); the panels, the crotch junction's front and back, and the centre bands
    // did not.
    assert!(
        !partial.resurfaced.is_empty() && partial.resurfaced.len() < fw.patches.len(),
        "{} of {}",
        partial.resurfaced.len(),
        fw.patches.len()
    );
    for kept in [
        "panel.front",
        "panel.back",
        "torso.hip_waist.front",
        "torso.bust_chest.back",
    ] {
        assert!(!partial.resurfaced.iter().any(|n| n == kept), "{kept} resurfaced");
    }
    assert_eq!(partial.m0.mesh, full.m0.mesh, "kept patches are what a rebuild gives");
}

/// Detection's memory is one per garment, shared by its states (no step copies it), so the
/// drag after an undo reads what the undone drag left in it. It may take from it only what
/// stands where it was found: that drag must give the same collided M0 and the same figures
/// as a session that never made the undone drag (the truth), all but the counts of work
/// that say what was taken from memory.
#[test]
fn a_drag_after_an_undo_collides_as_if_the_undone_drag_never_was() {
    // A tight ease, so that the drags leave vertices inside the body to be moved out.
    let head = "drape 1\nbody builtin\ngarment jumpsuit fit=tight\nset ease 0.004\ndrag waist.front_left by=0,0,0.02\n";
    let last = "drag left_knee by=0,0.03,0\n";
    let run = |text: &str| {
        let session = parse_session(text, "undo.drape", std::path::Path::new(".")).expect("parses");
        let mut sink = Steps::default();
        let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
        assert!(report.error.is_none(), "{:?}", report.error);
        assert!(sink.refused.is_empty(), "{:?}", sink.refused);
        let responded = sink.responded.last().map(|(_, m)| m.clone()).expect("collided");
        let clearance = sink.clearance.last().map(|(_, c)| c.clone()).expect("collided");
        let mut figures = report.steps.last().expect("a step").figures.clone();
        let tested = figures.get("tested_vertices").and_then(|t| t.as_u64());
        for work in [
            "tested_vertices",
            "tested_by_method",
            "skipped_inert",
            "skipped_patch",
            "patches_skipped",
            "reused",
        ] {
            figures.remove(work);
        }
        (responded, figures, clearance, tested)
    };
    let undone = run(&format!("{head}drag chest.front_left by=0,0,-0.04\nundo\n{last}"));
    let fresh = run(&format!("{head}{last}"));
    assert!(
        undone.1.get("hits").and_then(|h| h.as_u64()).is_some_and(|h| h > 0),
        "{:?}",
        undone.1
    );
    assert_eq!(undone.0, fresh.0, "the collided M0");
    assert_eq!(undone.1, fresh.1);
    let differ = (undone.2.iter().zip(&fresh.2))
        .filter(|(a, b)| a.to_bits() != b.to_bits())
        .count();
    assert_eq!(
        (undone.2.len(), differ),
        (fresh.2.len(), 0),
        "vertex clearances that differ"
    );
}

/// `undo` takes back the last `undo_limit` edits, no more: with a limit of 2, three drags
/// then three undos bring back the garment after the second drag, then after the first
/// (the truth: the meshes logged at those drags), and the third undo fails naming the
/// limit. With the default limit the same session undoes all three (back to the garment as
/// built), so the limit is what stopped it. The same over a worn garment (`name=`, `over=`),
/// whose undo goes through the steps that changed each garment.
#[test]
fn undo_takes_back_the_last_edits_up_to_the_limit_and_names_it_past_them() {
    let drags = "drag waist.front_left by=0,0,0.01\ndrag crotch.point by=0,-0.01,0\ndrag left_knee by=0,0.01,0\n";
    let text = format!("drape 1\nbody builtin\ngarment jumpsuit resolution=4\n{drags}undo\nundo\nundo\n");
    let session = parse_session(&text, "limit.drape", std::path::Path::new(".")).expect("parses");
    let run = |limit: usize| {
        let mut sink = Steps::default();
        let options = RunOptions {
            undo_limit: limit,
            ..RunOptions::default()
        };
        let report = run_session(&session, &options, &mut [&mut sink]);
        (report, sink)
    };
    // Steps: 1 garment, 2-4 drags, 5-7 undos.
    let (report, sink) = run(2);
    let error = report.error.expect("the third undo fails");
    assert_eq!(error.step, 7, "{error}");
    assert!(error.to_string().contains("the last 2 edits"), "{error}");
    assert_eq!(at(&sink.responded, 5), at(&sink.responded, 3), "first undo");
    assert_eq!(at(&sink.responded, 6), at(&sink.responded, 2), "second undo");
    assert_ne!(at(&sink.responded, 2), at(&sink.responded, 1));
    let (report, sink) = run(0);
    assert!(report.error.is_none(), "{:?}", report.error);
    assert_eq!(
        at(&sink.responded, 7),
        at(&sink.responded, 1),
        "the default undoes all three"
    );
    // Over a worn garment: the inner one dragged three times, then three undos.
    let worn = format!(
        "drape 1\nbody builtin\ngarment jumpsuit resolution=4 name=inner\ngarment dress fit=loose resolution=4 name=outer over=inner\n{}undo\nundo\nundo\n",
        drags.replace("drag ", "drag inner:")
    );
    let session = parse_session(&worn, "worn.drape", std::path::Path::new(".")).expect("parses");
    let options = RunOptions {
        undo_limit: 2,
        ..RunOptions::default()
    };
    let report = run_session(&session, &options, &mut []);
    let error = report.error.expect("the third undo fails");
    assert_eq!(error.step, 8, "{error}");
    assert!(error.to_string().contains("the last 2 edits"), "{error}");
}

/// The last mesh `v` holds at step `step`.
fn at(v: &[(usize, TriMesh)], step: usize) -> TriMesh {
    v.iter()
        .rev()
        .find(|(s, _)| *s == step)
        .map(|(_, m)| m.clone())
        .expect("logged")
}

/// Keeps M0 (before and after response) at every mesh stage.
#[derive(Default)]
struct Steps {
    m0: Vec<(usize, TriMesh)>,
    responded: Vec<(usize, TriMesh)>,
    /// Each vertex's signed distance to the body after the response, by step.
    clearance: Vec<(usize, Vec<f64>)>,
    refused: Vec<String>,
}

impl StageSink for Steps {
    fn garment(&mut self, info: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        if let GarmentStage::Part(fw, GarmentPart::Mesh) = stage {
            self.m0.push((info.step, fw.m0.mesh.clone()));
        }
        Ok(())
    }

    fn collision(&mut self, info: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        if stage.part == CollisionPart::Respond {
            self.responded.push((info.step, stage.outcome.collision.mesh.clone()));
            (self.clearance).push((info.step, stage.outcome.collision.quality.clearance.clone()));
        }
        Ok(())
    }

    fn constraints(&mut self, _: &StageInfo, stage: ConstraintStage<'_>) -> Result<(), SinkError> {
        if let ConstraintStage::Refused { message, .. } = stage {
            self.refused.push(message.to_string());
        }
        Ok(())
    }
}

#[test]
fn undo_restores_the_exact_previous_state_and_a_refused_drag_changes_nothing() {
    let text = "drape 1\nbody builtin\ngarment jumpsuit\ndrag waist.front_left by=0,0,0.02\n\
                drag crotch.point by=0,-0.02,0\nundo\ndrag waist.back by=0,0,0.35\nundo\nundo\n";
    let session = parse_session(text, "undo.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = Steps::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    // Steps: 1 garment, 2 drag, 3 drag, 4 undo, 5 refused drag, 6 undo, 7 undo.
    assert_ne!(at(&sink.m0, 2), at(&sink.m0, 1));
    assert_ne!(at(&sink.m0, 3), at(&sink.m0, 2));
    assert_eq!(at(&sink.m0, 4), at(&sink.m0, 2), "undo of the crotch drag");
    assert_eq!(at(&sink.responded, 4), at(&sink.responded, 2));
    assert_eq!(sink.refused.len(), 1);
    assert!(sink.refused[0].contains("'waist'"), "{}", sink.refused[0]);
    assert!(!sink.m0.iter().any(|(s, _)| *s == 5), "a refused drag logs no new mesh");
    assert_eq!(
        at(&sink.m0, 6),
        at(&sink.m0, 2),
        "undo of the refused drag changes nothing"
    );
    assert_eq!(at(&sink.m0, 7), at(&sink.m0, 1), "back to the garment as built");
    assert_eq!(at(&sink.responded, 7), at(&sink.responded, 1));
    // Undo against fresh runs of the session without the undone steps: after the undo of
    // the crotch drag, the state is what the session up to the first drag gives; after the
    // last undo, what the garment step alone gives.
    let fresh = |text: &str| {
        let session = parse_session(text, "fresh.drape", std::path::Path::new(".")).expect("parses");
        let mut sink = Steps::default();
        let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
        assert!(report.error.is_none(), "{:?}", report.error);
        let last = |v: &[(usize, TriMesh)]| v.last().map(|(_, m)| m.clone()).expect("logged");
        (last(&sink.m0), last(&sink.responded))
    };
    let one_drag = fresh("drape 1\nbody builtin\ngarment jumpsuit\ndrag waist.front_left by=0,0,0.02\n");
    assert_eq!(
        (at(&sink.m0, 4), at(&sink.responded, 4)),
        one_drag,
        "undo of the second drag"
    );
    assert_eq!(
        (at(&sink.m0, 6), at(&sink.responded, 6)),
        one_drag,
        "undo of the refused drag"
    );
    let built = fresh("drape 1\nbody builtin\ngarment jumpsuit\n");
    assert_eq!((at(&sink.m0, 7), at(&sink.responded, 7)), built, "undo of everything");
}
