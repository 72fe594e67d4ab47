//! A garment's surface as the layer over it sees it: its triangles in a search tree, the
//! angle-weighted pseudo-normals of its faces, edges and vertices (the side a point is on,
//! after Bærentzen and Aanæs), and which edges and vertices are its openings.
//!
//! A garment is an open surface oriented away from the body, so "behind it" is the body's
//! side of it, and only where the point's nearest surface point is not on an opening: past
//! a hem, a point is beside the garment, not behind it.

use glam::DVec3;

use crate::body::near_tree::NearTree;
use crate::geom::closest::{Feature, closest_on_triangle};
use crate::mesh::topology::NO_NEIGHBOUR;
use crate::mesh::{Adjacency, TriMesh};

/// Why a garment cannot be a layer's surface.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LayerError {
    /// A face names a vertex the mesh does not have, or a position is not finite.
    #[error("the {layer} garment is malformed: {what}")]
    Malformed {
        /// Which layer ("inner", "outer").
        layer: &'static str,
        /// What is wrong, and where.
        what: String,
    },
    /// An edge with three or more faces: no side of it is "behind".
    #[error(
        "the {layer} garment's edge between vertices {a} and {b} has {count} faces: a layer must be a manifold surface"
    )]
    NonManifold {
        /// Which layer ("inner", "outer").
        layer: &'static str,
        /// 0-based vertex.
        a: u32,
        /// 0-based vertex.
        b: u32,
        /// Faces on it.
        count: usize,
    },
}

/// The point of a surface nearest to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// The triangle it is on.
    pub triangle: u32,
    /// The point, m.
    pub point: DVec3,
    /// The pseudo-normal of the feature it is on (unit, away from the body).
    pub normal: DVec3,
    /// How far the query point stands in front of the surface (along `normal`; negative
    /// behind it), m.
    pub signed: f64,
    /// Whether the point is on an opening (a boundary edge or vertex).
    pub on_opening: bool,
    /// The feature of the triangle it is on.
    pub feature: Feature,
}

/// A garment's surface, ready for nearest-point and crossing queries.
#[derive(Clone, Debug)]
pub struct LayerSurface {
    /// The mesh, oriented away from the body.
    pub mesh: TriMesh,
    face_normals: Vec<DVec3>,
    /// Per triangle and edge `k`: the pseudo-normal, and whether the edge is an opening.
    edges: Vec<[(DVec3, bool); 3]>,
    /// Per vertex: the pseudo-normal, and whether it lies on an opening.
    vertices: Vec<(DVec3, bool)>,
    tree: NearTree,
}

/// The angle at `p` between `u` and `v`.
fn angle(u: DVec3, v: DVec3) -> f64 {
    u.angle_between(v)
}

impl LayerSurface {
    /// The surface of `mesh` (oriented away from the body); `layer` names it in errors.
    ///
    /// # Failures
    /// [`LayerError::Malformed`] for a face naming a missing vertex or a position that is
    /// not finite, [`LayerError::NonManifold`] for an edge of three or more faces.
    pub fn new(mesh: &TriMesh, layer: &'static str) -> Result<Self, LayerError> {
        let malformed = |what: String| LayerError::Malformed { layer, what };
        if let Some(v) = mesh.positions.iter().position(|p| !p.is_finite()) {
            return Err(malformed(format!("vertex {v} is not finite")));
        }
        let n = mesh.positions.len() as u32;
        if let Some(t) = mesh.triangles.iter().position(|t| t.iter().any(|&i| i >= n)) {
            return Err(malformed(format!("face {t} names a vertex past the {n} there are")));
        }
        let adjacency = Adjacency::try_new(mesh).map_err(|e| LayerError::NonManifold {
            layer,
            a: e.vertices[0],
            b: e.vertices[1],
            count: e.triangles.len(),
        })?;
        let face_normals: Vec<DVec3> = (0..mesh.triangles.len())
            .map(|t| mesh.scaled_normal(t).normalize_or_zero())
            .collect();
        let mut vertices = vec![(DVec3::ZERO, false); mesh.positions.len()];
        let edges: Vec<[(DVec3, bool); 3]> = (0..mesh.triangles.len())
            .map(|t| {
                std::array::from_fn(|k| {
                    let other = adjacency.neighbours[t][k];
                    if other == NO_NEIGHBOUR {
                        let tri = mesh.triangles[t];
                        vertices[tri[k] as usize].1 = true;
                        vertices[tri[(k + 1) % 3] as usize].1 = true;
                        (face_normals[t], true)
                    } else {
                        (
                            (face_normals[t] + face_normals[other as usize]).normalize_or_zero(),
                            false,
                        )
                    }
                })
            })
            .collect();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let c = tri.map(|i| mesh.positions[i as usize]);
            for k in 0..3 {
                let (p, q, r) = (c[k], c[(k + 1) % 3], c[(k + 2) % 3]);
                vertices[tri[k] as usize].0 += face_normals[t] * angle(q - p, r - p);
            }
        }
        for v in &mut vertices {
            v.0 = v.0.normalize_or_zero();
        }
        let diagonal = mesh.bounds().map_or(1.0, |(lo, hi)| (hi - lo).length().max(1e-9));
        let slack = 1e-6 * diagonal;
        let corners = |t: u32| mesh.triangles[t as usize].map(|i| mesh.positions[i as usize]);
        let bounds = |t: u32| {
            let c = corners(t);
            let lo = c[0].min(c[1]).min(c[2]) - DVec3::splat(slack);
            let hi = c[0].max(c[1]).max(c[2]) + DVec3::splat(slack);
            (lo.as_vec3(), hi.as_vec3())
        };
        let ids: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
        let tree = NearTree::new(&ids, corners, bounds);
        Ok(Self {
            mesh: mesh.clone(),
            face_normals,
            edges,
            vertices,
            tree,
        })
    }

    /// The nearest point of the surface to `p` (`None` for an empty surface).
    pub fn nearest(&self, p: DVec3) -> Option<Nearest> {
        let mut best: Option<(u32, DVec3, Feature, f64)> = None;
        self.tree.nearest(p.as_vec3(), f32::INFINITY, |t, corners| {
            let (q, feature) = closest_on_triangle(p, *corners);
            let d2 = q.distance_squared(p);
            if best.is_none_or(|b| d2 < b.3) {
                best = Some((t, q, feature, d2));
                // Widened a little: the tree's boxes are f32.
                Some((d2.sqrt() * (1.0 + 1e-6) + 1e-9).powi(2) as f32)
            } else {
                None
            }
        });
        let (t, point, feature, _) = best?;
        let tri = self.mesh.triangles[t as usize];
        let (normal, on_opening) = match feature {
            Feature::Face => (self.face_normals[t as usize], false),
            Feature::Edge(k) => self.edges[t as usize][k as usize],
            Feature::Vertex(k) => self.vertices[tri[k as usize] as usize],
        };
        Some(Nearest {
            triangle: t,
            point,
            normal,
            signed: (p - point).dot(normal),
            on_opening,
            feature,
        })
    }

    /// Calls `visit(triangle, corners)` for every triangle whose box the segment `a..b`
    /// meets (a superset of the triangles it crosses).
    pub fn along(&self, a: DVec3, b: DVec3, mut visit: impl FnMut(u32, &[DVec3; 3])) {
        self.tree.any_on_segment(a, b, 1e-6, |t, c| {
            visit(t, c);
            false
        });
    }

    /// Calls `visit(triangle, corners)` for every triangle whose box meets the box
    /// `lo..hi`.
    pub fn in_box(&self, lo: DVec3, hi: DVec3, mut visit: impl FnMut(u32, &[DVec3; 3])) {
        let pad = DVec3::splat(1e-6 * (hi - lo).length().max(1e-3));
        self.tree.any_in_box(lo - pad, hi + pad, |t, c| {
            visit(t, c);
            false
        });
    }
}
