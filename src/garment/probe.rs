//! Clearance against the body: signed distance from parry3d's oriented triangle mesh (its
//! BVH and pseudo-normals), and pushing curve samples out to a gap.
//!
//! Used for the curves that are not cut from a body section (shoulder seams, the crotch
//! junction, contour spans between rings): their samples are moved out along the surface
//! normal until they stand `gap` off the skin.

use glam::DVec3;
use parry3d::query::PointQuery;
use parry3d::shape::{TriMesh as ParryMesh, TriMeshFlags};

use crate::mesh::TriMesh;

/// A body prepared for distance queries (built once per body).
pub struct BodyProbe {
    mesh: ParryMesh,
}

impl std::fmt::Debug for BodyProbe {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BodyProbe")
            .field("triangles", &self.mesh.num_triangles())
            .finish()
    }
}

impl BodyProbe {
    /// Builds the probe; `None` if parry refuses the mesh (no triangles, or not orientable).
    pub fn new(mesh: &TriMesh) -> Option<Self> {
        let vertices = mesh.positions.iter().map(|p| p.as_vec3()).collect();
        let mesh = ParryMesh::with_flags(vertices, mesh.triangles.clone(), TriMeshFlags::ORIENTED).ok()?;
        Some(Self { mesh })
    }

    /// The nearest surface point and the signed distance (negative inside).
    pub fn nearest(&self, p: DVec3) -> (DVec3, f64) {
        let projection = self.mesh.project_local_point(p.as_vec3(), true);
        let foot = projection.point.as_dvec3();
        let d = p.distance(foot);
        (foot, if projection.is_inside { -d } else { d })
    }

    /// Signed distance to the body surface (negative inside).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        self.nearest(p).1
    }

    /// Moves `p` out until it stands at least `gap` off the body: from the nearest surface
    /// point along the outward direction. A few passes settle points near concave creases.
    /// Points already `gap` away are returned unchanged (bit for bit).
    pub fn clear(&self, p: DVec3, gap: f64) -> DVec3 {
        let mut q = p;
        for _ in 0..4 {
            let (foot, d) = self.nearest(q);
            // f32 queries: accept a hair under the gap.
            if d >= gap * (1.0 - 1e-4) {
                break;
            }
            let mut out = (q - foot) * d.signum();
            if out.length_squared() <= 1e-24 {
                out = self.normal_at(foot);
            }
            q = foot + out.normalize_or_zero() * gap;
        }
        q
    }

    fn normal_at(&self, foot: DVec3) -> DVec3 {
        let (_, feature) = self.mesh.project_local_point_and_get_feature(foot.as_vec3());
        match feature {
            parry3d::shape::FeatureId::Face(f) => {
                let t = self.mesh.triangle(f % self.mesh.num_triangles() as u32);
                t.normal().map_or(DVec3::Y, |n| n.as_dvec3())
            }
            _ => DVec3::Y,
        }
    }
}
