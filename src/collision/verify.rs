//! The brute-force ground truth (\[collide\] 4.2: "the most exact test intersects every
//! primitive of both"): every garment vertex against every body triangle by the
//! generalized winding number (inside above one half; the verdict of the sum over every
//! triangle, reached through [`WindingTree`]'s bounded far-field terms where they decide
//! it), every garment edge against every body triangle, and every body edge against every
//! garment face. No partitions, no body index, no pseudo-normals: independent, and what the
//! fast tests are checked against (`--verify`, tests, the benchmark).

use glam::DVec3;

use super::detect::Detection;
use super::quality::Quality;
use crate::body::DetectionMethod;
use crate::geom::closest::closest_on_triangle;
use crate::geom::predicates::segment_crosses_triangle;
use crate::geom::winding_tree::WindingTree;
use crate::mesh::TriMesh;
use crate::par::par_map as parallel;

/// The ground truth for one garment mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct GroundTruth {
    /// Whether each vertex lies inside the body.
    pub inside: Vec<bool>,
    /// Whether each edge meets the body surface.
    pub crossing: Vec<bool>,
    /// Whether an edge of the body passes through each face (empty where the faces were
    /// not asked for).
    pub pierced: Vec<bool>,
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

    /// Number of faces pierced.
    pub fn pierced_count(&self) -> usize {
        self.pierced.iter().filter(|c| **c).count()
    }

    /// The faces of `triangles` (at `positions`) an edge of the closed `body` passes
    /// through: every body edge against every face (a box overlap test first only saves
    /// time).
    pub fn with_faces(mut self, body: &TriMesh, positions: &[DVec3], triangles: &[[u32; 3]]) -> Self {
        let mut edges: Vec<[u32; 2]> = body
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])]))
            .collect();
        edges.sort_unstable();
        edges.dedup();
        let segments: Vec<[DVec3; 2]> = edges.iter().map(|e| e.map(|v| body.positions[v as usize])).collect();
        let boxes = SortedBoxes::new(segments.iter().map(|&[p, q]| (p.min(q), p.max(q))));
        self.pierced = parallel(triangles.len(), |f| {
            let tri = triangles[f].map(|v| positions[v as usize]);
            let (lo, hi) = (tri[0].min(tri[1]).min(tri[2]), tri[0].max(tri[1]).max(tri[2]));
            boxes.overlapping(lo, hi).any(|s| {
                let [p, q] = segments[s];
                segment_crosses_triangle(p, q, tri)
            })
        });
        self
    }
}

/// The ground truth of `positions` and `edges` against the closed `body`: a vertex is
/// inside when its winding number is above one half and it stands farther from every body
/// triangle than the skin tolerance ([`super::types::SKIN`] of the body's height).
pub fn ground_truth(body: &TriMesh, positions: &[DVec3], edges: &[[u32; 2]]) -> GroundTruth {
    // The body's height as the index takes it (its extent up, along y).
    let height = body.bounds().map_or(1.0, |(lo, hi)| hi.y - lo.y);
    let skin = super::types::SKIN * height;
    let off_skin =
        |p: DVec3| (0..body.triangles.len()).all(|t| closest_on_triangle(p, body.corners(t)).0.distance(p) > skin);
    let tree = WindingTree::new(body);
    let inside = parallel(positions.len(), |v| {
        tree.is_inside(positions[v]) && off_skin(positions[v])
    });
    // Every edge against every triangle whose box meets its own (the others cannot meet it).
    let boxes = SortedBoxes::new((0..body.triangles.len()).map(|t| {
        let [a, b, c] = body.corners(t);
        (a.min(b).min(c), a.max(b).max(c))
    }));
    let crossing = parallel(edges.len(), |e| {
        let [a, b] = edges[e];
        let (a, b) = (positions[a as usize], positions[b as usize]);
        boxes
            .overlapping(a.min(b), a.max(b))
            .any(|t| segment_crosses_triangle(a, b, body.corners(t)))
    });
    GroundTruth {
        inside,
        crossing,
        pierced: Vec::new(),
    }
}

/// Boxes sorted by their least `x`, to list the boxes that meet a query box without
/// reading the others: every box whose `x` range can meet the query's lies in one run of
/// the order (its least `x` at most the query's greatest, and at least the query's least
/// less the widest box's width).
struct SortedBoxes {
    /// `(least corner, greatest corner, index)`, by least `x`.
    boxes: Vec<(DVec3, DVec3, usize)>,
    widest: f64,
}

impl SortedBoxes {
    fn new(boxes: impl Iterator<Item = (DVec3, DVec3)>) -> Self {
        let mut boxes: Vec<(DVec3, DVec3, usize)> = boxes.enumerate().map(|(i, (lo, hi))| (lo, hi, i)).collect();
        boxes.sort_by(|a, b| a.0.x.total_cmp(&b.0.x).then(a.2.cmp(&b.2)));
        let widest = boxes.iter().map(|b| b.1.x - b.0.x).fold(0.0, f64::max);
        Self { boxes, widest }
    }

    /// The indices of the boxes that meet `[lo, hi]` (closed boxes), in `x` order.
    fn overlapping(&self, lo: DVec3, hi: DVec3) -> impl Iterator<Item = usize> + '_ {
        // Twice the widest, so that no rounding of the subtraction drops a box.
        let from = self.boxes.partition_point(|b| b.0.x < lo.x - 2.0 * self.widest);
        let to = self.boxes.partition_point(|b| b.0.x <= hi.x);
        self.boxes[from..to.max(from)]
            .iter()
            .filter(move |b| b.0.cmple(hi).all() && b.1.cmpge(lo).all())
            .map(|b| b.2)
    }
}

/// Detection's misses by cause.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Misses {
    /// On the skin: nearer to it than detection's surface tolerance (neither in nor out for
    /// detection; the winding number calls them inside). The others leave them out.
    pub on_skin: usize,
    /// Tested line-line (the method's own error).
    pub line_line: usize,
    /// Skipped untested (inert or in a still patch).
    pub untested: usize,
    /// Tested point-face.
    pub point_face: usize,
}

impl Misses {
    /// Adds `other`'s counts.
    pub fn add(&mut self, other: &Misses) {
        self.on_skin += other.on_skin;
        self.line_line += other.line_line;
        self.untested += other.untested;
        self.point_face += other.point_face;
    }
}

impl std::fmt::Display for Misses {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} on the skin; of the others line-line {}, skipped {}, point-face {}",
            self.on_skin, self.line_line, self.untested, self.point_face
        )
    }
}

/// Detection and quality checked against the ground truth.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct VerifyReport {
    /// Vertices inside before response (truth).
    pub inside_before: usize,
    /// Edges crossing before response (truth).
    pub crossing_before: usize,
    /// Inside vertices detection did not report.
    pub missed: usize,
    /// The missed by cause.
    pub missed_by: Misses,
    /// Reported vertices that are not inside.
    pub false_hits: usize,
    /// Of the false hits, those tested line-line.
    pub false_line_line: usize,
    /// Vertices whose verdict (hit or not) differs from a detection that tests every vertex
    /// (no inert or patch skipping): what the skips changed (the session runner sets it;
    /// [`compare`] leaves it 0).
    pub skips_changed: usize,
    /// Vertices inside after response (truth).
    pub inside_after: usize,
    /// Edges crossing after response (truth).
    pub crossing_after: usize,
    /// Faces pierced by the body before response (truth).
    pub pierced_before: usize,
    /// Faces pierced by the body after response (truth).
    pub pierced_after: usize,
    /// The quality figures after response equal the truth's.
    pub quality_agrees: bool,
    /// The step's quality check (partial unless the full one was asked for) gave exactly
    /// what a full check of every vertex and edge gives: every figure, every inside vertex
    /// and crossing edge, every clearance (the session runner sets it; [`compare`] leaves
    /// it false).
    pub full_check_agrees: bool,
}

/// Compares detection (on the mesh of `before`) and quality (on the mesh of `after`) with
/// the ground truth of both; `on_skin(v)` says whether vertex `v` lies on the skin, within
/// detection's surface tolerance.
pub fn compare(
    before: &GroundTruth,
    detection: &Detection,
    after: &GroundTruth,
    quality: &Quality,
    on_skin: impl Fn(usize) -> bool,
) -> VerifyReport {
    let mut reported = vec![false; before.inside.len()];
    for h in &detection.hits {
        if let Some(r) = reported.get_mut(h.vertex as usize) {
            *r = true;
        }
    }
    let line = |v: usize| detection.methods.get(v).copied().flatten() == Some(DetectionMethod::LineLine);
    let mut report = VerifyReport {
        inside_before: before.inside_count(),
        crossing_before: before.crossing_count(),
        inside_after: after.inside_count(),
        crossing_after: after.crossing_count(),
        pierced_before: before.pierced_count(),
        pierced_after: after.pierced_count(),
        ..VerifyReport::default()
    };
    for (v, (&truth, &said)) in before.inside.iter().zip(&reported).enumerate() {
        if truth && !said {
            report.missed += 1;
            let by = &mut report.missed_by;
            *match (on_skin(v), detection.methods.get(v).copied().flatten()) {
                (true, _) => &mut by.on_skin,
                (false, Some(DetectionMethod::LineLine)) => &mut by.line_line,
                (false, Some(DetectionMethod::PointFace)) => &mut by.point_face,
                (false, None) => &mut by.untested,
            } += 1;
        }
        if said && !truth {
            report.false_hits += 1;
            report.false_line_line += usize::from(line(v));
        }
    }
    let inside_after: Vec<u32> = (0..after.inside.len())
        .filter(|&v| after.inside[v])
        .map(|v| v as u32)
        .collect();
    let crossing_after: Vec<u32> = (0..after.crossing.len())
        .filter(|&e| after.crossing[e])
        .map(|e| e as u32)
        .collect();
    let pierced_after: Vec<u32> = (0..after.pierced.len())
        .filter(|&f| after.pierced[f])
        .map(|f| f as u32)
        .collect();
    report.quality_agrees =
        inside_after == quality.inside && crossing_after == quality.crossing && pierced_after == quality.pierced;
    report
}

/// Vertices reported by one detection and not the other.
pub fn changed_verdicts(a: &Detection, b: &Detection) -> usize {
    let hits = |d: &Detection| {
        let mut v: Vec<u32> = d.hits.iter().map(|h| h.vertex).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let (a, b) = (hits(a), hits(b));
    let common = a.iter().filter(|v| b.binary_search(v).is_ok()).count();
    a.len() + b.len() - 2 * common
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::SortedBoxes;

    /// The boxes listed for a query are exactly those a scan of every box finds meeting it.
    #[test]
    fn sorted_boxes_list_exactly_the_boxes_a_scan_finds() {
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut random_box = |size: f64| {
            let lo = DVec3::new(next(), next(), next());
            (lo, lo + size * DVec3::new(next(), next(), next()))
        };
        let boxes: Vec<(DVec3, DVec3)> = (0..500)
            .map(|k| random_box(if k % 50 == 0 { 0.5 } else { 0.05 }))
            .collect();
        let sorted = SortedBoxes::new(boxes.iter().copied());
        for k in 0..300 {
            let (lo, hi) = random_box(if k % 3 == 0 { 0.0 } else { 0.1 });
            let mut listed: Vec<usize> = sorted.overlapping(lo, hi).collect();
            listed.sort_unstable();
            let scan: Vec<usize> = (0..boxes.len())
                .filter(|&b| boxes[b].0.cmple(hi).all() && boxes[b].1.cmpge(lo).all())
                .collect();
            assert_eq!(listed, scan, "query {lo} .. {hi}");
        }
    }
}
