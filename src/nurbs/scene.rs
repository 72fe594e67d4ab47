//! NURBS parts in a scene: each part subdivided to a level with its hull hierarchy, collided
//! with the other parts (the paper's test with the true distance refined in the candidate
//! leaf pairs) and with the body, whose triangles get a hull hierarchy of their own so that
//! the same simultaneous descent discards far pairs early. Nothing here runs for a scene
//! without NURBS parts.

use glam::DVec3;

use super::distance::{nearest_among, pairs_within};
use super::hull::Kdop;
use super::surface::NurbsSurface;
use super::tree::{HullTree, PairVisitor, PatchTree, descend};
use crate::geom::closest::closest_on_triangle;

/// How parts are collided.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NurbsOptions {
    /// Subdivision level (default 4, what `drape nurbs-experiment` recommends for 0.5 mm on
    /// the shipped pair).
    pub level: u8,
    /// Collision threshold, m (default 0.5 mm): parts nearer than this collide.
    pub threshold_m: f64,
}

impl Default for NurbsOptions {
    fn default() -> Self {
        Self {
            level: 4,
            threshold_m: 0.5e-3,
        }
    }
}

/// A named part, subdivided.
#[derive(Clone, Debug)]
pub struct NurbsPart {
    /// Its name in the session.
    pub name: String,
    /// The surface where it stands now.
    pub surface: NurbsSurface,
    /// Its subdivision and hulls.
    pub tree: PatchTree,
}

impl NurbsPart {
    /// `surface` named `name`, subdivided to `level`.
    pub fn new(name: &str, surface: NurbsSurface, level: u8) -> Self {
        let tree = PatchTree::build(&surface, level);
        Self {
            name: name.to_string(),
            surface,
            tree,
        }
    }

    /// The part moved by `by` and turned by `turn_deg` about the vertical through the
    /// centre of its hull.
    pub fn moved(&self, by: DVec3, turn_deg: f64, level: u8) -> Self {
        let hull = self.tree.tree.nodes.first().map(|n| n.hull).unwrap_or(Kdop::EMPTY);
        let centre = DVec3::new(
            0.5 * (hull.min[0] + hull.max[0]),
            0.5 * (hull.min[1] + hull.max[1]),
            0.5 * (hull.min[2] + hull.max[2]),
        );
        let m = glam::DMat3::from_rotation_y(turn_deg.to_radians());
        let surface = self.surface.mapped(m, centre + by - m * centre);
        Self::new(&self.name, surface, level)
    }
}

/// The body's triangles with a hull hierarchy (one triangle per leaf).
#[derive(Clone, Debug)]
pub struct BodyHulls {
    /// The hierarchy.
    pub tree: HullTree,
    /// The triangles' corners.
    pub triangles: Vec<[DVec3; 3]>,
}

impl BodyHulls {
    /// The hierarchy over `triangles` of `positions`.
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> Self {
        let triangles: Vec<[DVec3; 3]> = triangles.iter().map(|t| t.map(|i| positions[i as usize])).collect();
        let hulls: Vec<Kdop> = triangles.iter().map(|t| Kdop::from_points(t.iter().copied())).collect();
        Self {
            tree: HullTree::over_items(&hulls),
            triangles,
        }
    }
}

/// What a part comes nearest to.
#[derive(Clone, Debug, PartialEq)]
pub struct Contact {
    /// The part.
    pub part: String,
    /// The other part's name, or `body`.
    pub other: String,
    /// Least distance found among the leaf pairs within the threshold, m: the true surface
    /// distance between parts; for the body, from the part's control points to the body's
    /// triangles (within the part's control-point coverage of the truth).
    pub distance_m: f64,
    /// The nearest points (on the part, on the other).
    pub points: [DVec3; 2],
    /// Leaf pairs within the threshold.
    pub candidates: usize,
    /// Points of the part (leaf corners, which lie on the surface) inside the body.
    pub inside: usize,
    /// Whether they collide: nearer than the threshold, or a part point inside the body.
    pub colliding: bool,
}

/// `a` against `b`: the leaf pairs within `threshold`, refined; `None` when no leaf pairs
/// come within it (the parts are farther apart than the threshold).
pub fn collide_parts(a: &NurbsPart, b: &NurbsPart, threshold: f64) -> Option<Contact> {
    let (pairs, _) = pairs_within(&a.tree, &b.tree, threshold);
    let nearest = nearest_among(&a.tree, &b.tree, &pairs)?;
    let (distance_m, points) = (nearest.distance, nearest.points);
    Some(Contact {
        part: a.name.clone(),
        other: b.name.clone(),
        distance_m,
        points,
        candidates: pairs.len(),
        inside: 0,
        colliding: distance_m < threshold,
    })
}

struct NearBody<'a> {
    part: &'a PatchTree,
    body: &'a BodyHulls,
    threshold: f64,
    best: Option<(f64, [DVec3; 2])>,
    candidates: usize,
}

impl PairVisitor for NearBody<'_> {
    fn bound(&self) -> f64 {
        self.threshold
    }

    fn leaves(&mut self, i: u32, t: u32, _gap: f64) {
        self.candidates += 1;
        let tri = self.body.triangles[t as usize];
        for p in &self.part.patches[i as usize].points {
            let (q, _) = closest_on_triangle(*p, tri);
            let d = p.distance(q);
            if self.best.is_none_or(|(b, _)| d < b) {
                self.best = Some((d, [*p, q]));
            }
        }
    }
}

/// `part` against the body: the leaf-triangle pairs within `threshold` (control points to
/// triangles), and the leaf corners `inside` says are in the body.
pub fn collide_body(
    part: &NurbsPart,
    body: &BodyHulls,
    threshold: f64,
    inside: impl Fn(DVec3) -> bool,
) -> Option<Contact> {
    let mut v = NearBody {
        part: &part.tree,
        body,
        threshold,
        best: None,
        candidates: 0,
    };
    descend(&part.tree.tree, &body.tree, &mut v);
    let mut corners: Vec<DVec3> = part
        .tree
        .patches
        .iter()
        .flat_map(|p| {
            let [nu, nv] = p.surface.count();
            [
                p.points[0],
                p.points[nv - 1],
                p.points[(nu - 1) * nv],
                p.points[nu * nv - 1],
            ]
        })
        .collect();
    corners.sort_by(|a, b| {
        a.to_array()
            .partial_cmp(&b.to_array())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    corners.dedup();
    let inside_count = corners.iter().filter(|p| inside(**p)).count();
    if v.best.is_none() && inside_count == 0 {
        return None;
    }
    let (distance_m, points) = v.best.unwrap_or((f64::INFINITY, [DVec3::ZERO; 2]));
    Some(Contact {
        part: part.name.clone(),
        other: "body".to_string(),
        distance_m,
        points,
        candidates: v.candidates,
        inside: inside_count,
        colliding: distance_m < threshold || inside_count > 0,
    })
}
