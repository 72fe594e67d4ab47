//! Triangles by height: the mesh's vertical extent cut into equal bands, each listing (in
//! ascending order) every triangle whose height range meets it. A horizontal section at
//! height `y` only has to look at the triangles of `y`'s band instead of all of them.
//!
//! The band of a height is `floor((y - floor) / width)`, clamped; in floating point that
//! is a non-decreasing function of `y`, so a triangle with `min_y <= y <= max_y` is always
//! listed in `y`'s band: the lists are a superset of what any section there crosses.

use crate::mesh::TriMesh;

/// The triangles of a mesh sorted into horizontal bands (compressed rows).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HeightBands {
    /// Lowest vertex height, m.
    floor: f64,
    /// Band height, m (positive).
    width: f64,
    /// Band `b` lists `triangles[starts[b]..starts[b + 1]]`.
    starts: Vec<u32>,
    triangles: Vec<u32>,
    /// The mesh the bands were made from, in brief ([`fingerprint`]).
    made_from: u64,
}

/// A digest of a mesh's size and of 64 of its vertices spread over it: a mesh moved,
/// scaled or re-meshed after its bands were made no longer matches them.
fn fingerprint(mesh: &TriMesh) -> u64 {
    const SAMPLES: usize = 64;
    // FNV-1a over the counts and the sampled coordinates' bits.
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u64| {
        for byte in x.to_le_bytes() {
            h = (h ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    eat(mesh.positions.len() as u64);
    eat(mesh.triangles.len() as u64);
    let step = mesh.positions.len().div_ceil(SAMPLES).max(1);
    for p in mesh.positions.iter().step_by(step) {
        for c in p.to_array() {
            eat(c.to_bits());
        }
    }
    h
}

impl HeightBands {
    /// Sorts `mesh`'s triangles into bands as tall as its median triangle (so a triangle
    /// meets about two bands whatever the mesh's resolution), at most one band a triangle.
    pub fn new(mesh: &TriMesh) -> Self {
        let ranges: Vec<(f64, f64)> = (0..mesh.triangles.len())
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y))
            })
            .collect();
        let Some((lo, hi)) = mesh.bounds() else {
            return Self::default();
        };
        let span = hi.y - lo.y;
        let mut extents: Vec<f64> = ranges.iter().map(|(a, b)| b - a).collect();
        let middle = extents.len() / 2;
        let median = if extents.is_empty() {
            span
        } else {
            *extents.select_nth_unstable_by(middle, f64::total_cmp).1
        };
        let count = if span > 0.0 && median > 0.0 && span.is_finite() {
            ((span / median).ceil() as usize).clamp(1, ranges.len().max(1))
        } else {
            1
        };
        let width = if span > 0.0 && span.is_finite() {
            span / count as f64
        } else {
            1.0
        };
        let mut bands = Self {
            floor: lo.y,
            width,
            starts: vec![0; count + 1],
            triangles: Vec::new(),
            made_from: fingerprint(mesh),
        };
        let spans: Vec<(usize, usize)> = ranges.iter().map(|&(a, b)| (bands.band(a), bands.band(b))).collect();
        for &(first, last) in &spans {
            for b in first..=last {
                bands.starts[b + 1] += 1;
            }
        }
        for b in 0..count {
            bands.starts[b + 1] += bands.starts[b];
        }
        let mut next: Vec<u32> = bands.starts[..count].to_vec();
        bands.triangles = vec![0; bands.starts[count] as usize];
        for (t, &(first, last)) in spans.iter().enumerate() {
            for slot in &mut next[first..=last] {
                bands.triangles[*slot as usize] = t as u32;
                *slot += 1;
            }
        }
        bands
    }

    /// The band holding height `y` (the nearest one outside the mesh; band 0 for NaN).
    fn band(&self, y: f64) -> usize {
        let last = self.starts.len().saturating_sub(2);
        let k = ((y - self.floor) / self.width).floor();
        if k > 0.0 { (k as usize).min(last) } else { 0 }
    }

    /// Every triangle whose height range may hold `y`, in ascending order (a superset of
    /// those with `min_y <= y <= max_y`).
    pub fn at(&self, y: f64) -> &[u32] {
        if self.starts.len() < 2 {
            return &[];
        }
        let b = self.band(y);
        &self.triangles[self.starts[b] as usize..self.starts[b + 1] as usize]
    }

    /// Whether `mesh` still looks like the mesh the bands were made from (its size and 64
    /// sampled vertices, bit for bit): a mesh moved or scaled since does not.
    pub fn fit(&self, mesh: &TriMesh) -> bool {
        self.made_from == fingerprint(mesh)
    }
}
