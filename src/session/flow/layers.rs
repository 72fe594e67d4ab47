//! Layers in a session: the garments under the one a step works on, as surfaces
//! ([`Below`]), and the push of that garment out in front of them after its body collision:
//! its M0 against their M0s (before M1 is built on it), then its latest mesh (the last
//! sculpt, else M1) against their latest meshes. Where a push moved a mesh, its body check
//! is made again, so the step's guarantee (nothing inside or through the body) holds for
//! the pushed mesh. The certificate between layers is [`crate::layers::certify_layers`].

use glam::DVec3;

use crate::collision::{self, BodyIndex, Quality};
use crate::layers::{
    LayerError, LayerSurface, PushOptions, PushReport, away_from_body, certify_layers, push_outside_along,
};
use crate::m1::M1Collision;
use crate::mesh::TriMesh;
use crate::session::stage::{LayerPair, Layered};
use crate::session::state::{GarmentState, Worn};

/// A garment under the one a step works on.
pub(in crate::session) struct Below {
    /// Its name.
    pub(in crate::session) name: String,
    /// Its M0 after its collision (and its own pushes), facing away from the body.
    pub(in crate::session) m0: LayerSurface,
    /// Its latest mesh (the last sculpt, else M1), when it has one beyond M0.
    pub(in crate::session) latest: Option<LayerSurface>,
}

impl Below {
    /// The surface the latest mesh of a garment over it is pushed against.
    fn latest(&self) -> &LayerSurface {
        self.latest.as_ref().unwrap_or(&self.m0)
    }
}

/// The garment's latest mesh beyond M0: the last sculpt's result, else M1 (after their
/// collisions); `None` when it has neither.
pub(in crate::session) fn latest_mesh(g: &GarmentState) -> Option<TriMesh> {
    match (&g.sculpted, &g.m1) {
        (Some(s), _) => Some(s.mesh()),
        (None, Some(m1)) => Some(TriMesh {
            positions: m1.collision.positions.clone(),
            triangles: m1.m1.mesh.triangles.clone(),
        }),
        (None, None) => None,
    }
}

/// The garment's surface as the layers see it: its latest mesh, else its collided M0.
fn surface_mesh(g: &GarmentState) -> Option<TriMesh> {
    latest_mesh(g).or_else(|| g.collision.as_ref().map(|c| c.collision.mesh.clone()))
}

/// The worn garments `worn` (those under the step's garment) as surfaces.
///
/// # Failures
/// [`LayerError`] for a garment that is not a manifold surface.
pub(in crate::session) fn below(worn: &[Worn], index: &BodyIndex) -> Result<Vec<Below>, LayerError> {
    worn.iter()
        .filter_map(|w| {
            let g = w.garment.as_ref()?;
            let m0 = g.collision.as_ref()?.collision.mesh.clone();
            Some((w.name.clone(), m0, latest_mesh(g)))
        })
        .map(|(name, m0, latest)| {
            Ok(Below {
                name,
                m0: LayerSurface::new(&away_from_body(m0, index), "inner")?,
                latest: latest
                    .map(|m| LayerSurface::new(&away_from_body(m, index), "inner"))
                    .transpose()?,
            })
        })
        .collect()
}

/// Pushes `positions` (of a mesh with `triangles`) out in front of every surface `under`
/// picks from `below`, innermost first; the reports' `after` is the certificate against
/// each once all pushes are made.
fn push_all(
    positions: &mut [DVec3],
    triangles: &[[u32; 3]],
    below: &[Below],
    under: impl Fn(&Below) -> &LayerSurface,
    (index, options): (&BodyIndex, &PushOptions),
) -> Result<(Vec<PushReport>, bool), LayerError> {
    let mut mesh = away_from_body(
        TriMesh {
            positions: positions.to_vec(),
            triangles: triangles.to_vec(),
        },
        index,
    );
    let mut reports = Vec::with_capacity(below.len());
    let reach = 2.0 * index.height;
    let outward = |p: DVec3| index.nearest(p, reach).map(|n| n.normal);
    for b in below {
        reports.push(push_outside_along(under(b), &mut mesh, options, &outward)?);
    }
    let moved = reports.iter().any(|r| r.moved > 0);
    if moved && below.len() > 1 {
        let surface = LayerSurface::new(&mesh, "outer")?;
        for (r, b) in reports.iter_mut().zip(below) {
            r.after = certify_layers(under(b), &surface);
        }
    }
    positions.copy_from_slice(&mesh.positions);
    Ok((reports, moved))
}

/// The body check of a pushed mesh (every vertex, edge and face), as the collision's own.
fn body_check(
    index: &BodyIndex,
    before: &[DVec3],
    after: &[DVec3],
    triangles: &[[u32; 3]],
    edges: &[[u32; 2]],
) -> Quality {
    collision::quality(index, before, after, edges, &[]).with_faces(index, after, triangles, None)
}

/// Pushes the state's collided M0 out in front of the garments under it, checking the
/// body again when it moved; returns the reports, one per garment under it.
pub(in crate::session) fn push_m0(
    index: &BodyIndex,
    (garment, c): (&collision::GarmentMesh, &mut collision::Collision),
    below: &[Below],
    ease: f64,
) -> Result<Vec<PushReport>, LayerError> {
    let options = PushOptions {
        ease,
        ..PushOptions::default()
    };
    let before = c.mesh.positions.clone();
    let (reports, moved) = push_all(
        &mut c.mesh.positions,
        &c.mesh.triangles,
        below,
        |b| &b.m0,
        (index, &options),
    )?;
    if moved {
        let (positions, triangles) = (&c.mesh.positions, &c.mesh.triangles);
        c.quality = collision::quality(index, &before, positions, &garment.edges, &c.responses)
            .with_faces(index, positions, triangles, None)
            .with_face_clearance(index, positions, triangles, c.ease, None);
    }
    Ok(reports)
}

/// Pushes a refined mesh's collided positions (M1's or a sculpt's) out in front of the
/// latest meshes under it, checking the body again when it moved.
fn push_refined(
    index: &BodyIndex,
    c: &mut M1Collision,
    triangles: &[[u32; 3]],
    below: &[Below],
    options: &PushOptions,
) -> Result<Vec<PushReport>, LayerError> {
    let before = c.positions.clone();
    let (reports, moved) = push_all(&mut c.positions, triangles, below, Below::latest, (index, options))?;
    if moved {
        let edges = crate::mesh::topology::undirected_edges(&TriMesh {
            positions: Vec::new(),
            triangles: triangles.to_vec(),
        });
        let q = body_check(index, &before, &c.positions, triangles, &edges);
        c.crossing_after_edges = q.crossing.iter().map(|&e| edges[e as usize]).collect();
        c.inside_after = q.inside.clone();
        c.pierced_after = q.pierced.clone();
        c.quality = q;
    }
    Ok(reports)
}

/// After the state's M1 and sculpts are made: pushes its latest mesh out in front of the
/// garments under it, and puts together what the layers show (`m0`: the M0 pushes).
pub(in crate::session) fn finish(
    index: &BodyIndex,
    state: &mut GarmentState,
    below: &[Below],
    m0: Vec<PushReport>,
    ease: f64,
) -> Result<(), LayerError> {
    let options = PushOptions {
        ease,
        ..PushOptions::default()
    };
    let latest = if let Some(s) = &mut state.sculpted {
        let triangles = s.sculpt.refined.mesh.triangles.clone();
        Some(push_refined(index, &mut s.collision, &triangles, below, &options)?)
    } else if let Some(m1) = &mut state.m1 {
        let triangles = m1.m1.mesh.triangles.clone();
        Some(push_refined(index, &mut m1.collision, &triangles, below, &options)?)
    } else {
        None
    };
    let pairs = below
        .iter()
        .zip(m0)
        .enumerate()
        .map(|(k, (b, m0))| LayerPair {
            under: b.name.clone(),
            m0,
            latest: latest.as_ref().map(|l| l[k].clone()),
        })
        .collect();
    let mesh = surface_mesh(state)
        .map(|m| away_from_body(m, index))
        .unwrap_or_default();
    let gaps = below.last().map_or_else(Vec::new, |b| {
        mesh.positions
            .iter()
            .map(|&p| crate::layers::certificate::signed_gap(b.latest(), p).unwrap_or(f64::NAN))
            .collect()
    });
    state.layered = Some(Layered {
        pairs,
        mesh,
        gaps,
        under: below
            .iter()
            .map(|b| (b.name.clone(), b.latest().mesh.clone()))
            .collect(),
    });
    Ok(())
}

/// The first pair of layers out of order after the pushes: the garment under, and the
/// certificate of M0's push or else the latest mesh's.
pub(in crate::session) fn out_of_order(state: &GarmentState) -> Option<(String, crate::layers::LayerCounts)> {
    state.layered.as_ref()?.pairs.iter().find_map(|p| {
        let unclear = |r: &PushReport| (!r.after.clear()).then(|| r.after.clone());
        unclear(&p.m0)
            .or_else(|| p.latest.as_ref().and_then(unclear))
            .map(|c| (p.under.clone(), c))
    })
}
