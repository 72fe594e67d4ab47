//! A symmetric positive definite sparse system with some unknowns pinned: assembled from
//! triplets, the pinned unknowns moved to the right-hand side, the free block ordered by
//! reverse Cuthill-McKee (a narrow band, so that the Cholesky factor stays sparse) and
//! factored once (`nalgebra-sparse`), then solved for as many right-hand sides as needed.

use nalgebra::DVector;
use nalgebra_sparse::factorization::CscCholesky;
use nalgebra_sparse::{CooMatrix, CscMatrix};

use super::types::FlattenError;

/// A factored system `K x = b` over the free unknowns, `K` the free block of a symmetric
/// matrix; the pinned unknowns' columns kept to move their values to the right-hand side.
pub(crate) struct PinnedSystem {
    /// Free unknown of each unknown (`None`: pinned).
    free: Vec<Option<usize>>,
    /// The Cholesky factor of the free block, in the band order.
    factor: CscCholesky<f64>,
    /// Band position of each free unknown.
    position: Vec<usize>,
    /// Coupling of free unknowns to pinned ones: `(free, pinned, value)`.
    coupling: Vec<(usize, usize, f64)>,
}

impl PinnedSystem {
    /// Factors the `n x n` matrix given by `triplets` (summed where repeated; symmetric, both
    /// halves given) with the unknowns in `pinned` held.
    pub(crate) fn factor(n: usize, triplets: &[(usize, usize, f64)], pinned: &[usize]) -> Result<Self, FlattenError> {
        let mut free = vec![Some(0); n];
        for &p in pinned {
            free[p] = None;
        }
        let mut count = 0;
        for f in free.iter_mut().filter(|f| f.is_some()) {
            *f = Some(count);
            count += 1;
        }
        // The free block's graph, for the band order.
        let mut neighbours = vec![Vec::new(); count];
        let mut coupling = Vec::new();
        let mut block = Vec::with_capacity(triplets.len());
        for &(i, j, v) in triplets {
            match (free[i], free[j]) {
                (Some(a), Some(b)) => {
                    if a != b {
                        neighbours[a].push(b);
                    }
                    block.push((a, b, v));
                }
                (Some(a), None) => coupling.push((a, j, v)),
                _ => {}
            }
        }
        let order = reverse_cuthill_mckee(&mut neighbours);
        let mut position = vec![0; count];
        for (k, &f) in order.iter().enumerate() {
            position[f] = k;
        }
        let mut coo = CooMatrix::new(count, count);
        for (a, b, v) in block {
            coo.push(position[a], position[b], v);
        }
        let csc = CscMatrix::from(&coo);
        let factor = CscCholesky::factor(&csc).map_err(|_| FlattenError::NotPositiveDefinite { unknowns: count })?;
        Ok(Self {
            free,
            factor,
            position,
            coupling,
        })
    }

    /// Solves for the free unknowns with right-hand side `rhs` (one entry per unknown, the
    /// pinned ones ignored) and the pinned unknowns at `values` (read at pinned indices);
    /// writes the free unknowns into `values`.
    pub(crate) fn solve(&self, rhs: &[f64], values: &mut [f64]) {
        let position = &self.position;
        let mut b = DVector::zeros(position.len());
        for (i, f) in self.free.iter().enumerate() {
            if let Some(f) = f {
                b[position[*f]] = rhs[i];
            }
        }
        for &(a, j, v) in &self.coupling {
            b[position[a]] -= v * values[j];
        }
        let x = self.factor.solve(&b);
        for (i, f) in self.free.iter().enumerate() {
            if let Some(f) = f {
                values[i] = x[position[*f]];
            }
        }
    }
}

/// Reverse Cuthill-McKee order of a graph given by its neighbour lists (sorted and deduplicated
/// here): breadth first from a vertex of least degree, neighbours by increasing degree,
/// every component in turn; the order reversed.
fn reverse_cuthill_mckee(neighbours: &mut [Vec<usize>]) -> Vec<usize> {
    for list in neighbours.iter_mut() {
        list.sort_unstable();
        list.dedup();
    }
    let n = neighbours.len();
    let degree: Vec<usize> = neighbours.iter().map(Vec::len).collect();
    let mut by_degree: Vec<usize> = (0..n).collect();
    by_degree.sort_by_key(|&v| (degree[v], v));
    let mut seen = vec![false; n];
    let mut order = Vec::with_capacity(n);
    for &start in &by_degree {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let mut head = order.len();
        order.push(start);
        while head < order.len() {
            let v = order[head];
            head += 1;
            let mut next: Vec<usize> = neighbours[v].iter().copied().filter(|&w| !seen[w]).collect();
            next.sort_by_key(|&w| (degree[w], w));
            for w in next {
                seen[w] = true;
                order.push(w);
            }
        }
    }
    order.reverse();
    order
}
