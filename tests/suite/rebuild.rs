//! A dimension edit's framework built with the framework before it (rings taken where their
//! inputs are the same, contour spans and patches where their samples are), its drags
//! replayed taking patches from the framework just before and from the garment before the
//! edit, against the same framework built from nothing and its drags replayed surfacing
//! every patch anew: on every shipped body, through random chains of drags and dimension
//! edits, the two are equal field by field, bit for bit (compared through their exact
//! `Debug` text: Rust prints an `f64` with the shortest digits that read back to the same
//! bits), and the edits really kept rings and patches.

use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::constraint::{ConstraintNet, Edit, NetworkOptions, SolverOptions, Target, solve};
use drape::garment::assemble::assemble_among;
use drape::garment::{
    BodyProbe, Dimensions, Fit, Framework, FrameworkOptions, TemplateKind, build_framework, rebuild_framework,
};
use glam::DVec3;

use super::common::{Lcg, shipped_bodies};

/// The control points the drags move.
const POINTS: [&str; 4] = [
    "waist.front_left",
    "chest.front_left",
    "left_knee.outer",
    "crotch.point",
];

/// The dimensions the edits change, each with the span of a change, m.
const DIMENSIONS: [(&str, f64); 5] = [
    ("waist_girth", 0.04),
    ("hip_girth", 0.04),
    ("inseam", 0.05),
    ("waist_ease", 0.01),
    ("ease", 0.004),
];

/// The first field in which `a` and `b` differ, by name.
fn first_difference(a: &Framework, b: &Framework) -> Option<&'static str> {
    let text = |fw: &Framework| {
        [
            ("rings", format!("{:?}", fw.rings)),
            ("open_curves", format!("{:?}", fw.open_curves)),
            ("contours", format!("{:?}", fw.contours)),
            ("straightened", format!("{:?}", fw.straightened)),
            ("planes", format!("{:?}", fw.planes)),
            ("lines", format!("{:?}", fw.lines)),
            ("patches", format!("{:?}", fw.patches)),
            ("m0", format!("{:?}", fw.m0)),
            ("spans", format!("{:?}", fw.spans)),
            ("dimensions", format!("{:?}", fw.dimensions)),
            ("layout", format!("{:?}", fw.layout)),
            ("built_rings", format!("{:?}", fw.built_rings)),
        ]
    };
    text(a)
        .into_iter()
        .zip(text(b))
        .find(|(x, y)| x.1 != y.1)
        .map(|(x, _)| x.0)
}

/// A drag of a random control point.
fn random_drag(rng: &mut Lcg) -> Edit {
    let name = POINTS[((rng.next() * POINTS.len() as f64) as usize).min(POINTS.len() - 1)];
    let by = DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 0.03;
    Edit::Point {
        name: name.to_string(),
        target: Target::By(by),
    }
}

/// `fw` after `edit`, as a session makes it: the solve, then the assembly given the
/// frameworks `previous` (none: every patch surfaced anew); `None` when the drag is refused.
fn dragged(fw: &Framework, edit: &Edit, probe: &BodyProbe, previous: &[&Framework]) -> Option<Framework> {
    let net = ConstraintNet::for_framework(fw, probe, &NetworkOptions::default());
    let solution = solve(fw, &net, edit, probe, &SolverOptions::default()).ok()?;
    let mut built = assemble_among(&solution.framework, probe, previous).ok()?;
    let mut after = solution.framework;
    built.place_on(&mut after);
    Some(after)
}

/// `fw` after `edits` made again in turn, each assembled from nothing (`earlier` `None`) or
/// as a dimension edit's replay makes it: given the framework just before and `earlier`.
fn replayed(mut fw: Framework, edits: &[Edit], probe: &BodyProbe, earlier: Option<&Framework>) -> Option<Framework> {
    for edit in edits {
        fw = match earlier {
            Some(earlier) => dragged(&fw, edit, probe, &[&fw, earlier])?,
            None => dragged(&fw, edit, probe, &[])?,
        };
    }
    Some(fw)
}

#[test]
fn a_framework_rebuilt_after_a_dimension_edit_equals_one_built_from_nothing_on_every_body() {
    let options = FrameworkOptions {
        resolution: 5,
        fit: Fit::Tight,
        ..FrameworkOptions::default()
    };
    for (b, path) in shipped_bodies().into_iter().enumerate() {
        let mesh = BodyMesh::load(&BodySource::File(path.clone()), 1.0).expect("loads");
        let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).expect("analyses");
        let probe = BodyProbe::new(&body);
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mut dims = Dimensions::default();
        let mut fw = build_framework(&body, &probe, TemplateKind::Jumpsuit, &dims, &options).expect("builds");
        let mut rng = Lcg(0x5eed + b as u64);
        let (mut edits, mut rings_kept, mut patches_kept) = (0, 0, 0);
        let mut drags: Vec<Edit> = Vec::new();
        for step in 0..8 {
            if rng.next() < 0.5 {
                let edit = random_drag(&mut rng);
                if let Some(after) = dragged(&fw, &edit, &probe, &[&fw]) {
                    fw = after;
                    drags.push(edit);
                }
            }
            let k = ((rng.next() * DIMENSIONS.len() as f64) as usize).min(DIMENSIONS.len() - 1);
            let (dimension, span) = DIMENSIONS[k];
            let value = fw.dimension(dimension).unwrap_or(0.0) + span * (rng.next() - 0.5);
            let mut next = dims.clone();
            next.values.insert(dimension.to_string(), value);
            let fresh = build_framework(&body, &probe, TemplateKind::Jumpsuit, &next, &options)
                .map(|f| replayed(f, &drags, &probe, None));
            let rebuilt = rebuild_framework(&body, &probe, TemplateKind::Jumpsuit, &next, &options, Some(&fw))
                .map(|(f, report)| (replayed(f, &drags, &probe, Some(&fw)), report));
            match (fresh, rebuilt) {
                (Ok(Some(fresh)), Ok((Some(rebuilt), report))) => {
                    let difference = first_difference(&fresh, &rebuilt);
                    assert!(
                        difference.is_none(),
                        "{name}, step {step} ({dimension} = {value}, {} drags replayed): the rebuilt \
                         framework's {difference:?} differ",
                        drags.len()
                    );
                    edits += 1;
                    rings_kept += report.rings_kept;
                    patches_kept += report.patches_kept;
                    (dims, fw) = (next, rebuilt);
                }
                (Ok(None), Ok((None, _))) => {}
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{name}, step {step}"),
                (a, b) => panic!(
                    "{name}, step {step}: built from nothing {:?}, rebuilt {:?}",
                    a.map(|f| f.is_some()),
                    b.map(|(f, _)| f.is_some())
                ),
            }
        }
        println!("{name}: {edits} edits, {rings_kept} rings and {patches_kept} patches kept");
        assert!(edits >= 4, "{name}: only {edits} edits were accepted");
        assert!(rings_kept > 0 && patches_kept > 0, "{name}: nothing kept");
    }
}
