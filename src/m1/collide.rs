//! M1's collision (\[collide\] section 3.1): M0 has been collided; M1 is collided only where
//! it differs from M0. Its new vertices (and old ones the smoothing moved) are tested
//! exactly against the whole body, those inside are pushed out by their partition's rule
//! (the partition of the M0 vertex they descend from), and the edge rounds lift M1's
//! crossing edges by moving only those vertices: M0's vertices stay where M0's collision
//! put them, so M1 and M0 agree on them. The exact check then measures what differs from M0
//! (the vertices tested, the edges with an end among them); M1's vertices and edges that are
//! M0's, where M0 has them, take M0's own exact check: together, all of M1.

use glam::DVec3;

use crate::collision::faces::FaceRounds;
use crate::collision::quality::{Measured, quality_where};
use crate::collision::{
    BodyIndex, CollisionOptions, Hit, KnownClearance, Quality, Response, VertexRoles, pierced_faces, respond,
    respond_edges, respond_faces, response_ease,
};
use crate::mesh::trimesh::vertex_normals_of;
use crate::par::par_map;

/// M1 after its collision.
#[derive(Clone, Debug, PartialEq)]
pub struct M1Collision {
    /// Vertices tested (those M0 does not have).
    pub tested: usize,
    /// Of those, inside the body before the response.
    pub hits: usize,
    /// M1's edges crossing the body before the response (exact).
    pub crossing_before: usize,
    /// Those edges.
    pub crossing_before_edges: Vec<[u32; 2]>,
    /// The moves made (vertex response, then the edge rounds).
    pub responses: Vec<Response>,
    /// Edges crossing at the start of each edge round.
    pub edge_rounds: Vec<usize>,
    /// M1's positions after the response.
    pub positions: Vec<DVec3>,
    /// The exact check after the response, over all of M1 (`inside` and `crossing` are
    /// left empty: see `crossing_after_edges`).
    pub quality: Quality,
    /// The edges crossing the body after the response.
    pub crossing_after_edges: Vec<[u32; 2]>,
    /// The vertices inside the body after the response, sorted.
    pub inside_after: Vec<u32>,
    /// Faces pierced by the body before the face rounds (after the vertex response and the
    /// edge rounds).
    pub pierced_before: usize,
    /// Faces pierced at the start of each face round.
    pub face_rounds: Vec<usize>,
    /// The faces (indices into the refined mesh's faces) pierced by the body after the
    /// response, ascending.
    pub pierced_after: Vec<u32>,
}

/// What M0's collision left: its vertices inside the body and its edges crossing it (both
/// from its exact check), and per vertex its partition and ring role.
#[derive(Clone, Copy, Debug)]
pub struct M0Collided<'a> {
    /// Vertices inside after M0's response.
    pub inside: &'a [u32],
    /// Edges (their ends) crossing after M0's response.
    pub crossing: &'a [[u32; 2]],
    /// The base's faces.
    pub triangles: &'a [[u32; 3]],
    /// Those the body pierced after the base's response (indices into `triangles`).
    pub pierced: &'a [u32],
    /// Partition of each vertex (from M0's detection).
    pub partition: &'a [usize],
    /// Ring plane normal of each vertex on a garment ring.
    pub ring_normal: &'a [Option<DVec3>],
    /// Its vertices' distances as its exact check measured them, if kept: the check of the
    /// refinement takes those of the base's vertices it leaves in place from here.
    pub measured: Option<&'a Measured>,
}

/// A refinement of a mesh already collided (M1 over M0, a sculpt over the garment): the
/// base's vertices first, with the same indices, then the new ones.
#[derive(Clone, Copy, Debug)]
pub struct RefinedInput<'a> {
    /// The refined mesh's positions.
    pub positions: &'a [DVec3],
    /// Its faces.
    pub triangles: &'a [[u32; 3]],
    /// Its undirected edges, each once.
    pub edges: &'a [[u32; 2]],
    /// The base's vertex count: vertices from here on are new.
    pub base_vertices: usize,
    /// Base vertices that are not where the base has them (smoothed, dragged).
    pub moved: &'a [u32],
    /// A base vertex each vertex descends from (its partition and roles).
    pub anchor: &'a [u32],
}

impl RefinedInput<'_> {
    /// The vertices that differ from the base (moved, then new): what the collision tests.
    pub fn tested(&self) -> Vec<u32> {
        let mut out = self.moved.to_vec();
        out.extend(self.base_vertices as u32..self.positions.len() as u32);
        out
    }
}

/// The partition of each refined vertex: its anchor's in the base (`0` past the base's).
pub fn partition_through(anchor: &[u32], partition: &[usize]) -> Vec<usize> {
    anchor
        .iter()
        .map(|&a| partition.get(a as usize).copied().unwrap_or(0))
        .collect()
}

/// Collides a refinement of a collided mesh: only its new and moved vertices are tested and
/// may move; the base's other vertices stay where the base's collision put them, and its
/// other edges cross exactly when the base's check said so.
pub fn collide_refined(
    index: &BodyIndex,
    refined: &RefinedInput<'_>,
    m0: &M0Collided<'_>,
    garment_ease: f64,
    options: &CollisionOptions,
) -> M1Collision {
    let pinned = pinned_of(refined);
    let (kept, faces) = kept_from_base(refined, &pinned, m0);
    let free = collide_free(index, refined, &pinned, &faces, m0, garment_ease, options);
    assemble(kept, free)
}

/// Which vertices of a refinement stay where the base has them: the base's, but those it
/// moved.
pub(super) fn pinned_of(refined: &RefinedInput<'_>) -> Vec<bool> {
    let mut pinned = vec![true; refined.base_vertices];
    pinned.resize(refined.positions.len(), false);
    refined.moved.iter().for_each(|&v| pinned[v as usize] = false);
    pinned
}

/// What the base's check says of the refinement's parts that are the base's (every vertex
/// pinned): its edges crossing, its vertices inside and its faces pierced.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Kept {
    /// The base's edges crossing, in edge order.
    pub(super) crossing: Vec<[u32; 2]>,
    /// The pinned vertices inside, ascending.
    pub(super) inside: Vec<u32>,
    /// The faces (of the refined mesh) pierced, ascending.
    pub(super) pierced: Vec<u32>,
}

/// The refinement's kept part ([`Kept`]) and the faces with a corner that is not pinned,
/// which its collision checks.
fn kept_from_base(refined: &RefinedInput<'_>, pinned: &[bool], m0: &M0Collided<'_>) -> (Kept, Vec<u32>) {
    let (crossing, inside) = known_from_base(refined, pinned, m0);
    let (pierced, faces) = faces_to_check(refined, pinned, m0);
    (
        Kept {
            crossing,
            inside,
            pierced,
        },
        faces,
    )
}

/// What the collision of a refinement found and did where it differs from its base: at the
/// vertices that are not pinned, the edges with such an end and the faces with such a
/// corner. Vertex, edge and face numbers are the refined mesh's.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Free {
    /// Vertices tested.
    pub(super) tested: usize,
    /// Of those, inside before the response.
    pub(super) hits: usize,
    /// Edges crossing before the response, sorted.
    pub(super) crossing_before: Vec<[u32; 2]>,
    /// The moves made.
    pub(super) responses: Vec<Response>,
    /// Edges crossing at the start of each edge round.
    pub(super) edge_rounds: Vec<usize>,
    /// The positions after the response (the pinned vertices where they were).
    pub(super) positions: Vec<DVec3>,
    /// The check after the response (its `inside` and `crossing` index what it measured).
    pub(super) quality: Quality,
    /// Edges crossing after the response, sorted.
    pub(super) crossing_after: Vec<[u32; 2]>,
    /// Faces pierced before the face rounds.
    pub(super) pierced_before: usize,
    /// Faces pierced at the start of each face round.
    pub(super) face_rounds: Vec<usize>,
    /// Faces pierced after the response, ascending.
    pub(super) pierced_after: Vec<u32>,
}

/// The collision of a refinement's free part (see [`Free`]): `faces` are the faces with a
/// corner not pinned.
#[allow(clippy::too_many_arguments)]
pub(super) fn collide_free(
    index: &BodyIndex,
    refined: &RefinedInput<'_>,
    pinned: &[bool],
    faces: &[u32],
    m0: &M0Collided<'_>,
    garment_ease: f64,
    options: &CollisionOptions,
) -> Free {
    let (partition, ring_normal) = (m0.partition, m0.ring_normal);
    let reach = 0.2 * index.height;
    let positions = refined.positions;
    let tested = refined.tested();
    let m1_partition = partition_through(refined.anchor, partition);
    let normals = vertex_normals_of(refined.positions, refined.triangles);
    let boundary = vec![false; positions.len()];
    let mut rings: Vec<Option<DVec3>> = ring_normal.to_vec();
    rings.resize(positions.len(), None);
    let roles = VertexRoles {
        normals: &normals,
        boundary: &boundary,
        ring_normal: &rings,
        pinned,
    };
    let edges: Vec<[u32; 2]> = refined
        .edges
        .iter()
        .copied()
        .filter(|&[a, b]| !pinned[a as usize] || !pinned[b as usize])
        .collect();
    let before = quality_where(index, positions, positions, &tested, &edges, &[], m0.measured);
    let crossing_before: Vec<[u32; 2]> = before.crossing.iter().map(|&e| edges[e as usize]).collect();
    // The vertices the check found inside are the hits.
    let hits = hits_at(index, positions, &before.inside, &m1_partition, reach);
    let ease = response_ease(index, garment_ease, &options.response);
    let (mut moved, mut responses) = respond(index, positions, &hits, &roles, ease, &options.response);
    // The check before measured every end of these edges: those whose free balls cover
    // them need no ray in the first edge round.
    let free = before.free();
    let known = KnownClearance {
        at: positions,
        free: &free,
    };
    let (edge_responses, edge_rounds, _) = respond_edges(
        index,
        &mut moved,
        &edges,
        &m1_partition,
        &roles,
        ease,
        &options.response,
        None,
        Some(known),
    );
    responses.extend(edge_responses);
    // Faces: those with a corner not pinned are checked, lifted where pierced (face
    // rounds, then edge rounds at the lifted corners) and checked again after.
    let subset: Vec<[u32; 3]> = faces.iter().map(|&f| refined.triangles[f as usize]).collect();
    let rounds = respond_faces(
        index,
        &mut moved,
        (&subset, &edges),
        (0..subset.len() as u32).collect(),
        &m1_partition,
        &roles,
        ease,
        &options.response,
        Some(known),
    );
    let pierced_before = rounds.first.len();
    responses.extend(rounds.lifts.iter().copied());
    // After the response only what moved (and what was inside) is measured again, with the
    // edges at those vertices; the others stand as the check before found them.
    let again = marked(
        positions.len(),
        responses.iter().map(|r| r.vertex).chain(before.inside.iter().copied()),
    );
    let remeasured: Vec<u32> = (0..positions.len() as u32).filter(|&v| again[v as usize]).collect();
    let (touching, untouched): (Vec<usize>, Vec<usize>) =
        (0..edges.len()).partition(|&e| edges[e].iter().any(|&v| again[v as usize]));
    let touching_edges: Vec<[u32; 2]> = touching.iter().map(|&e| edges[e]).collect();
    let quality = quality_where(
        index,
        positions,
        &moved,
        &remeasured,
        &touching_edges,
        &responses,
        m0.measured,
    );
    let crossing_after = crossing_after(
        (&edges, &untouched, &before.crossing),
        (&touching_edges, &quality.crossing),
    );
    // The faces again, each vertex's distance as last measured where it stands now.
    let (again_faces, after) = pierced_again(index, &moved, (&subset, &rounds), (&quality.clearance, &again, &free));
    let mut pierced_after: Vec<u32> = after.iter().map(|&k| faces[again_faces[k as usize] as usize]).collect();
    pierced_after.sort_unstable();
    Free {
        tested: tested.len(),
        hits: hits.len(),
        crossing_before,
        responses,
        edge_rounds,
        positions: moved,
        quality,
        crossing_after,
        pierced_before,
        face_rounds: rounds.found,
        pierced_after,
    }
}

/// The collision of a refinement from its kept and free parts.
pub(super) fn assemble(kept: Kept, free: Free) -> M1Collision {
    let Free {
        tested,
        hits,
        mut crossing_before,
        responses,
        edge_rounds,
        positions,
        mut quality,
        mut crossing_after,
        pierced_before,
        face_rounds,
        mut pierced_after,
    } = free;
    crossing_before.extend(&kept.crossing);
    crossing_after.extend(&kept.crossing);
    let inside_after = with_kept(&mut quality, &kept.inside, crossing_after.len());
    pierced_after.extend(&kept.pierced);
    pierced_after.sort_unstable();
    quality.pierced_faces = pierced_after.len();
    M1Collision {
        tested,
        hits,
        crossing_before: crossing_before.len(),
        crossing_before_edges: crossing_before,
        responses,
        edge_rounds,
        positions,
        quality,
        crossing_after_edges: crossing_after,
        inside_after,
        pierced_before: pierced_before + kept.pierced.len(),
        face_rounds,
        pierced_after,
    }
}

/// The hits: each vertex of `inside` (of `positions`) with the body's nearest point within
/// `reach`, tested point-face in its partition.
fn hits_at(index: &BodyIndex, positions: &[DVec3], inside: &[u32], partition: &[usize], reach: f64) -> Vec<Hit> {
    par_map(inside.len(), |k| {
        let v = inside[k];
        let p = positions[v as usize];
        let near = index.nearest(p, reach)?;
        Some(Hit {
            vertex: v,
            partition: partition[v as usize],
            method: crate::body::DetectionMethod::PointFace,
            depth: (-near.signed(p)).max(0.0),
            foot: near.foot,
            normal: near.normal,
            triangle: Some(near.triangle),
        })
    })
    .into_iter()
    .flatten()
    .collect()
}

/// The refined mesh's faces split by what is known of them: the base's faces whose corners
/// are all pinned are pierced exactly when the base's check said so (the first list: those
/// pierced); the others (the second) are to be checked.
fn faces_to_check(refined: &RefinedInput<'_>, pinned: &[bool], m0: &M0Collided<'_>) -> (Vec<u32>, Vec<u32>) {
    let kept_faces = base_verdicts(m0);
    let mut pierced: Vec<u32> = Vec::new();
    let mut faces: Vec<u32> = Vec::new();
    for (f, tri) in refined.triangles.iter().enumerate() {
        let verdict = tri
            .iter()
            .all(|&v| pinned[v as usize])
            .then(|| kept_faces.get(&sorted(*tri)).copied())
            .flatten();
        match verdict {
            Some(true) => pierced.push(f as u32),
            Some(false) => {}
            None => faces.push(f as u32),
        }
    }
    (pierced, faces)
}

/// The checked faces (`subset`) pierced after the face rounds `rounds`, at `moved`, each
/// vertex free by its `clearance` where measured `again`, else by `free`: only the faces the first round found pierced, or with a
/// corner moved since, can be. Returns the faces looked at (indices into `subset`) and
/// those of them pierced (indices into the first list).
fn pierced_again(
    index: &BodyIndex,
    moved: &[DVec3],
    (subset, rounds): (&[[u32; 3]], &FaceRounds),
    (clearance, again, free): (&[f64], &[bool], &[f64]),
) -> (Vec<u32>, Vec<u32>) {
    let free_now: Vec<f64> = (0..moved.len())
        .map(|v| if again[v] { free_at(clearance[v]) } else { free[v] })
        .collect();
    let mut since = vec![false; moved.len()];
    for r in &rounds.lifts {
        since[r.vertex as usize] = true;
    }
    let again_faces: Vec<u32> = (0..subset.len() as u32)
        .filter(|&k| rounds.first.binary_search(&k).is_ok() || subset[k as usize].iter().any(|&v| since[v as usize]))
        .collect();
    let again_subset: Vec<[u32; 3]> = again_faces.iter().map(|&k| subset[k as usize]).collect();
    let after = pierced_faces(index, moved, &again_subset, &free_now, None);
    (again_faces, after)
}

/// The edges crossing after the response, sorted: the untouched edges (indices into
/// `edges`) the check before found crossing (`was`, indices into `edges`), and the touching
/// edges the check after found crossing (`now`, indices into `touching`).
fn crossing_after(
    (edges, untouched, was): (&[[u32; 2]], &[usize], &[u32]),
    (touching, now): (&[[u32; 2]], &[u32]),
) -> Vec<[u32; 2]> {
    let was: std::collections::BTreeSet<u32> = was.iter().copied().collect();
    let mut after: Vec<[u32; 2]> = untouched
        .iter()
        .filter(|&&e| was.contains(&(e as u32)))
        .map(|&e| edges[e])
        .collect();
    after.extend(now.iter().map(|&e| touching[e as usize]));
    after.sort_unstable();
    after
}

/// How far a vertex measured again is free of the body: its clearance's size where the
/// check measured one, else nothing.
fn free_at(clearance: f64) -> f64 {
    if clearance.is_finite() { clearance.abs() } else { 0.0 }
}

/// What the base's check already says: of the base's edges (both ends pinned) those
/// crossing, exactly when the base's check said so; the pinned vertices the base found
/// inside.
fn known_from_base(refined: &RefinedInput<'_>, pinned: &[bool], m0: &M0Collided<'_>) -> (Vec<[u32; 2]>, Vec<u32>) {
    let kept = refined
        .edges
        .iter()
        .copied()
        .filter(|&[a, b]| pinned[a as usize] && pinned[b as usize]);
    let m0_crossing: std::collections::BTreeSet<[u32; 2]> =
        m0.crossing.iter().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
    let kept_crossing: Vec<[u32; 2]> = kept.filter(|e| m0_crossing.contains(e)).collect();
    let kept_inside: Vec<u32> = m0.inside.iter().copied().filter(|&v| pinned[v as usize]).collect();
    (kept_crossing, kept_inside)
}

/// The check after the response made whole: the base's kept inside vertices counted in
/// (`crossing` is the whole count of crossing edges), its lists of what it measured emptied
/// (they index the measured subsets). Returns every vertex inside, sorted.
fn with_kept(quality: &mut Quality, kept_inside: &[u32], crossing: usize) -> Vec<u32> {
    let mut inside_after: Vec<u32> = quality.inside.clone();
    inside_after.extend(kept_inside);
    inside_after.sort_unstable();
    quality.penetrating_vertices += kept_inside.len();
    quality.crossing_edges = crossing;
    quality.inside.clear();
    quality.crossing.clear();
    inside_after
}

/// A flag per vertex of `n`, set for those of `vertices`.
fn marked(n: usize, vertices: impl Iterator<Item = u32>) -> Vec<bool> {
    let mut flags = vec![false; n];
    for v in vertices {
        flags[v as usize] = true;
    }
    flags
}

/// A face's corners in ascending order (the same face whatever its orientation).
fn sorted(mut tri: [u32; 3]) -> [u32; 3] {
    tri.sort_unstable();
    tri
}

/// The base's verdict on each of its faces (by sorted corners): pierced or not.
fn base_verdicts(m0: &M0Collided<'_>) -> std::collections::BTreeMap<[u32; 3], bool> {
    let mut verdicts: std::collections::BTreeMap<[u32; 3], bool> =
        m0.triangles.iter().map(|&t| (sorted(t), false)).collect();
    for &f in m0.pierced {
        if let Some(&t) = m0.triangles.get(f as usize) {
            verdicts.insert(sorted(t), true);
        }
    }
    verdicts
}
