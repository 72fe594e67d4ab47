//! Solving one curve: the constraints from its solved neighbours (coincident points,
//! mirrored points, tangents; its other control points follow in proportion), then its
//! self constraints (the plane, symmetry, the ease and the design region), then the node and
//! curve layers, and the self-crossing check.

use std::collections::BTreeSet;

use glam::{DVec2, DVec3};

use super::limits::SelfLimits;
use super::{Chains, EditError, Iteration, Run, refit_error};
use crate::constraint::crossing::self_crossings;
use crate::constraint::curves::{self, CurveKind, CurveNode};
use crate::constraint::kinds::{Kind, SAMPLES_PER_SPAN, mirror};
use crate::geom::Plane;

impl Run<'_> {
    pub(super) fn solve_curve(
        &mut self,
        pass: usize,
        c: usize,
        moves: &[(usize, DVec3)],
        solved: &BTreeSet<usize>,
    ) -> Result<Iteration, EditError> {
        let tol = self.options.tolerance;
        // The tolerance of a length: the same fraction of the body's height.
        let tol_m = tol * self.net.scale;
        let node = self.node(c).clone();
        let touching = self.net.touching(c);
        let (driven_by, moved, pinned) = self.driven_by_solved(c, &node, &touching, moves, solved);
        let mut control = curves::spread(&self.fw, &node, &moved);
        if node.kind == CurveKind::Open {
            // An open curve's plane is the vertical plane through its ends.
            let (a, b) = (control[0], control[control.len() - 1]);
            let n = (b - a).cross(DVec3::Y).normalize_or_zero();
            if n != DVec3::ZERO {
                let old = self.fw.open_curves[node.index].plane.normal;
                let n = if n.dot(old) < 0.0 { -n } else { n };
                self.fw.open_curves[node.index].plane = Plane::from_point_normal(a, n);
            }
        }
        // 2. Self constraints: the plane; symmetry (each pair takes its driven side, or the
        // side whose pair stands further off the body); then the ease and the design region,
        // applied as joint pushes of each mirrored pair so that they keep the symmetry; the
        // plane again.
        if let Some(plane) = curves::plane(&self.fw, &node) {
            // Into the plane first, so the choices below are made where the points will be.
            for p in control.iter_mut() {
                *p = plane.snap(*p);
            }
            let driven: BTreeSet<usize> = moved.iter().map(|m| m.0).collect();
            let limits = SelfLimits::of(self.net, &touching, &plane, true);
            self.keep_symmetry(&node, &touching, (&plane, &limits), &driven, &mut control);
            limits.hold(&self.mirror_pairs(c), &BTreeSet::new(), &mut control, tol_m);
            for p in control.iter_mut() {
                *p = plane.snap(*p);
            }
        }
        curves::set_points(&mut self.fw, &node, control, &self.options.ring).map_err(|m| refit_error(&node, m))?;
        self.check_crossing(&node)?;
        // 3. Node layer.
        let keep: BTreeSet<usize> = if self.options.chains == Chains::Split {
            pinned
        } else {
            BTreeSet::new()
        };
        let node_hits = self.node_layer(c, &keep)?;
        // 4. Curve layer.
        let curve_layer = self.curve_layer(c, &keep)?;
        self.check_crossing(&node)?;
        Ok(Iteration {
            pass,
            curve: c,
            driven_by,
            node: node_hits,
            curve_layer,
            residuals: Vec::new(),
            broken: Vec::new(),
            control: curves::points(&self.fw, &node).to_vec(),
        })
    }

    /// The solve's first part, from the solved neighbours of curve `c` (`node`): the moves
    /// their violated constraints drive (added to `moves`), the points shared with them (pinned, for split
    /// chains), and a contour's end tangent from the open curve it runs on from. Returns the
    /// driving constraints, the moves and the pinned points.
    fn driven_by_solved(
        &mut self,
        c: usize,
        node: &CurveNode,
        touching: &[usize],
        moves: &[(usize, DVec3)],
        solved: &BTreeSet<usize>,
    ) -> (Vec<usize>, Vec<(usize, DVec3)>, BTreeSet<usize>) {
        let tol = self.options.tolerance;
        let mut driven_by = Vec::new();
        let mut moved: Vec<(usize, DVec3)> = moves.to_vec();
        let mut pinned: BTreeSet<usize> = BTreeSet::new();
        // 1. From the solved neighbours.
        let mut tangents = match node.kind {
            CurveKind::Contour => self.fw.contours[node.index].tangents,
            _ => [None, None],
        };
        for &k in touching {
            let con = &self.net.constraints[k];
            let o = con.other(c);
            if o == c || !solved.contains(&o) {
                continue;
            }
            // Shared points stay where the solved curve put them (split chains).
            if let Kind::Coincident { a, b } = con.kind {
                pinned.insert(if con.i == c { a } else { b });
            }
            if !con.drives(o, c) || !self.net.violated(k, con.residual(&self.fw, &self.net.curves), tol) {
                continue;
            }
            driven_by.push(k);
            let (po, pc) = (curves::points(&self.fw, self.node(o)), curves::points(&self.fw, node));
            match &con.kind {
                Kind::Coincident { a, b } => {
                    let (on_c, on_o) = if con.i == c { (*a, *b) } else { (*b, *a) };
                    set_move(&mut moved, on_c, po[on_o] - pc[on_c]);
                }
                Kind::Symmetry { mid_x, pairs, rest } => {
                    let plane = curves::plane(&self.fw, node);
                    for (&(i, j), r) in pairs.iter().zip(rest) {
                        let (on_c, want) = if con.i == c {
                            (i, mirror(po[j] - *r, *mid_x))
                        } else {
                            (j, mirror(po[i], *mid_x) + *r)
                        };
                        let want = plane.map_or(want, |p| p.snap(want));
                        set_move(&mut moved, on_c, want - pc[on_c]);
                    }
                }
                Kind::Tangent { front } => {
                    let t = self.fw.open_curves[self.node(o).index].end_tangent(*front);
                    tangents[1] = Some(t);
                }
                _ => {}
            }
        }
        if node.kind == CurveKind::Contour {
            self.fw.contours[node.index].tangents = tangents;
        }
        (driven_by, moved, pinned)
    }

    /// The solve's second part, the curve's own symmetry in its plane: each mirrored pair
    /// takes its driven side, or
    /// the side that leaves the control polygon uncrossed, or the side the ease and the
    /// region (`limits`) move less, or the side whose pair stands further off the body.
    fn keep_symmetry(
        &self,
        node: &CurveNode,
        touching: &[usize],
        (plane, limits): (&Plane, &SelfLimits<'_>),
        driven: &BTreeSet<usize>,
        control: &mut [DVec3],
    ) {
        let tol_m = self.options.tolerance * self.net.scale;
        for &k in touching {
            let con = &self.net.constraints[k];
            if !con.is_self() {
                continue;
            }
            if let Kind::Symmetry { mid_x, pairs, rest } = &con.kind {
                for (&(i, j), r) in pairs.iter().zip(rest) {
                    if i == j {
                        // A point on the mirror plane stays there (up to its rest offset).
                        control[i].x = *mid_x + 0.5 * r.x;
                        continue;
                    }
                    let from_i = plane.snap(mirror(control[i], *mid_x) + *r);
                    let from_j = plane.snap(mirror(control[j] - *r, *mid_x));
                    let take_i = match (driven.contains(&i), driven.contains(&j)) {
                        (true, false) => true,
                        (false, true) => false,
                        // Both or neither driven: keep the side that leaves the control
                        // polygon uncrossed, else the side the ease and region need to
                        // move less, else the side whose pair stands further off the body
                        // (the nearer of its two points).
                        _ => {
                            let crosses = |k: usize, p: DVec3| {
                                let flat: Vec<DVec2> = (0..control.len())
                                    .map(|m| plane.project(if m == k { p } else { control[m] }))
                                    .collect();
                                !self_crossings(&flat, curves::closed(node)).is_empty()
                            };
                            let fix = |k: usize, p: DVec3| (limits.apply(k, p, tol_m) - p).length();
                            let sd = |p: DVec3| self.probe.signed_distance(p);
                            let (fix_i, fix_j) =
                                (fix(i, control[i]) + fix(j, from_i), fix(i, from_j) + fix(j, control[j]));
                            match (crosses(j, from_i), crosses(i, from_j)) {
                                (false, true) => true,
                                (true, false) => false,
                                _ if (fix_i - fix_j).abs() > tol_m => fix_i < fix_j,
                                _ => sd(control[i]).min(sd(from_i)) >= sd(from_j).min(sd(control[j])),
                            }
                        }
                    };
                    if take_i {
                        control[j] = from_i;
                    } else {
                        control[i] = from_j;
                    }
                }
            }
        }
    }

    fn check_crossing(&self, node: &CurveNode) -> Result<(), EditError> {
        let Some(plane) = curves::plane(&self.fw, node) else {
            return Ok(());
        };
        let samples = curves::samples(&self.fw, node, SAMPLES_PER_SPAN);
        let flat: Vec<DVec2> = samples.iter().map(|(_, p)| plane.project(*p)).collect();
        if let Some(x) = self_crossings(&flat, curves::closed(node)).first() {
            return Err(EditError::SelfCrossing {
                curve: node.name.clone(),
                i: x.i,
                j: x.j,
                at: plane.lift(x.at),
                loop_length: x.loop_length,
            });
        }
        Ok(())
    }
}

/// Records a driven move of point `i` unless a stronger constraint (seen earlier, in
/// priority order) or the edit itself already placed it.
fn set_move(moved: &mut Vec<(usize, DVec3)>, i: usize, d: DVec3) {
    if !moved.iter().any(|m| m.0 == i) {
        moved.push((i, d));
    }
}
