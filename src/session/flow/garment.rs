//! The garment's solve, shared by the steps that make a framework (`garment`, `set`): the
//! framework solved on the body with its constraint network and figures, and the body's one
//! index, built by the first step that needs it.

use crate::body::Body;
use crate::collision::BodyIndex;
use crate::constraint::{ConstraintNet, NetworkOptions};
use crate::garment::{BodyProbe, DimensionValue, Framework, StitchReport, rebuild_framework};
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::options::StepContext;
use crate::session::state::GarmentState;
use serde::Serialize;

/// The figures of a solved framework.
#[derive(Serialize)]
struct FrameworkFigures<'a> {
    /// Template name.
    template: &'static str,
    /// Contour fit.
    fit: &'static str,
    /// How contours pass through their points.
    contours: &'static str,
    /// Segments per anchor arc.
    resolution: usize,
    /// M0 vertices, faces and undirected edges.
    m0_vertices: usize,
    m0_faces: usize,
    m0_edges: usize,
    /// Coons patches.
    patches: usize,
    /// Rings and patches taken from the framework before a dimension edit (their inputs the
    /// same), not built again.
    rings_kept: usize,
    patches_kept: usize,
    /// What welding did.
    stitch: StitchReport,
    /// Each ring's girth against its target and the body's tape girth.
    girths: Vec<Girth<'a>>,
    /// Every dimension's value after the solve.
    dimensions: &'a [DimensionValue],
    /// Constraints and curves of the network.
    constraints: usize,
    curves: usize,
}

/// A ring's girth, m.
#[derive(Serialize)]
struct Girth<'a> {
    ring: &'a str,
    girth_m: f64,
    target_m: Option<f64>,
    body_tape_m: f64,
    /// (girth - target) / target.
    relative_error: Option<f64>,
}

/// Solves the framework of `garment` and builds its constraint network, recording the
/// figures. The body's index is built on first use. Given the framework `previous` (a
/// dimension edit), what its inputs did not change is taken from it.
pub(in crate::session) fn solve_garment(
    scope: &mut StepScope<'_, '_, '_>,
    body: &Body,
    probe: &mut Option<BodyProbe>,
    cx: &StepContext<'_>,
    mut garment: GarmentState,
    previous: Option<&Framework>,
) -> Result<GarmentState, StepError> {
    let probe = body_probe(scope, body, probe, cx);
    let Some(template) = garment.template else {
        // A garment from a file is never solved: nothing to do.
        return Ok(garment);
    };
    let (fw, rebuilt) = scope.timed("garment.solve", || {
        rebuild_framework(body, probe, template, &garment.dims, &garment.options, previous)
    })?;
    // The assembly measured the new patches' samples: the collision need not again.
    garment
        .detect_memory()
        .remember_nearest(probe.index(), &fw.m0.mesh.positions, &rebuilt.measured);
    for (name, count) in [
        ("garment.rings_kept", rebuilt.rings_kept),
        ("garment.patches_kept", rebuilt.patches_kept),
    ] {
        let key = scope.timing_key(name);
        scope.metrics.record_work(key, count);
    }
    let net = scope.timed("constraints.network", || {
        ConstraintNet::for_framework(&fw, probe, &NetworkOptions::default())
    });
    scope.record(&FrameworkFigures {
        template: template.name(),
        fit: fw.fit.name(),
        contours: garment.options.contours.name(),
        resolution: garment.options.resolution,
        m0_vertices: fw.m0.mesh.positions.len(),
        m0_faces: fw.m0.mesh.triangles.len(),
        m0_edges: fw.m0.edges.len(),
        patches: fw.patches.len(),
        rings_kept: rebuilt.rings_kept,
        patches_kept: rebuilt.patches_kept,
        stitch: fw.m0.report,
        girths: fw
            .rings
            .iter()
            .map(|r| Girth {
                ring: &r.name,
                girth_m: r.girth,
                target_m: r.target,
                body_tape_m: r.body_girth,
                relative_error: r.girth_error(),
            })
            .collect(),
        dimensions: &fw.dimensions,
        constraints: net.constraints.len(),
        curves: net.curves.len(),
    });
    garment.net = Some(net);
    garment.framework = Some(fw);
    Ok(garment)
}

/// The body's one index (curve clearance, collision, NURBS parts' inside test), built by the
/// first step that needs it and kept for the session.
pub(in crate::session) fn body_probe<'p>(
    scope: &mut StepScope<'_, '_, '_>,
    body: &Body,
    slot: &'p mut Option<BodyProbe>,
    cx: &StepContext<'_>,
) -> &'p BodyProbe {
    slot.get_or_insert_with(|| {
        let slices = &cx.options.collision.slices;
        let (index, outcome) = scope.timed("body.index", || match &cx.options.index_cache {
            Some(cache) => {
                let (index, outcome) = cache.load_or_build(body, slices);
                (index, Some(outcome))
            }
            None => (BodyIndex::new(body, slices), None),
        });
        if let Some(outcome) = outcome {
            scope.note(outcome.to_string());
        }
        BodyProbe::from_index(index)
    })
}
