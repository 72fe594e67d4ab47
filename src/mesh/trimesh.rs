//! The indexed triangle mesh every stage shares.

use glam::DVec3;

/// An indexed triangle mesh in metres (`y` up). Triangles index into `positions`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions, m (world frame) for bodies and garments.
    pub positions: Vec<DVec3>,
    /// Triangles as vertex indices, counter-clockwise seen from outside once validated.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// The three corners of triangle `t`.
    pub fn corners(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Area-weighted normal (twice the area in length) of triangle `t`.
    pub fn scaled_normal(&self, t: usize) -> DVec3 {
        let [a, b, c] = self.corners(t);
        (b - a).cross(c - a)
    }

    /// Axis-aligned bounds `(min, max)`; `None` for an empty mesh.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))),
        )
    }

    /// Enclosed volume by the divergence theorem, `sum (a . (b x c)) / 6` over the triangles
    /// (cubic mesh units; positive for outward-facing triangles).
    pub fn signed_volume(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.corners(t);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// Total surface area (square mesh units).
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| 0.5 * self.scaled_normal(t).length())
            .sum()
    }

    /// Per-vertex normals: the normalized sum of incident area-weighted face normals.
    pub fn vertex_normals(&self) -> Vec<DVec3> {
        vertex_normals_of(&self.positions, &self.triangles)
    }

    /// Every triangle split into four at its edges' midpoints (the same surface, each
    /// shared midpoint once): the new vertices after the old, in first-met order.
    pub fn split_in_four(&self) -> Self {
        let mut positions = self.positions.clone();
        let mut mid = std::collections::BTreeMap::new();
        let mut at = |a: u32, b: u32, positions: &mut Vec<DVec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                positions.push(0.5 * (positions[a as usize] + positions[b as usize]));
                (positions.len() - 1) as u32
            })
        };
        let mut triangles = Vec::with_capacity(4 * self.triangles.len());
        for &[a, b, c] in &self.triangles {
            let (ab, bc, ca) = (
                at(a, b, &mut positions),
                at(b, c, &mut positions),
                at(c, a, &mut positions),
            );
            triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        Self { positions, triangles }
    }

    /// Positions as `f32` triples (for display and export).
    pub fn positions_f32(&self) -> Vec<[f32; 3]> {
        self.positions.iter().map(|p| p.as_vec3().to_array()).collect()
    }
}

/// [`TriMesh::vertex_normals`] of the mesh `triangles` make over `positions`, without
/// building the mesh.
pub fn vertex_normals_of(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let mut normals = Vec::new();
    vertex_normals_into(positions, triangles, &mut normals);
    normals
}

/// [`vertex_normals_of`] written into `normals` (its old contents dropped), so that a caller
/// that makes normals again and again reuses one buffer: each vertex's faces' cross
/// products summed in face order, then normalised in place (the same bits).
pub fn vertex_normals_into(positions: &[DVec3], triangles: &[[u32; 3]], normals: &mut Vec<DVec3>) {
    normals.clear();
    normals.resize(positions.len(), DVec3::ZERO);
    for tri in triangles {
        let [a, b, c] = tri.map(|v| positions[v as usize]);
        let n = (b - a).cross(c - a);
        for &v in tri {
            normals[v as usize] += n;
        }
    }
    for n in normals.iter_mut() {
        *n = n.normalize_or_zero();
    }
}
