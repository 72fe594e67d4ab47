//! Propagation: one pass outward through the network from the curves with pending moves,
//! visiting the neighbours whose constraint with a solved curve is violated, in priority
//! order; a curve driven one way waits (once) for the curve that drives it.

use std::collections::{BTreeMap, BTreeSet, VecDeque};

use glam::DVec3;

use super::{EditError, Run};

impl Run<'_> {
    /// One pass outward from the curves with pending moves. Returns the constraints left
    /// broken by a curve solved after the other end of the constraint.
    pub(super) fn pass(
        &mut self,
        pass: usize,
        pending: &mut BTreeMap<usize, Vec<(usize, DVec3)>>,
        solved_all: &mut BTreeSet<usize>,
    ) -> Result<Vec<(usize, usize)>, EditError> {
        let tol = self.options.tolerance;
        let mut solved: BTreeSet<usize> = BTreeSet::new();
        let mut queue: VecDeque<usize> = pending.keys().copied().collect();
        let mut queued: BTreeSet<usize> = queue.iter().copied().collect();
        let mut broken: Vec<(usize, usize)> = Vec::new();
        let mut deferred: BTreeSet<usize> = BTreeSet::new();
        while let Some(c) = queue.pop_front() {
            // A curve waits (once) for a queued curve that drives it one way (a strap
            // before the contour that continues it).
            let waits = self.net.touching(c).iter().any(|&k| {
                let con = &self.net.constraints[k];
                con.directed && con.j == c && queue.contains(&con.i) && !solved.contains(&con.i)
            });
            if waits && deferred.insert(c) {
                queue.push_back(c);
                continue;
            }
            let moves = pending.remove(&c).unwrap_or_default();
            let mut it = self.solve_curve(pass, c, &moves, &solved)?;
            solved.insert(c);
            solved_all.insert(c);
            let touching = self.net.touching(c);
            for &k in &touching {
                let r = self.residual(k);
                it.residuals.push((k, r));
                let o = self.net.constraints[k].other(c);
                if self.net.violated(k, r, tol) && solved.contains(&o) {
                    it.broken.push(k);
                    broken.push((k, c));
                }
            }
            self.iterations.push(it);
            // Outward, in priority order: neighbours whose constraint with c is violated.
            for &k in &touching {
                let con = &self.net.constraints[k];
                let o = con.other(c);
                if o == c || solved.contains(&o) || queued.contains(&o) || !con.drives(c, o) {
                    continue;
                }
                if self.net.violated(k, self.residual(k), tol) {
                    queue.push_back(o);
                    queued.insert(o);
                }
            }
        }
        Ok(broken)
    }
}
