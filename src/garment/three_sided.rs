//! Three-sided patches in M0 (\[frame\] section 4): a [`PatchGrid`] over three sampled sides,
//! its points on a triangular grid whose sides are the samples themselves (so that it meets
//! its neighbours sample for sample), and the interior points with their grid neighbours
//! that clearing and relaxation walk, for both kinds of patch.

use glam::DVec3;

use super::m0::{PatchError, PatchGrid, Samples};
use crate::geom::TrianglePatch;

impl PatchGrid {
    /// The three-sided patch over three sampled boundaries, corner to corner (`c0` from `V0`
    /// to `V1`, `c1` from `V1` to `V2`, `c2` from `V2` to `V0`), each with `n + 1` samples
    /// (\[frame\] section 4; Nielson's side-vertex blend, [`TrianglePatch`]). Corners must meet
    /// within `tolerance`. Boundary grid points are the samples themselves, so that it meets
    /// its neighbours sample for sample.
    pub fn triangle(name: &str, [c0, c1, c2]: [&[DVec3]; 3], tolerance: f64) -> Result<Self, PatchError> {
        let n = c0.len().saturating_sub(1);
        if n == 0 || c1.len() != n + 1 || c2.len() != n + 1 {
            return Err(PatchError::Counts {
                patch: name.to_string(),
                counts: [c0.len(), c1.len(), c2.len(), 0],
            });
        }
        let patch = TrianglePatch::try_new([Samples(c0), Samples(c1), Samples(c2)], tolerance)
            .map_err(|e| PatchError::Corners(name.to_string(), e))?;
        let mut points = patch.grid(n);
        let mut start = 0;
        for r in 0..=n {
            let last = start + n - r;
            if r == 0 {
                points[start..=last].copy_from_slice(c0);
            }
            // Side c1 runs up the rows' last points, c2 down their first.
            points[last] = c1[r];
            points[start] = c2[n - r];
            start = last + 1;
        }
        Ok(Self {
            name: name.to_string(),
            nu: n,
            nv: n,
            points,
            curves: Vec::new(),
            triangular: true,
        })
    }

    /// Its three sides as given to [`Self::triangle`] (none for a four-sided patch).
    fn triangle_sides(&self) -> Option<[Vec<DVec3>; 3]> {
        if !self.triangular {
            return None;
        }
        let n = self.nu;
        let starts: Vec<usize> = (0..=n)
            .scan(0, |s, r| {
                let at = *s;
                *s += n - r + 1;
                Some(at)
            })
            .collect();
        let c0 = self.points[..=n].to_vec();
        let c1 = (0..=n).map(|r| self.points[starts[r] + n - r]).collect();
        let c2 = (0..=n).map(|r| self.points[starts[n - r]]).collect();
        Some([c0, c1, c2])
    }

    /// Whether it is the three-sided patch over `sides` (as given to [`Self::triangle`]).
    pub fn triangle_sides_are(&self, sides: [&[DVec3]; 3]) -> bool {
        self.triangle_sides()
            .is_some_and(|own| own.iter().zip(sides).all(|(a, b)| a.as_slice() == b))
    }

    /// The indices of its interior points (those on no side), each with its neighbours
    /// on the grid ([`Interior::around`]): left, right, down and up first (they give the
    /// tangent plane), then any others (a three-sided grid has two more, along its
    /// diagonals).
    pub fn interior(&self) -> Vec<Interior> {
        let (nu, nv) = (self.nu, self.nv);
        let mut out = Vec::new();
        if !self.triangular {
            let at = |i: usize, j: usize| j * (nu + 1) + i;
            for j in 1..nv {
                for i in 1..nu {
                    let around = [at(i - 1, j), at(i + 1, j), at(i, j - 1), at(i, j + 1), 0, 0];
                    out.push(Interior::new(at(i, j), around, 4));
                }
            }
            return out;
        }
        let n = nu;
        let starts: Vec<usize> = (0..=n)
            .scan(0, |s, r| {
                let at = *s;
                *s += n - r + 1;
                Some(at)
            })
            .collect();
        let at = |i: usize, r: usize| starts[r] + i;
        for r in 1..n {
            for i in 1..n - r {
                let around = [
                    at(i - 1, r),
                    at(i + 1, r),
                    at(i, r - 1),
                    at(i, r + 1),
                    at(i + 1, r - 1),
                    at(i - 1, r + 1),
                ];
                out.push(Interior::new(at(i, r), around, 6));
            }
        }
        out
    }
}

/// An interior point of a patch grid (see [`PatchGrid::interior`]) and its neighbours on
/// the grid, held in place (a grid has many: no allocation each).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Interior {
    /// The point's index.
    pub index: usize,
    around: [usize; 6],
    count: u8,
}

impl Interior {
    fn new(index: usize, around: [usize; 6], count: u8) -> Self {
        Self { index, around, count }
    }

    /// Its neighbours: left, right, down and up, then (on a three-sided grid) the two
    /// along its diagonals.
    pub fn around(&self) -> &[usize] {
        &self.around[..usize::from(self.count)]
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::PatchGrid;

    /// A grid whose points stand at their lattice coordinates `(i, row)`.
    fn lattice(nu: usize, nv: usize, triangular: bool) -> PatchGrid {
        let points = (0..=nv)
            .flat_map(|r| (0..=if triangular { nu - r } else { nu }).map(move |i| DVec3::new(i as f64, r as f64, 0.0)))
            .collect();
        PatchGrid {
            name: "lattice".into(),
            nu,
            nv,
            points,
            curves: Vec::new(),
            triangular,
        }
    }

    /// The interior points and their neighbours, against a search of the points by where
    /// they stand: every point on no side, each with the points one lattice step away in
    /// the order left, right, down, up (then, on a three-sided grid, down-right and
    /// up-left).
    #[test]
    fn the_interior_points_are_those_on_no_side_with_their_lattice_neighbours() {
        for (nu, nv, triangular) in [(5, 3, false), (1, 4, false), (6, 6, true), (2, 2, true)] {
            let grid = lattice(nu, nv, triangular);
            let find = |i: i64, r: i64| {
                grid.points
                    .iter()
                    .position(|p| *p == DVec3::new(i as f64, r as f64, 0.0))
            };
            let on_side = |i: usize, r: usize| {
                let last = if triangular { nu - r } else { nu };
                i == 0 || r == 0 || i == last || (!triangular && r == nv)
            };
            let expected: Vec<(usize, Vec<usize>)> = (grid.points.iter().enumerate())
                .filter(|(_, p)| !on_side(p.x as usize, p.y as usize))
                .map(|(k, p)| {
                    let (i, r) = (p.x as i64, p.y as i64);
                    let mut steps = vec![(-1, 0), (1, 0), (0, -1), (0, 1)];
                    if triangular {
                        steps.extend([(1, -1), (-1, 1)]);
                    }
                    let around = steps
                        .iter()
                        .map(|(di, dr)| find(i + di, r + dr).expect("a neighbour"))
                        .collect();
                    (k, around)
                })
                .collect();
            let got: Vec<(usize, Vec<usize>)> = (grid.interior().iter())
                .map(|point| (point.index, point.around().to_vec()))
                .collect();
            assert_eq!(got, expected, "{nu} x {nv}, three-sided: {triangular}");
        }
    }
}
