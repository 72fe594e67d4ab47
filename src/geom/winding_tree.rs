//! The brute-force inside test's verdict, decided without summing every triangle: a tree
//! of triangle clusters whose far ones enter the winding number as one dipole term with a
//! proven error bound. Where the bound cannot decide (a point whose winding number lies
//! within the bound of one half), the sum over every triangle
//! ([`super::inside::winding_number`]) decides, so the verdict is always the brute force's.
//!
//! For a cluster `C` of triangles inside a ball of centre `c` and radius `r`, seen from `p`
//! at `d = |c - p| > r`: each triangle's solid angle is `∫ n · f(x) dA` with
//! `f(x) = (x - p) / |x - p|³`, and `|f(x) - f(c)| <= 2 r / (d - r)³` (the Jacobian of
//! `y / |y|³` has norm `2 / |y|³`, and `|y| >= d - r` on the ball). So the cluster's solid
//! angle is `D · f(c)`, with `D = Σ area · normal`, within `2 A r / (d - r)³` (`A` its area).
//! A cluster is taken whole when that bound is below [`WindingTree::TOLERANCE`]; the bounds
//! taken add up to the error of the point's winding number. Independent of the body index
//! and its trees: a second way to the same truth.

use glam::DVec3;

use super::inside::{solid_angle, winding_number};
use crate::mesh::TriMesh;

/// One cluster: its ball, area, dipole and triangles (a range of `order`), or two children.
#[derive(Clone, Debug)]
struct Node {
    center: DVec3,
    radius: f64,
    area: f64,
    /// `Σ area · unit normal` of its triangles (outward).
    dipole: DVec3,
    /// Its triangles, `order[start..end]`.
    start: u32,
    end: u32,
    /// Its children (indices into the nodes), none for a leaf.
    children: Option<[u32; 2]>,
}

/// The winding-number tree of a closed, outward-oriented mesh.
#[derive(Clone, Debug)]
pub struct WindingTree<'a> {
    mesh: &'a TriMesh,
    nodes: Vec<Node>,
    order: Vec<u32>,
}

const LEAF: usize = 8;
const FOUR_PI: f64 = 4.0 * std::f64::consts::PI;

impl<'a> WindingTree<'a> {
    /// The error a cluster taken whole may add to a solid angle, steradians.
    pub const TOLERANCE: f64 = 1e-3;

    /// Builds the tree over every triangle of `mesh` (median splits along the longest side of
    /// the centroids' box).
    pub fn new(mesh: &'a TriMesh) -> Self {
        let centroids: Vec<DVec3> = (0..mesh.triangles.len())
            .map(|t| mesh.corners(t).iter().sum::<DVec3>() / 3.0)
            .collect();
        let mut tree = Self {
            mesh,
            nodes: Vec::new(),
            order: (0..mesh.triangles.len() as u32).collect(),
        };
        if !mesh.triangles.is_empty() {
            tree.build(0, mesh.triangles.len(), &centroids);
        }
        tree
    }

    fn build(&mut self, start: usize, end: usize, centroids: &[DVec3]) -> u32 {
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        let (mut area, mut dipole) = (0.0, DVec3::ZERO);
        for &t in &self.order[start..end] {
            let [a, b, c] = self.mesh.corners(t as usize);
            lo = lo.min(a).min(b).min(c);
            hi = hi.max(a).max(b).max(c);
            let n = 0.5 * (b - a).cross(c - a);
            area += n.length();
            dipole += n;
        }
        let center = 0.5 * (lo + hi);
        let radius = self.order[start..end]
            .iter()
            .flat_map(|&t| self.mesh.corners(t as usize))
            .map(|x| x.distance(center))
            .fold(0.0, f64::max);
        let at = self.nodes.len() as u32;
        self.nodes.push(Node {
            center,
            radius,
            area,
            dipole,
            start: start as u32,
            end: end as u32,
            children: None,
        });
        if end - start > LEAF {
            let (clo, chi) = self.order[start..end]
                .iter()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &t| {
                    (l.min(centroids[t as usize]), h.max(centroids[t as usize]))
                });
            let axis = (chi - clo).max_position();
            let mid = (start + end) / 2;
            self.order[start..end].select_nth_unstable_by(mid - start, |&x, &y| {
                centroids[x as usize][axis].total_cmp(&centroids[y as usize][axis])
            });
            let left = self.build(start, mid, centroids);
            let right = self.build(mid, end, centroids);
            self.nodes[at as usize].children = Some([left, right]);
        }
        at
    }

    /// The winding number at `p` (over `4 pi`) with a bound on its error.
    pub fn winding_with_bound(&self, p: DVec3) -> (f64, f64) {
        let (mut sum, mut bound) = (0.0, 0.0);
        let mut stack = if self.nodes.is_empty() { Vec::new() } else { vec![0u32] };
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k as usize];
            let y = node.center - p;
            let d = y.length();
            if d > node.radius {
                let e = 2.0 * node.area * node.radius / (d - node.radius).powi(3);
                if e <= Self::TOLERANCE {
                    sum += node.dipole.dot(y) / (d * d * d) / FOUR_PI;
                    bound += e / FOUR_PI;
                    continue;
                }
            }
            match node.children {
                Some(children) => stack.extend(children),
                None => {
                    for &t in &self.order[node.start as usize..node.end as usize] {
                        let [a, b, c] = self.mesh.corners(t as usize);
                        sum += solid_angle(p, a, b, c);
                    }
                }
            }
        }
        (sum, bound)
    }

    /// Whether `p` is inside: the winding number of every triangle summed above one half,
    /// the verdict of [`super::inside::is_inside`], decided by the tree where its bound
    /// allows and by the full sum elsewhere.
    pub fn is_inside(&self, p: DVec3) -> bool {
        let (w, bound) = self.winding_with_bound(p);
        // The margin also covers the rounding of both sums (far below 1e-9 on any mesh
        // drape reads).
        let margin = bound + 1e-9;
        if w - 0.5 > margin {
            true
        } else if 0.5 - w > margin {
            false
        } else {
            winding_number(self.mesh, p) > 0.5
        }
    }
}
