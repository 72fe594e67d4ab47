//! Cutting a mesh into panels along its seam edges.
//!
//! Faces are joined across every edge that is not a seam; each group is a panel. A panel's
//! own vertices are its faces' corners joined the same way, so a seam that runs into a
//! panel and stops (a slit) opens it there too. A panel must be a disc: one boundary loop,
//! Euler characteristic `V - E + F = 1`, no vertex where its boundary touches itself.

use glam::DVec3;

use crate::garment::m0::find;

/// One panel: its faces in the mesh and its own vertices and triangles.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// Name (`torso.front_left`, `sleeve.left`, ...).
    pub name: String,
    /// The mesh's faces in it, ascending.
    pub faces: Vec<u32>,
    /// The mesh vertex of each of its own vertices.
    pub vertex: Vec<u32>,
    /// Its own vertices' positions, m.
    pub positions: Vec<DVec3>,
    /// Its triangles over its own vertices, in the mesh's orientation.
    pub triangles: Vec<[u32; 3]>,
    /// Its boundary loop, its own vertices in order (the triangles' orientation).
    pub boundary: Vec<u32>,
}

/// Why a panel is not a disc.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "panel {panel} is not a disc ({loops} boundary loops, Euler characteristic {euler}{pinch}): add a seam across it{hint}"
)]
pub struct NotADisc {
    /// The panel.
    pub panel: String,
    /// Its boundary loops.
    pub loops: usize,
    /// `V - E + F`.
    pub euler: i64,
    /// `", its boundary touching itself"` when a vertex has two boundary edges out.
    pub pinch: String,
    /// The seams that would cut it, when known.
    pub hint: String,
}

/// The mesh's faces grouped by `panel_of` (one entry per face, dense panel indices): each
/// panel's own mesh, vertices split where a seam edge (`is_seam`) runs between two of its
/// faces.
pub fn split(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    panel_of: &[u32],
    names: &[String],
    is_seam: impl Fn([u32; 2]) -> bool,
) -> Vec<Panel> {
    // Corners (face, k) joined across non-seam edges inside one panel.
    let mut parent: Vec<u32> = (0..3 * triangles.len() as u32).collect();
    for ((a, b), (fa, fb)) in interior_edges(triangles) {
        if panel_of[fa as usize] != panel_of[fb as usize] || is_seam([a, b]) {
            continue;
        }
        for v in [a, b] {
            let (ka, kb) = (corner(triangles, fa, v), corner(triangles, fb, v));
            union(&mut parent, ka, kb);
        }
    }
    let count = names.len();
    let mut faces: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (f, &p) in panel_of.iter().enumerate() {
        faces[p as usize].push(f as u32);
    }
    faces
        .into_iter()
        .zip(names)
        .map(|(faces, name)| {
            let mut local = std::collections::BTreeMap::new();
            let mut vertex = Vec::new();
            let mut tris = Vec::with_capacity(faces.len());
            for &f in &faces {
                tris.push(std::array::from_fn(|k| {
                    let root = find(&mut parent, 3 * f + k as u32);
                    *local.entry(root).or_insert_with(|| {
                        vertex.push(triangles[f as usize][k]);
                        vertex.len() as u32 - 1
                    })
                }));
            }
            let positions: Vec<DVec3> = vertex.iter().map(|&v| positions[v as usize]).collect();
            Panel {
                name: name.clone(),
                faces,
                boundary: Vec::new(),
                vertex,
                positions,
                triangles: tris,
            }
        })
        .collect()
}

/// The faces grouped across every edge that is not a seam: each face's group, numbered
/// by their first face, and the number of groups.
pub fn components(triangles: &[[u32; 3]], is_seam: impl Fn([u32; 2]) -> bool) -> (Vec<u32>, usize) {
    let mut parent: Vec<u32> = (0..triangles.len() as u32).collect();
    for ((a, b), (fa, fb)) in interior_edges(triangles) {
        if !is_seam([a, b]) {
            union(&mut parent, fa, fb);
        }
    }
    let mut id = vec![u32::MAX; triangles.len()];
    let mut count = 0;
    let out = (0..triangles.len() as u32)
        .map(|f| {
            let r = find(&mut parent, f) as usize;
            if id[r] == u32::MAX {
                id[r] = count;
                count += 1;
            }
            id[r]
        })
        .collect();
    (out, count as usize)
}

/// Checks that a panel is a disc and finds its boundary loop.
pub fn disc_boundary(panel: &Panel) -> Result<Vec<u32>, NotADisc> {
    let half = crate::pattern::flatten::boundary_half_edges(&panel.triangles);
    let v = panel.positions.len() as i64;
    let f = panel.triangles.len() as i64;
    let e = (3 * f + half.len() as i64) / 2;
    let euler = v - e + f;
    let mut next = vec![u32::MAX; panel.positions.len()];
    let mut pinched = false;
    for &[a, b] in &half {
        pinched |= next[a as usize] != u32::MAX;
        next[a as usize] = b;
    }
    let mut seen = vec![false; panel.positions.len()];
    let mut loops = Vec::new();
    for &[start, _] in &half {
        if seen[start as usize] {
            continue;
        }
        let mut walk = Vec::new();
        let mut v = start;
        while !seen[v as usize] && v != u32::MAX {
            seen[v as usize] = true;
            walk.push(v);
            v = next[v as usize];
        }
        loops.push(walk);
    }
    if loops.len() != 1 || euler != 1 || pinched {
        return Err(NotADisc {
            panel: panel.name.clone(),
            loops: loops.len(),
            euler,
            pinch: if pinched {
                ", its boundary touching itself".into()
            } else {
                String::new()
            },
            hint: String::new(),
        });
    }
    Ok(loops.swap_remove(0))
}

/// Every edge shared by two faces: `((a, b), (face, face))`, `a < b`, sorted. An edge of
/// more than two faces is paired face by face in order.
pub fn interior_edges(triangles: &[[u32; 3]]) -> Vec<((u32, u32), (u32, u32))> {
    let mut half: Vec<((u32, u32), u32)> = triangles
        .iter()
        .enumerate()
        .flat_map(|(f, t)| {
            (0..3).map(move |k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                ((a.min(b), a.max(b)), f as u32)
            })
        })
        .collect();
    half.sort_unstable();
    half.windows(2)
        .filter(|w| w[0].0 == w[1].0)
        .map(|w| (w[0].0, (w[0].1, w[1].1)))
        .collect()
}

fn corner(triangles: &[[u32; 3]], f: u32, v: u32) -> u32 {
    let k = triangles[f as usize].iter().position(|&x| x == v).unwrap_or(0);
    3 * f + k as u32
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        parent[hi as usize] = lo;
    }
}
