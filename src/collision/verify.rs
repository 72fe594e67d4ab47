//! The brute-force ground truth ([collide] 4.2: "the most exact test intersects every
//! primitive of both"): every garment vertex against every body triangle by the
//! generalized winding number (inside above one half), and every garment edge against
//! every body triangle. No partitions, no BVH, no pseudo-normals: slow, independent,
//! and what the fast tests are checked against (`--verify`, tests, the benchmark).

use glam::DVec3;

use super::ray::ray_triangle;
use crate::geom::inside::winding_number;
use crate::mesh::TriMesh;

/// The ground truth for one garment mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct GroundTruth {
    /// Whether each vertex lies inside the body.
    pub inside: Vec<bool>,
    /// Whether each edge meets the body surface.
    pub crossing: Vec<bool>,
}

impl GroundTruth {
    /// Number of vertices inside.
    pub fn inside_count(&self) -> usize {
        self.inside.iter().filter(|i| **i).count()
    }

    /// Number of edges crossing.
    pub fn crossing_count(&self) -> usize {
        self.crossing.iter().filter(|c| **c).count()
    }
}

/// Runs `f` over `0..n` on all cores, results in order.
fn parallel<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get()).min(16);
    let chunk = n.div_ceil(threads.max(1)).max(1);
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..n)
            .step_by(chunk)
            .map(|start| {
                let f = &f;
                s.spawn(move || (start..(start + chunk).min(n)).map(f).collect::<Vec<T>>())
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    })
}

/// The ground truth of `positions` and `edges` against the closed `body`.
pub fn ground_truth(body: &TriMesh, positions: &[DVec3], edges: &[[u32; 2]]) -> GroundTruth {
    let inside = parallel(positions.len(), |v| winding_number(body, positions[v]) > 0.5);
    let crossing = parallel(edges.len(), |e| {
        let [a, b] = edges[e];
        let (a, b) = (positions[a as usize], positions[b as usize]);
        (0..body.triangles.len()).any(|t| ray_triangle(a, b - a, body.corners(t), 0.0, 1.0).is_some())
    });
    GroundTruth { inside, crossing }
}
