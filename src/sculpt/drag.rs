//! The drag ([sculpt] section 2): a pick point on the mesh, a radius `r`, a peak offset
//! `h` and a direction; every vertex within `r` of the pick moves by `h f(d / r)` along the
//! direction.
//!
//! **Distance.** `d` is the Euclidean distance from the pick point, over the vertices
//! *connected* to the picked face through vertices within `r` (a flood over the mesh's
//! edges that stops at the radius). A garment is thin and folded: the back of a sleeve or
//! the other leg can lie within `r` of the pick in space without being part of the surface
//! the user touched, and the flood leaves them alone. Within the flooded patch the distance
//! is the exact Euclidean one, so the falloff's smoothness carries over to the surface
//! unchanged (a geodesic along edges would make the bump polygonal on a structured mesh).
//!
//! **Stopping at an obstacle.** [`displace_clear_of`] takes a test for the places a
//! vertex must not go (in a session: inside the body or nearer to it than the garment's
//! ease). A vertex whose offset would end there moves along its offset only as far as the
//! test allows, found by bisection (`sculpt.stop.bisection`, to 0.01 mm): a push into the
//! body flattens against it smoothly, vertex by vertex, instead of going in and being
//! thrown back out by the collision response.
//!
//! **Direction.** By default the surface normal at the pick (the picked face's vertex
//! normals, interpolated at the pick's barycentric coordinates). A positive peak pulls
//! outward, a negative one pushes in.

use glam::DVec3;

use super::falloff::Falloff;
use super::options::SculptError;
use crate::geom::closest::closest_on_triangle;
use crate::mesh::TriMesh;

/// One drag.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drag {
    /// Where the user picked, m (snapped to the nearest point of the mesh).
    pub at: DVec3,
    /// Radius of the moved region, m (> 0).
    pub radius: f64,
    /// Offset of the pick point, m (negative: against the direction).
    pub peak: f64,
    /// Direction of the offset (normalised); `None`: the surface normal at the pick.
    pub direction: Option<DVec3>,
    /// The falloff profile.
    pub falloff: Falloff,
}

impl Drag {
    /// A drag along the surface normal with the default falloff.
    pub fn new(at: DVec3, radius: f64, peak: f64) -> Self {
        Self {
            at,
            radius,
            peak,
            direction: None,
            falloff: Falloff::default(),
        }
    }
}

/// The picked point of the mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    /// The nearest point of the mesh to [`Drag::at`].
    pub point: DVec3,
    /// The face it lies on.
    pub face: u32,
    /// The unit surface normal there.
    pub normal: DVec3,
    /// Distance from [`Drag::at`] to the point, m.
    pub distance: f64,
}

/// A drag applied to a mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Displacement {
    /// The pick.
    pub pick: Pick,
    /// Unit direction of the offsets.
    pub direction: DVec3,
    /// The moved vertices and their offsets, by vertex index (zero offsets left out).
    pub offsets: Vec<(u32, DVec3)>,
    /// All positions after the drag.
    pub positions: Vec<DVec3>,
    /// Faces with a moved corner, sorted: the region the refinement works on.
    pub region: Vec<u32>,
    /// Vertices whose offset was shortened at the obstacle.
    pub stopped: usize,
}

/// How close to the obstacle a stopped vertex ends, m (the bisection's bracket).
pub const STOP_TOLERANCE_M: f64 = 1e-5;

/// The point of `mesh` nearest to `at`, with its face and the interpolated normal.
///
/// # Errors
/// [`SculptError::EmptyMesh`] for a mesh without faces.
pub fn pick(mesh: &TriMesh, normals: &[DVec3], at: DVec3) -> Result<Pick, SculptError> {
    let mut best: Option<(f64, u32, DVec3)> = None;
    for t in 0..mesh.triangles.len() {
        let (q, _) = closest_on_triangle(at, mesh.corners(t));
        let d = q.distance_squared(at);
        if best.is_none_or(|(bd, _, _)| d < bd) {
            best = Some((d, t as u32, q));
        }
    }
    let (d2, face, point) = best.ok_or(SculptError::EmptyMesh)?;
    let [a, b, c] = mesh.corners(face as usize);
    let w = barycentric(point, [a, b, c]);
    let tri = mesh.triangles[face as usize];
    let interpolated: DVec3 = (0..3).map(|k| w[k] * normals[tri[k] as usize]).sum();
    let normal = interpolated
        .try_normalize()
        .or_else(|| (b - a).cross(c - a).try_normalize())
        .unwrap_or(DVec3::Y);
    Ok(Pick {
        point,
        face,
        normal,
        distance: d2.sqrt(),
    })
}

/// Barycentric coordinates of `p` (in the triangle's plane) in `[a, b, c]`; the centroid's
/// for a degenerate triangle.
pub(crate) fn barycentric(p: DVec3, [a, b, c]: [DVec3; 3]) -> [f64; 3] {
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let (d00, d01, d11) = (v0.dot(v0), v0.dot(v1), v1.dot(v1));
    let (d20, d21) = (v2.dot(v0), v2.dot(v1));
    let den = d00 * d11 - d01 * d01;
    if den.abs() <= 1e-300 || !den.is_finite() {
        return [1.0 / 3.0; 3];
    }
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    [1.0 - v - w, v, w]
}

/// Applies `drag` to `mesh` (whose unit vertex normals are `normals`).
///
/// # Errors
/// A radius that is not a positive finite length, a zero direction, a pick farther from
/// the mesh than the radius, or an empty mesh.
pub fn displace(mesh: &TriMesh, normals: &[DVec3], drag: &Drag) -> Result<Displacement, SculptError> {
    displace_clear_of(mesh, normals, drag, None)
}

/// [`displace`], each offset shortened where it would end in `keep_out` (true where a
/// vertex must not go).
///
/// # Errors
/// As [`displace`].
pub fn displace_clear_of(
    mesh: &TriMesh,
    normals: &[DVec3],
    drag: &Drag,
    keep_out: Option<&(dyn Fn(DVec3) -> bool + Sync)>,
) -> Result<Displacement, SculptError> {
    if !(drag.radius.is_finite() && drag.radius > 0.0) {
        return Err(SculptError::Radius(drag.radius));
    }
    if !drag.peak.is_finite() || !drag.at.is_finite() {
        return Err(SculptError::NotFinite);
    }
    let direction = match drag.direction {
        Some(d) => d.try_normalize().ok_or(SculptError::ZeroDirection)?,
        None => DVec3::ZERO,
    };
    let pick = pick(mesh, normals, drag.at)?;
    if pick.distance > drag.radius {
        return Err(SculptError::FarPick {
            distance: pick.distance,
            radius: drag.radius,
            nearest: pick.point,
        });
    }
    let direction = if drag.direction.is_some() {
        direction
    } else {
        pick.normal
    };
    let n = mesh.positions.len();
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); n];
    for tri in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            neighbours[a as usize].push(b);
            neighbours[b as usize].push(a);
        }
    }
    // Flood from the picked face's corners over vertices within the radius.
    let within = |v: u32| mesh.positions[v as usize].distance(pick.point) < drag.radius;
    let mut reached = vec![false; n];
    let mut stack: Vec<u32> = mesh.triangles[pick.face as usize]
        .iter()
        .copied()
        .filter(|&v| within(v))
        .collect();
    for &v in &stack {
        reached[v as usize] = true;
    }
    while let Some(v) = stack.pop() {
        for &w in &neighbours[v as usize] {
            if !reached[w as usize] && within(w) {
                reached[w as usize] = true;
                stack.push(w);
            }
        }
    }
    let mut positions = mesh.positions.clone();
    let mut offsets = Vec::new();
    let mut stopped = 0;
    let search = crate::convergence::Bisection {
        name: "sculpt.stop.bisection",
        steps: 64,
        tolerance: STOP_TOLERANCE_M,
        stop_at_tolerance: true,
    };
    for v in (0..n as u32).filter(|&v| reached[v as usize]) {
        let p = mesh.positions[v as usize];
        let d = p.distance(pick.point);
        let mut offset = direction * (drag.peak * drag.falloff.value(d / drag.radius));
        if let Some(out) = keep_out
            && offset != DVec3::ZERO
            && out(p + offset)
        {
            stopped += 1;
            offset = if out(p) {
                DVec3::ZERO
            } else {
                search.run(p, p + offset, |q| !out(q)).0 - p
            };
        }
        if offset != DVec3::ZERO {
            positions[v as usize] += offset;
            offsets.push((v, offset));
        }
    }
    let mut moved = vec![false; n];
    for &(v, _) in &offsets {
        moved[v as usize] = true;
    }
    let region = (0..mesh.triangles.len() as u32)
        .filter(|&t| mesh.triangles[t as usize].iter().any(|&v| moved[v as usize]))
        .collect();
    Ok(Displacement {
        pick,
        direction,
        offsets,
        positions,
        region,
        stopped,
    })
}
