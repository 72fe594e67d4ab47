//! Closed chains (\[collide\] section 2.3): when a collision response breaks a joint with a
//! curve solved before (A -> B -> C -> A), the earlier curve takes the later one's point (or
//! tangent) and the next pass solves again from it.

use std::collections::BTreeMap;

use glam::DVec3;

use super::Run;
use crate::constraint::curves;
use crate::constraint::kinds::{Kind, mirror};

impl Run<'_> {
    /// Moves for the next pass: for each broken constraint (k, by curve c), the other
    /// curve A takes c's point (or c itself is solved again for a self constraint).
    pub(super) fn close_chains(&mut self, broken: &[(usize, usize)]) -> BTreeMap<usize, Vec<(usize, DVec3)>> {
        let mut out: BTreeMap<usize, Vec<(usize, DVec3)>> = BTreeMap::new();
        for &(k, c) in broken {
            let con = &self.net.constraints[k];
            let a = con.other(c);
            let entry = out.entry(a).or_default();
            if a == c {
                continue;
            }
            if let Kind::Tangent { front } = con.kind {
                let (open, contour) = (self.net.curves[con.i].index, self.net.curves[con.j].index);
                let t = self.fw.open_curves[open].end_tangent(front);
                self.fw.contours[contour].tangents[1] = Some(t);
                continue;
            }
            let (pa, pc) = (
                curves::points(&self.fw, self.node(a)),
                curves::points(&self.fw, self.node(c)),
            );
            match &con.kind {
                Kind::Coincident { a: ia, b: ib } => {
                    let (on_a, on_c) = if con.i == a { (*ia, *ib) } else { (*ib, *ia) };
                    entry.push((on_a, pc[on_c] - pa[on_a]));
                }
                Kind::Symmetry { mid_x, pairs, rest } => {
                    let plane = curves::plane(&self.fw, &self.net.curves[a]);
                    for (&(i, j), r) in pairs.iter().zip(rest) {
                        let (on_a, want) = if con.i == a {
                            (i, mirror(pc[j] - *r, *mid_x))
                        } else {
                            (j, mirror(pc[i], *mid_x) + *r)
                        };
                        let want = plane.map_or(want, |p| p.snap(want));
                        entry.push((on_a, want - pa[on_a]));
                    }
                }
                _ => {}
            }
        }
        out
    }
}
