//! M1's selection rules, against a plain reading of them written here: per patch, its
//! faces' edges in a set, each rule tested on them one by one. The selection that keeps
//! each patch's rules from the step before (while nothing they read moved) must agree with
//! it at every step of a sequence that moves some patches, single vertices on patch
//! borders, the standard size and the thresholds.

use std::collections::{BTreeMap, BTreeSet};

use drape::collision::BodyIndex;
use drape::m1::{Rule, SelectInput, SelectMemory, SelectOptions, select_keeping};
use drape::mesh::TriMesh;
use glam::DVec3;

use super::common::{Lcg, real_jumpsuit, real_probe};

/// The rules that fire for each patch, read plainly: a patch's edges are the edges of its
/// faces (each once); the angle rule reads an edge whose two faces (it has no others) are
/// both the patch's; the body's edge beneath a vertex is the mean edge of the body
/// triangle nearest it.
fn plain_rules(
    mesh: &TriMesh,
    face_patch: &[u32],
    standard: Option<&[DVec3]>,
    index: &BodyIndex,
    options: &SelectOptions,
) -> Vec<Vec<Rule>> {
    let patches = face_patch.iter().max().map_or(0, |&p| p as usize + 1);
    let mut faces_of_edge: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    for (f, t) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            faces_of_edge.entry((a.min(b), a.max(b))).or_default().push(f);
        }
    }
    let unit_normal = |f: usize| {
        let [a, b, c] = mesh.triangles[f].map(|v| mesh.positions[v as usize]);
        (b - a).cross(c - a).normalize_or_zero()
    };
    let beneath = |v: u32| {
        index
            .nearest(mesh.positions[v as usize], 0.2 * index.height)
            .map_or(0.0, |n| {
                let [a, b, c] = index.triangles[n.triangle as usize].map(|i| index.positions[i as usize]);
                (a.distance(b) + b.distance(c) + c.distance(a)) / 3.0
            })
    };
    let on = |r: Rule| options.rules.contains(&r);
    (0..patches as u32)
        .map(|p| {
            let edges: BTreeSet<(u32, u32)> = (mesh.triangles.iter().zip(face_patch))
                .filter(|(_, q)| **q == p)
                .flat_map(|(t, _)| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
                .collect();
            let length = |(a, b): (u32, u32)| mesh.positions[a as usize].distance(mesh.positions[b as usize]);
            let lengths: Vec<f64> = edges.iter().map(|&e| length(e)).collect();
            let mut rules = BTreeSet::new();
            if let Some(standard) = standard
                && on(Rule::Stretch)
                && edges.iter().any(|&(a, b)| {
                    length((a, b)) > options.stretch * standard[a as usize].distance(standard[b as usize])
                })
            {
                rules.insert(Rule::Stretch);
            }
            let cos_limit = options.angle_deg.to_radians().cos();
            if on(Rule::Angle)
                && edges.iter().any(|e| match faces_of_edge[e][..] {
                    [f, g] => {
                        face_patch[f] == p && face_patch[g] == p && unit_normal(f).dot(unit_normal(g)) < cos_limit
                    }
                    _ => false,
                })
            {
                rules.insert(Rule::Angle);
            }
            let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
            let (least, most) = lengths
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(l, m), &x| (l.min(x), m.max(x)));
            if on(Rule::Edges) && (most > options.long_edge * mean || least < options.short_edge * mean) {
                rules.insert(Rule::Edges);
            }
            if on(Rule::Body)
                && edges.iter().any(|&(a, b)| {
                    let (ea, eb) = (beneath(a), beneath(b));
                    ea > 0.0 && eb > 0.0 && length((a, b)) > options.body_edge * 0.5 * (ea + eb)
                })
            {
                rules.insert(Rule::Body);
            }
            rules.into_iter().collect()
        })
        .collect()
}

/// The selection keeping each patch's rules from the step before agrees with the plain
/// reading at every step of a sequence: patches stretched and let go again, one patch
/// bent, single vertices moved (on patch borders among them), nothing moved, the
/// thresholds changed, and the standard size changed and taken away. The sequence makes
/// the rules of some patch change at most steps, so a patch wrongly kept shows.
#[test]
fn the_selection_kept_patch_by_patch_agrees_with_a_plain_reading_of_the_rules_at_every_step() {
    let fw = real_jumpsuit();
    let index = real_probe().index();
    let face_patch: &[u32] = &fw.m0.face_patch;
    let patches = fw.m0.patch_names.len();
    let standard = fw.m0.mesh.positions.clone();
    let mut mesh = fw.m0.mesh.clone();
    let vertex_patch: Vec<u32> = {
        let mut of = vec![u32::MAX; mesh.positions.len()];
        for (t, &p) in mesh.triangles.iter().zip(face_patch) {
            for v in t {
                of[*v as usize] = of[*v as usize].min(p);
            }
        }
        of
    };
    // Stretches (or lets go, with a factor below 1) patch `p` about its centre.
    let scale = |mesh: &mut TriMesh, p: u32, k: f64| {
        let mine: Vec<usize> = (0..mesh.positions.len()).filter(|&v| vertex_patch[v] == p).collect();
        let centre = mine.iter().map(|&v| mesh.positions[v]).sum::<DVec3>() / mine.len() as f64;
        for v in mine {
            mesh.positions[v] = centre + (mesh.positions[v] - centre) * k;
        }
    };
    let mut options = SelectOptions::default();
    let mut rng = Lcg(7);
    let mut memory: Option<SelectMemory> = None;
    let mut changed_steps = 0;
    let mut last_rules: Option<Vec<Vec<Rule>>> = None;
    for step in 0..12 {
        let mut standard_now = Some(standard.as_slice());
        match step {
            0 => {}
            1 | 5 => scale(&mut mesh, 3, 1.35),
            2 | 6 => scale(&mut mesh, 3, 1.0 / 1.35),
            3 => {
                // Single vertices, wherever they fall (borders among them).
                for v in (0..mesh.positions.len()).step_by(97) {
                    mesh.positions[v] += DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 0.03;
                }
            }
            4 => {} // nothing moved
            7 => options.angle_deg = 12.0,
            8 => standard_now = None,
            9 => {
                // One patch bent along its middle.
                let p = 10;
                let mine: Vec<usize> = (0..mesh.positions.len()).filter(|&v| vertex_patch[v] == p).collect();
                let centre = mine.iter().map(|&v| mesh.positions[v]).sum::<DVec3>() / mine.len() as f64;
                for v in mine {
                    let d = mesh.positions[v].y - centre.y;
                    mesh.positions[v].z += 0.2 * d.abs();
                }
            }
            10 => options.stretch = 1.02,
            _ => scale(&mut mesh, 20, 1.2),
        }
        let input = SelectInput {
            mesh: &mesh,
            face_patch,
            patches,
            standard: standard_now,
            measured: None,
            edges: None,
        };
        let (selection, next) = select_keeping(&input, index, &options, memory.as_ref());
        let truth = plain_rules(&mesh, face_patch, standard_now, index, &options);
        assert_eq!(selection.rules, truth, "step {step}");
        if last_rules.as_ref().is_some_and(|r| *r != truth) {
            changed_steps += 1;
        }
        last_rules = Some(truth);
        memory = Some(next);
    }
    let fired = last_rules.unwrap_or_default().iter().filter(|r| !r.is_empty()).count();
    assert!(changed_steps >= 6, "the rules changed at only {changed_steps} steps");
    assert!(
        fired > 0 && fired < patches,
        "{fired} of {patches} patches selected at the end"
    );
}
