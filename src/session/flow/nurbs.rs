//! What the NURBS steps (`nurbs`, `move`) share: a part's contacts with the body and the
//! other parts, and their figures.

use crate::nurbs::{BodyHulls, Contact, NurbsOptions, NurbsPart, collide_body, collide_parts};
use crate::session::emit::StepScope;
use crate::session::options::StepContext;
use crate::session::state::SessionState;
use glam::DVec3;
use serde::Serialize;

/// The figures of a NURBS step.
#[derive(Serialize)]
struct NurbsFigures<'a> {
    /// The part added or moved.
    part: &'a str,
    /// Parts in the scene.
    parts: usize,
    /// Leaves of its subdivision.
    leaves: usize,
    /// Least distance to the body within the threshold, m (absent: farther).
    body_distance_m: Option<f64>,
    /// Its leaf corners inside the body.
    inside_body: usize,
    /// Least distance to another part within the threshold, m (absent: farther).
    part_distance_m: Option<f64>,
    /// Whether it collides with anything.
    colliding: bool,
}

/// `part` against the body and every other part of `state`.
pub(in crate::session) fn contacts(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    part: &NurbsPart,
    options: &NurbsOptions,
) -> Vec<Contact> {
    let body = &state.body;
    let probe = super::garment::body_probe(scope, body, &mut state.probe, cx);
    let hulls = match &mut state.nurbs_body {
        Some(h) => h,
        slot @ None => slot.insert(scope.timed("nurbs.body_hulls", || {
            BodyHulls::new(&body.mesh.mesh.positions, &body.mesh.mesh.triangles)
        })),
    };
    let index = probe.index();
    scope.timed("nurbs.collide", || {
        let mut out: Vec<Contact> = collide_body(part, hulls, options.threshold_m, |p: DVec3| index.winding(p) != 0)
            .into_iter()
            .collect();
        for other in state.nurbs.iter().filter(|o| o.name != part.name) {
            out.extend(collide_parts(part, other, options.threshold_m));
        }
        out
    })
}

pub(in crate::session) fn record(
    scope: &mut StepScope<'_, '_, '_>,
    part: &NurbsPart,
    parts: usize,
    contacts: &[Contact],
) {
    let body = contacts.iter().find(|c| c.other == "body");
    scope.record(&NurbsFigures {
        part: &part.name,
        parts,
        leaves: part.tree.patches.len(),
        body_distance_m: body.map(|c| c.distance_m).filter(|d| d.is_finite()),
        inside_body: body.map_or(0, |c| c.inside),
        part_distance_m: contacts
            .iter()
            .filter(|c| c.other != "body")
            .map(|c| c.distance_m)
            .reduce(f64::min),
        colliding: contacts.iter().any(|c| c.colliding),
    });
}

pub(in crate::session) fn describe(c: &Contact, threshold: f64) -> String {
    if c.inside > 0 {
        format!("'{}' would have {} point(s) inside the {}", c.part, c.inside, c.other)
    } else {
        format!(
            "'{}' would come {:.3} mm from '{}', nearer than the threshold {:.3} mm",
            c.part,
            c.distance_m * 1e3,
            c.other,
            threshold * 1e3
        )
    }
}
