//! The parts of M1 that are M0's: every vertex pinned (where M1's collision moves nothing),
//! with the verdicts M0's collision and check left on them.

use super::M1;
use super::collide::{Kept, M0Collided};

/// The parts of M1 that are M0's (every vertex pinned), with M0's verdicts: its edges M0's
/// check found crossing, its vertices inside, and its faces pierced (a face of M1 whose
/// corners are all pinned is a face of M0 the refinement left whole).
pub(super) fn kept_of_m1(m1: &M1, pinned: &[bool], m0: &M0Collided<'_>) -> Kept {
    let both = |[a, b]: [u32; 2]| pinned.get(a as usize) == Some(&true) && pinned.get(b as usize) == Some(&true);
    let mut crossing: Vec<[u32; 2]> = m0
        .crossing
        .iter()
        .map(|&[a, b]| [a.min(b), a.max(b)])
        .filter(|&e| both(e) && m1.edges.binary_search(&e).is_ok())
        .collect();
    crossing.sort_unstable();
    crossing.dedup();
    let inside: Vec<u32> = m0
        .inside
        .iter()
        .copied()
        .filter(|&v| pinned.get(v as usize) == Some(&true))
        .collect();
    let sorted = |mut t: [u32; 3]| {
        t.sort_unstable();
        t
    };
    let mut m0_pierced: Vec<[u32; 3]> = m0
        .pierced
        .iter()
        .filter_map(|&f| m0.triangles.get(f as usize).map(|&t| sorted(t)))
        .collect();
    m0_pierced.sort_unstable();
    let pierced = if m0_pierced.is_empty() {
        Vec::new()
    } else {
        (0..m1.mesh.triangles.len() as u32)
            .filter(|&f| {
                let t = m1.mesh.triangles[f as usize];
                t.iter().all(|&v| pinned[v as usize]) && m0_pierced.binary_search(&sorted(t)).is_ok()
            })
            .collect()
    };
    Kept {
        crossing,
        inside,
        pierced,
    }
}
