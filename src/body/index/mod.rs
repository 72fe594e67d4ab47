//! The body prepared for distance, inside and ray queries, built once per body and shared
//! by the garment (curve clearance) and the collision: `f64` triangles with face, edge and
//! vertex pseudo-normals (Bærentzen and Aanæs 2005: angle-weighted at vertices, the two
//! faces' sum on edges), one tree ([`NearTree`]) for nearest points, segments and rays and
//! one per partition A-G (detection), all over the body's outer shell (the triangles of a self-crossing body
//! that lie inside another part left out, see [`super::shell`]), and the horizontal slice
//! stack the line-line test and the ring-centre response read.

use std::cell::Cell;
use std::cmp::Ordering;

use glam::DVec3;
use parry3d::bounding_volume::Aabb;
use parry3d::partitioning::{Bvh, BvhBuildStrategy, BvhWorkspace};

use super::near_tree::NearTree;
use super::shell::{Shell, find_shell};
use super::slices::{SliceOptions, SliceStack};
use super::{Body, DetectionMethod, PartitionId, ResponseRule};
use crate::geom::closest::{Feature, closest_on_triangle};
use crate::geom::predicates::{line_through_triangle, segment_crosses_triangle, side, strictly_apart};
use crate::geom::ray::ray_triangle;

use crate::mesh::topology::NO_NEIGHBOUR;

mod queries;

pub use queries::edges_through;

/// The nearest point of the body (or of a partition) to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// Body triangle.
    pub triangle: u32,
    /// Nearest surface point, m (world frame).
    pub foot: DVec3,
    /// Which feature of the triangle it lies on.
    pub feature: Feature,
    /// Distance from the query point to `foot`, m.
    pub distance: f64,
    /// Outward pseudo-normal of that feature (unit; zero on a fully degenerate feature).
    pub normal: DVec3,
    /// Where the foot lies inside a face: whether the query point lies behind the face's
    /// plane, decided exactly ([`crate::geom::predicates::side`]); `None` on an edge or a
    /// corner (and next to a self-crossing), where the pseudo-normal decides.
    pub behind: Option<bool>,
}

/// The least distance from the skin, as a fraction of the body's height, at which the way
/// from a point's foot to the point is a direction: nearer, the difference of the two rounded
/// points is mostly rounding (a point on the skin, 1e-18 m off its foot, would get an
/// arbitrary axis), and the feature's pseudo-normal gives the way instead.
pub const RESOLVED: f64 = 1e-9;

impl Nearest {
    /// The unit way out of the body from `p` (away from it, for a point outside): from the
    /// foot through `p` (reversed for a point inside) where `p` stands more than `resolved`
    /// (m, [`BodyIndex::resolved`]) from the skin, else the feature's outward pseudo-normal.
    pub fn way_out(&self, p: DVec3, resolved: f64) -> DVec3 {
        if self.distance > resolved {
            (p - self.foot) / self.distance * self.signed(p).signum()
        } else {
            self.normal
        }
    }

    /// Signed distance of `p` (m): negative inside the body (the point lies behind the
    /// feature's angle-weighted pseudo-normal, Baerentzen and Aanaes 2005), zero on the surface.
    pub fn signed(&self, p: DVec3) -> f64 {
        let behind = self.behind.unwrap_or_else(|| (p - self.foot).dot(self.normal) < 0.0);
        if behind { -self.distance } else { self.distance }
    }
}

/// One partition's triangles and their BVH.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub struct PartitionIndex {
    /// Which partition.
    pub id: PartitionId,
    /// Lower bound, m.
    pub lower_y: f64,
    /// Upper bound, m.
    pub upper_y: f64,
    /// Its detection method.
    pub method: DetectionMethod,
    /// Its response rule.
    pub response: ResponseRule,
    /// Body triangles (with the margin band), ascending.
    pub triangles: Vec<u32>,
    /// Their nearest-point tree.
    tree: NearTree,
}

/// The body prepared for collision.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct BodyIndex {
    /// Vertex positions, m (world frame).
    pub positions: Vec<DVec3>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
    /// Unit face normals (zero for zero-area triangles).
    pub face_normals: Vec<DVec3>,
    /// Per triangle and local edge `k` (corner `k` to `k + 1`): the edge pseudo-normal.
    pub edge_normals: Vec<[DVec3; 3]>,
    /// Angle-weighted vertex pseudo-normals.
    pub vertex_normals: Vec<DVec3>,
    /// Partitions, bottom to top.
    pub partitions: Vec<PartitionIndex>,
    /// Horizontal sections for the line-line test and ring centres.
    pub slices: SliceStack,
    /// Body height, m (scale of every tolerance).
    pub height: f64,
    /// Which triangles lie inside another part of the body (see [`super::shell`]); the
    /// nearest-point and ray queries see only the others.
    pub shell: Shell,
    /// The shell's triangles (every triangle not buried), ascending.
    leaves: Vec<u32>,
    /// Per triangle: it shares a vertex with a triangle where the surface crosses itself, so
    /// its pseudo-normals may point the wrong way; the sign of a point nearest to it is
    /// counted along rays instead.
    tangled: Vec<bool>,
    /// Every triangle's tree (buried ones too), for those counts; only on a body with
    /// buried triangles (else the shell's tree holds every triangle).
    all: Option<NearTree>,
    /// How far the boxes of the trees reach past their triangles, m (room for `f32`
    /// rounding).
    pub(super) slack: f64,
    /// The shell's tree: nearest points, segments and rays.
    pub(super) near: NearTree,
    /// [`Self::fingerprint`], hashed the first time it is asked for (every M1 collision
    /// asks).
    #[serde(skip)]
    fingerprint: std::sync::OnceLock<u64>,
}

thread_local! {
    /// The last triangle a nearest-point search on this thread found: (the index's key,
    /// triangle). Only a hint: see [`BodyIndex::nearest`].
    static LAST_FOUND: Cell<(usize, u32)> = const { Cell::new((0, u32::MAX)) };
    /// Where the winner of the last upward search on this thread lay: (the tree's key,
    /// its leaf). Only a start: see [`BodyIndex::nearest_in_partition`].
    static LAST_LEAF: Cell<(usize, usize)> = const { Cell::new((0, usize::MAX)) };
}

/// Directions of the rays that count windings (fixed, off every axis and diagonal).
const WINDING_RAYS: [DVec3; 3] = [
    DVec3::new(0.267_261_2, 0.534_522_5, 0.801_783_7),
    DVec3::new(-0.801_783_7, 0.267_261_2, -0.534_522_5),
    DVec3::new(0.534_522_5, -0.801_783_7, -0.267_261_2),
];

impl std::fmt::Debug for BodyIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BodyIndex")
            .field("triangles", &self.triangles.len())
            .field("partitions", &self.partitions.len())
            .field("slices", &self.slices.len())
            .finish()
    }
}

/// A squared distance beyond which the square root, rounded, lies strictly above `d` (m):
/// `d²` widened by a relative 1e-12, thousands of times the rounding of the product and
/// the square root.
fn beyond(d: f64) -> f64 {
    d * d * (1.0 + 1e-12)
}

fn aabb_of(corners: [DVec3; 3], slack: f64) -> Aabb {
    let lo = corners[0].min(corners[1]).min(corners[2]) - DVec3::splat(slack);
    let hi = corners[0].max(corners[1]).max(corners[2]) + DVec3::splat(slack);
    Aabb::new(lo.as_vec3(), hi.as_vec3())
}

fn angle(a: DVec3, b: DVec3) -> f64 {
    let (la, lb) = (a.length(), b.length());
    if la == 0.0 || lb == 0.0 {
        return 0.0;
    }
    (a.dot(b) / (la * lb)).clamp(-1.0, 1.0).acos()
}

impl BodyIndex {
    /// A hash of the body the index answers for: xxh64 of its positions' bits, its
    /// triangles and its height, little-endian, streamed through a small buffer (what a
    /// result kept from an earlier step checks it was found against); hashed once.
    pub fn fingerprint(&self) -> u64 {
        *self.fingerprint.get_or_init(|| self.hash_body())
    }

    /// The hash [`Self::fingerprint`] keeps.
    fn hash_body(&self) -> u64 {
        const BLOCK: usize = 1 << 15;
        let mut hasher = xxhash_rust::xxh64::Xxh64::new(0);
        let mut bytes: Vec<u8> = Vec::with_capacity(BLOCK + 8);
        let mut put = |word: &[u8]| {
            bytes.extend_from_slice(word);
            if bytes.len() >= BLOCK {
                hasher.update(&bytes);
                bytes.clear();
            }
        };
        for p in &self.positions {
            p.to_array().iter().for_each(|x| put(&x.to_bits().to_le_bytes()));
        }
        for t in &self.triangles {
            t.iter().for_each(|v| put(&v.to_le_bytes()));
        }
        put(&self.height.to_bits().to_le_bytes());
        hasher.update(&bytes);
        hasher.digest()
    }

    /// Prepares `body` (its mesh, adjacency, partitions and landmarks).
    pub fn new(body: &Body, slices: &SliceOptions) -> Self {
        let parts: Vec<PartitionIndex> = body
            .partitions
            .iter()
            .map(|p| PartitionIndex {
                id: p.id,
                lower_y: p.lower_y,
                upper_y: p.upper_y,
                method: p.method,
                response: p.response,
                triangles: p.triangles.clone(),
                tree: NearTree::default(),
            })
            .collect();
        Self::build(
            &body.mesh.mesh,
            &body.mesh.adjacency.neighbours,
            body.mesh.height(),
            parts,
            SliceStack::new(body, slices),
        )
    }

    /// Prepares a closed mesh with no landmarks: one partition over all of it, tested
    /// point-face and responded along vertex normals; no slices. For tests and for
    /// bodies that are not human.
    pub fn from_mesh(mesh: &crate::mesh::TriMesh) -> Result<Self, crate::mesh::topology::NonManifoldEdge> {
        let adjacency = crate::mesh::Adjacency::try_new(mesh)?;
        let height = mesh.bounds().map_or(1.0, |(lo, hi)| (hi - lo).max_element());
        let part = PartitionIndex {
            id: PartitionId::A,
            lower_y: f64::NEG_INFINITY,
            upper_y: f64::INFINITY,
            method: DetectionMethod::PointFace,
            response: ResponseRule::VertexNormal,
            triangles: (0..mesh.triangles.len() as u32).collect(),
            tree: NearTree::default(),
        };
        Ok(Self::build(
            mesh,
            &adjacency.neighbours,
            height,
            vec![part],
            SliceStack::default(),
        ))
    }

    fn build(
        mesh: &crate::mesh::TriMesh,
        neighbours: &[[u32; 3]],
        height: f64,
        mut partitions: Vec<PartitionIndex>,
        slices: SliceStack,
    ) -> Self {
        let height = height.max(f64::MIN_POSITIVE);
        let positions = mesh.positions.clone();
        let triangles = mesh.triangles.clone();
        let face_normals: Vec<DVec3> = (0..triangles.len())
            .map(|t| mesh.scaled_normal(t).normalize_or_zero())
            .collect();
        let edge_normals: Vec<[DVec3; 3]> = (0..triangles.len())
            .map(|t| {
                std::array::from_fn(|k| {
                    let other = neighbours.get(t).map_or(NO_NEIGHBOUR, |n| n[k]);
                    let across = if other == NO_NEIGHBOUR {
                        DVec3::ZERO
                    } else {
                        face_normals[other as usize]
                    };
                    (face_normals[t] + across).normalize_or_zero()
                })
            })
            .collect();
        let mut vertex_normals = vec![DVec3::ZERO; positions.len()];
        for (t, tri) in triangles.iter().enumerate() {
            let c = tri.map(|i| positions[i as usize]);
            for k in 0..3 {
                let (p, q, r) = (c[k], c[(k + 1) % 3], c[(k + 2) % 3]);
                vertex_normals[tri[k] as usize] += face_normals[t] * angle(q - p, r - p);
            }
        }
        for n in &mut vertex_normals {
            *n = n.normalize_or_zero();
        }
        // f32 boxes widened so that rounding never drops a triangle.
        let slack = 1e-6 * height;
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| aabb_of(t.map(|i| positions[i as usize]), slack))
            .collect();
        let bounds = |t: u32| (boxes[t as usize].mins, boxes[t as usize].maxs);
        let leaves: Vec<u32> = (0..boxes.len() as u32).collect();
        let mut index = Self {
            positions,
            triangles,
            face_normals,
            edge_normals,
            vertex_normals,
            partitions: Vec::new(),
            slices,
            height,
            shell: Shell::default(),
            near: NearTree::default(),
            tangled: Vec::new(),
            all: None,
            slack: 1e-5 * height,
            leaves,
            fingerprint: std::sync::OnceLock::new(),
        };
        index.near = NearTree::new(&index.leaves, |t| index.corners(t), bounds);
        // The box-overlapping triangle pairs, from parry3d's self-test of a tree over every
        // triangle (kept only for it).
        let mut overlapping = Vec::new();
        Bvh::from_leaves(BvhBuildStrategy::Binned, &boxes).traverse_bvtt_single_tree::<false>(
            &mut BvhWorkspace::default(),
            &mut |a, b| {
                overlapping.push((a, b));
            },
        );
        index.shell = find_shell(mesh, neighbours, height, &overlapping, |p| index.winding(p));
        if index.shell.crossing > 0 {
            let mut near_crossing = vec![false; index.positions.len()];
            for (t, tri) in index.triangles.iter().enumerate() {
                if index.shell.crossing_at[t] {
                    for &v in tri {
                        near_crossing[v as usize] = true;
                    }
                }
            }
            index.tangled = index
                .triangles
                .iter()
                .map(|tri| tri.iter().any(|&v| near_crossing[v as usize]))
                .collect();
            // The shell's own tree, unless nothing is buried (crossing pieces that bury no
            // triangle): then it would be the whole tree again, leaf for leaf.
            if index.shell.buried.contains(&true) {
                index.leaves.retain(|&t| !index.shell.buried[t as usize]);
                let shell = NearTree::new(&index.leaves, |t| index.corners(t), bounds);
                index.all = Some(std::mem::replace(&mut index.near, shell));
                for p in &mut partitions {
                    p.triangles.retain(|&t| !index.shell.buried[t as usize]);
                }
            }
        }
        // Each partition's tree (on the worker threads: the trees do not depend on how many
        // there are).
        let corners = |t: u32| index.corners(t);
        let trees = crate::par::par_map_from(partitions.len(), 2, |i| {
            NearTree::new(&partitions[i].triangles, corners, bounds)
        });
        for (p, tree) in partitions.iter_mut().zip(trees) {
            p.tree = tree;
        }
        index.partitions = partitions;
        index
    }

    /// Finishes an index read back from the cache file, which stores its trees without their
    /// triangles' corners: makes those again; `false` if the index does not hold together
    /// (a triangle's corner, or a tree's triangle, out of range).
    pub(super) fn restore(&mut self) -> bool {
        let (count, vertices) = (self.triangles.len(), self.positions.len());
        if self.triangles.iter().flatten().any(|&i| i as usize >= vertices) {
            return false;
        }
        let (triangles, positions) = (&self.triangles, &self.positions);
        let corners = |t: u32| triangles[t as usize].map(|i| positions[i as usize]);
        // The shell's and the partitions' trees are searched upwards (`nearest_next`,
        // `nearest_in_partition`); the tree of every triangle only counts windings.
        self.near.restore(count, corners, true)
            && self.all.as_mut().is_none_or(|all| all.restore(count, corners, false))
            && self.partitions.iter_mut().all(|p| p.tree.restore(count, corners, true))
    }
}
