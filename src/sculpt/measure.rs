//! The figures a sculpt is compared by, over the faces of the sculpted region.
//!
//! * **max edge**: the longest edge of a region face, m.
//! * **min angle**: the smallest corner angle of a region face, degrees (slivers show here).
//! * **smoothness**: the mean angle between the normals of two region faces that share an
//!   edge, degrees: how far the surface turns from one face to the next. 0 is flat; lower
//!   is smoother to the eye (shading follows the normals). `max_turn` is the largest such
//!   angle (a crease or a fold-over shows here).

use std::collections::BTreeMap;

use glam::DVec3;

use crate::mesh::TriMesh;

/// Figures of a mesh over its region faces.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Measures {
    /// All faces of the mesh.
    pub faces: usize,
    /// Faces of the region.
    pub region_faces: usize,
    /// Longest edge of a region face, m.
    pub max_edge_m: f64,
    /// Smallest corner angle of a region face, degrees.
    pub min_angle_deg: f64,
    /// Mean angle between the normals of adjacent region faces, degrees.
    pub smoothness: f64,
    /// Largest angle between the normals of adjacent region faces, degrees.
    pub max_turn_deg: f64,
}

fn angle(u: DVec3, v: DVec3) -> f64 {
    u.angle_between(v).to_degrees()
}

/// The figures of `mesh` over the faces `region` marks.
pub fn measure(mesh: &TriMesh, region: &[bool]) -> Measures {
    let mut m = Measures {
        faces: mesh.triangles.len(),
        min_angle_deg: 180.0,
        ..Measures::default()
    };
    let mut normals: BTreeMap<(u32, u32), Vec<DVec3>> = BTreeMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate().filter(|(t, _)| region[*t]) {
        m.region_faces += 1;
        let p = mesh.corners(t);
        for k in 0..3 {
            let (a, b, c) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            m.max_edge_m = m.max_edge_m.max(a.distance(b));
            m.min_angle_deg = m.min_angle_deg.min(angle(b - a, c - a));
            let e = (tri[k].min(tri[(k + 1) % 3]), tri[k].max(tri[(k + 1) % 3]));
            normals.entry(e).or_default().push(mesh.scaled_normal(t));
        }
    }
    let turns: Vec<f64> = normals
        .values()
        .filter_map(|n| match n.as_slice() {
            [a, b] => Some(angle(*a, *b)),
            _ => None,
        })
        .collect();
    if m.region_faces == 0 {
        m.min_angle_deg = 0.0;
    }
    if !turns.is_empty() {
        m.smoothness = turns.iter().sum::<f64>() / turns.len() as f64;
        m.max_turn_deg = turns.iter().copied().fold(0.0, f64::max);
    }
    m
}
