//! Which side of a garment is its outside: the side away from the body. A garment's faces
//! agree, on the whole (area-weighted), with the body's outward normal at the nearest skin
//! when they face away from it, also where the garment dips inside.

use crate::collision::BodyIndex;
use crate::mesh::TriMesh;

/// The area-weighted agreement of `triangles` of `mesh` with the body's outward normal at
/// the skin nearest each one's centre: positive when they face away from the body.
pub fn facing(mesh: &TriMesh, triangles: impl IntoIterator<Item = usize>, index: &BodyIndex) -> f64 {
    let reach = 2.0 * index.height;
    triangles
        .into_iter()
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            let n = (b - a).cross(c - a);
            index
                .nearest((a + b + c) / 3.0, reach)
                .map_or(0.0, |near| n.dot(near.normal))
        })
        .sum()
}

/// `mesh` facing away from the body: its faces all turned when, on the whole, they face it.
pub fn away_from_body(mut mesh: TriMesh, index: &BodyIndex) -> TriMesh {
    if facing(&mesh, 0..mesh.triangles.len(), index) < 0.0 {
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
    }
    mesh
}
