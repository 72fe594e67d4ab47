//! What a collision remembers between steps so that it measures only what a step could
//! have changed: the signed distance of each vertex where the quality check last measured
//! it, for each edge whether it crossed the body at the ends it had when last tested
//! (by the quality check, or found clear by the first edge round, which decides with the
//! check's test), and for each face whether the body pierced it at the corners it had
//! when last tested (by the check or the first face round, which share their test).
//!
//! A remembered answer is used only where the positions are the same, bit for bit: a
//! distance and a crossing depend on nothing else (the body is fixed for a session), so
//! the answers are exactly those a full check gives. An edit moves only the patches whose
//! curves changed, and the response moves only the vertices near the body, so most of a
//! garment is the same from step to step.

use glam::DVec3;

use super::types::VertexDistance;

/// Remembered answers, by vertex and by edge (the same garment topology).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Reuse {
    /// Per vertex: where its distance was measured, and the distance.
    distance: Vec<Option<(DVec3, VertexDistance)>>,
    /// Per edge: the pass of the quality check that last tested it (see [`Moves`]; 0:
    /// none), and whether it met the body then.
    crossing: Vec<(u32, bool)>,
    /// Per edge: the pass of the first edge round that last found it clear (0: none, or
    /// it crossed).
    clear_in_round: Vec<u32>,
    /// Per face: the pass that last tested it (0: none), and whether the body pierced it
    /// then (see [`super::faces`]).
    faces: Vec<(u32, bool)>,
    /// Per face: the pass that last measured its distance to the body (0: none), and the
    /// distance, capped at `face_cap` (see [`super::faces::faces_nearer`]).
    face_distance: Vec<(u32, f64)>,
    /// The cap of those distances, m.
    face_cap: f64,
    /// The faces those verdicts are for.
    triangles: Vec<[u32; 3]>,
    /// The vertex moves between passes, checks and rounds alike.
    moves: Moves,
}

/// The passes over a garment's edges that remember a verdict per edge (the quality checks
/// and the first edge rounds, in one sequence), numbered from 1, and per vertex where it
/// stood at the last pass and the pass at which it last stood somewhere else than at the
/// one before. An edge's verdict holds while neither end has moved since the pass that gave
/// it, which is exactly when its ends are those it was given at: a few bytes an edge
/// instead of both ends' positions.
#[derive(Clone, Debug, Default, PartialEq)]
struct Moves {
    passes: u32,
    edges: Vec<[u32; 2]>,
    at: Vec<DVec3>,
    moved_at: Vec<u32>,
}

impl Moves {
    /// Starts a pass over `edges` with the vertices at `positions`: notes the vertices that
    /// moved since the last pass (every one when the edges or the vertex count changed);
    /// true when they changed (every verdict is void).
    fn begin(&mut self, positions: &[DVec3], edges: &[[u32; 2]]) -> bool {
        self.passes += 1;
        if self.edges != edges || self.at.len() != positions.len() {
            self.edges = edges.to_vec();
            self.at = positions.to_vec();
            self.moved_at = vec![self.passes; positions.len()];
            return true;
        }
        for ((at, moved), &p) in self.at.iter_mut().zip(&mut self.moved_at).zip(positions) {
            // `!=`, not a distance: a NaN position, never equal to itself, never stands still.
            if *at != p {
                *at = p;
                *moved = self.passes;
            }
        }
        false
    }

    /// Whether a verdict given at pass `given` on the edge or face with corners `ends`
    /// still holds.
    fn holds(&self, given: u32, ends: impl IntoIterator<Item = u32>) -> bool {
        let moved = |v: u32| self.moved_at.get(v as usize).copied().unwrap_or(u32::MAX);
        given > 0 && ends.into_iter().all(|v| given >= moved(v))
    }
}

/// How much a step took from [`Reuse`] (for the metrics).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Reused {
    /// Vertices whose signed distance was not measured again.
    pub vertices: usize,
    /// Edges the quality check did not test again.
    pub quality_edges: usize,
    /// Edges the first edge round did not test again.
    pub round_edges: usize,
}

impl Reuse {
    /// Forgets everything (the full check: everything is measured again).
    pub fn clear(&mut self) {
        *self = Self::default();
    }

    /// The distance of vertex `v` at `p`, if it was measured there.
    pub fn distance(&self, v: usize, p: DVec3) -> Option<VertexDistance> {
        match self.distance.get(v) {
            Some(Some((at, s))) if *at == p => Some(*s),
            _ => None,
        }
    }

    /// Starts a pass over `edges` on the vertices at `positions` (see [`Moves`]): a quality
    /// check then reads its verdicts ([`Self::check_verdict`]) and gives one to every edge
    /// ([`Self::set_crossing`]); a first edge round reads [`Self::clear_in_round`] and
    /// gives [`Self::set_round`]. A change of the edges forgets every verdict.
    pub fn begin_pass(&mut self, positions: &[DVec3], edges: &[[u32; 2]]) {
        if self.moves.begin(positions, edges) {
            self.crossing = vec![(0, false); edges.len()];
            self.clear_in_round = vec![0; edges.len()];
            self.faces.clear();
            self.face_distance.clear();
        }
    }

    /// Whether edge `[a, b]` (edge `e` of this check's edges) meets the body, if it was
    /// tested by a check since which neither end moved.
    pub fn crossing(&self, e: usize, ends: [u32; 2]) -> Option<bool> {
        let &(tested, hit) = self.crossing.get(e)?;
        self.moves.holds(tested, ends).then_some(hit)
    }

    /// What a quality check knows of edge `[a, b]` (edge `e` of its edges): its own verdict
    /// ([`Self::crossing`]), or else clear if a first edge round since which neither end
    /// moved found it clear (the rounds decide with the check's test).
    pub fn check_verdict(&self, e: usize, ends: [u32; 2]) -> Option<bool> {
        self.crossing(e, ends)
            .or_else(|| self.clear_in_round(e, ends).then_some(false))
    }

    /// Whether a first edge round since which neither end of edge `[a, b]` (edge `e` of
    /// this round's edges) moved found it clear of the body.
    pub fn clear_in_round(&self, e: usize, ends: [u32; 2]) -> bool {
        self.clear_in_round
            .get(e)
            .is_some_and(|&given| self.moves.holds(given, ends))
    }

    /// Remembers the distance of vertex `v` at `p`.
    pub fn set_distance(&mut self, vertices: usize, v: usize, p: DVec3, s: VertexDistance) {
        if self.distance.len() != vertices {
            self.distance = vec![None; vertices];
        }
        self.distance[v] = Some((p, s));
    }

    /// Remembers whether edge `e` meets the body at this check's pass.
    pub fn set_crossing(&mut self, e: usize, hit: bool) {
        let check = self.moves.passes;
        if let Some(slot) = self.crossing.get_mut(e) {
            *slot = (check, hit);
        }
    }

    /// Starts remembering verdicts on `triangles` (the faces of this pass's edges): a
    /// change of the faces forgets every face verdict.
    pub fn begin_faces(&mut self, triangles: &[[u32; 3]]) {
        if self.triangles != triangles || self.faces.len() != triangles.len() {
            self.triangles = triangles.to_vec();
            self.faces = vec![(0, false); triangles.len()];
            self.face_distance.clear();
        }
    }

    /// The distance of face `f` (corners `corners`) to the body capped at `cap`, if it was
    /// measured with that cap at a pass since which none of its corners moved.
    pub fn face_distance(&self, f: usize, corners: [u32; 3], cap: f64) -> Option<f64> {
        if cap != self.face_cap {
            return None;
        }
        let &(given, d) = self.face_distance.get(f)?;
        self.moves.holds(given, corners).then_some(d)
    }

    /// Remembers the distance of face `f` to the body, capped at `cap`, at this pass (of
    /// `faces` faces; another cap forgets the others).
    pub fn set_face_distance(&mut self, faces: usize, f: usize, cap: f64, d: f64) {
        if cap != self.face_cap || self.face_distance.len() != faces {
            self.face_cap = cap;
            self.face_distance = vec![(0, 0.0); faces];
        }
        self.face_distance[f] = (self.moves.passes, d);
    }

    /// Whether face `f` (corners `corners`) is pierced by the body, if it was tested by a
    /// pass since which none of its corners moved.
    pub fn face(&self, f: usize, corners: [u32; 3]) -> Option<bool> {
        let &(tested, hit) = self.faces.get(f)?;
        self.moves.holds(tested, corners).then_some(hit)
    }

    /// Remembers whether face `f` is pierced at this pass.
    pub fn set_face(&mut self, f: usize, hit: bool) {
        let pass = self.moves.passes;
        if let Some(slot) = self.faces.get_mut(f) {
            *slot = (pass, hit);
        }
    }

    /// Remembers whether this first edge round found edge `e` clear of the body.
    pub fn set_round(&mut self, e: usize, clear: bool) {
        let round = self.moves.passes;
        if let Some(slot) = self.clear_in_round.get_mut(e) {
            *slot = if clear { round } else { 0 };
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::Reuse;

    struct Lcg(u64);

    impl Lcg {
        fn below(&mut self, n: usize) -> usize {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((self.0 >> 33) % n as u64) as usize
        }
    }

    /// 400 passes over a ring of 12 vertices: before each, up to three vertices move to
    /// one of five spots (so some go back to where they stood before) or, one time in
    /// eight, to NaN; after 200, other edges. `pass(reuse, rng, edges, positions, ends)`
    /// makes a pass with each edge's ends, and is told (`ends` empty) when the edges change.
    #[allow(clippy::type_complexity)]
    fn random_passes(seed: u64, mut pass: impl FnMut(&mut Reuse, &mut Lcg, &[[u32; 2]], &[DVec3], &[[DVec3; 2]])) {
        let mut rng = Lcg(seed);
        let spots = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE, DVec3::NAN];
        let n = 12;
        let mut edges: Vec<[u32; 2]> = (0..n as u32).map(|v| [v, (v + 1) % n as u32]).collect();
        let mut positions: Vec<DVec3> = (0..n).map(|v| spots[v % 5]).collect();
        let mut reuse = Reuse::default();
        for k in 0..400 {
            if k == 200 {
                edges = (0..n as u32).map(|v| [v, (v + 5) % n as u32]).collect();
                pass(&mut reuse, &mut rng, &edges, &positions, &[]);
            }
            for _ in 0..rng.below(4) {
                let v = rng.below(n);
                let choices = spots.len() - usize::from(rng.below(8) != 0);
                positions[v] = spots[rng.below(choices)];
            }
            let ends: Vec<[DVec3; 2]> = edges
                .iter()
                .map(|&[a, b]| [positions[a as usize], positions[b as usize]])
                .collect();
            pass(&mut reuse, &mut rng, &edges, &positions, &ends);
        }
    }

    /// Checks as the quality check makes them (every edge read; those without a verdict
    /// tested and remembered) over [`random_passes`]: an edge's verdict is taken exactly
    /// when its ends are those it was tested at, as a record of both ends' positions
    /// written here says, and it is the verdict given then.
    #[test]
    fn a_verdict_is_taken_exactly_when_the_edges_ends_are_those_it_was_tested_at() {
        let mut record: Vec<Option<([DVec3; 2], bool)>> = Vec::new();
        let (mut taken, mut tested) = (0, 0);
        random_passes(7, |reuse, rng, edges, positions, ends| {
            reuse.begin_pass(positions, edges);
            if ends.is_empty() || record.len() != edges.len() {
                // Other edges: nothing known of them.
                record = vec![None; edges.len()];
            }
            for (e, (&edge, &ends)) in edges.iter().zip(ends).enumerate() {
                let want = record[e].and_then(|(at, hit)| (at == ends).then_some(hit));
                assert_eq!(reuse.crossing(e, edge), want, "edge {e}");
                if want.is_some() {
                    taken += 1;
                } else {
                    let hit = rng.below(2) == 1;
                    reuse.set_crossing(e, hit);
                    record[e] = Some((ends, hit));
                    tested += 1;
                }
            }
        });
        assert!(taken > 2000 && tested > 500, "{taken} taken, {tested} tested");
    }

    /// The same for the first edge rounds' verdicts (clear, or none: a crossing edge is
    /// tested again), given as a round gives them to every edge it does not keep.
    #[test]
    fn a_clear_round_verdict_is_taken_exactly_when_the_edges_ends_are_those_it_was_found_clear_at() {
        let mut record: Vec<Option<[DVec3; 2]>> = Vec::new();
        let (mut kept, mut given) = (0, 0);
        random_passes(11, |reuse, rng, edges, positions, ends| {
            reuse.begin_pass(positions, edges);
            if ends.is_empty() || record.len() != edges.len() {
                record = vec![None; edges.len()];
            }
            for (e, (&edge, &ends)) in edges.iter().zip(ends).enumerate() {
                let want = record[e] == Some(ends);
                assert_eq!(reuse.clear_in_round(e, edge), want, "edge {e}");
                if want {
                    kept += 1;
                } else {
                    let clear = rng.below(4) != 0;
                    reuse.set_round(e, clear);
                    record[e] = clear.then_some(ends);
                    given += 1;
                }
            }
        });
        assert!(kept > 2000 && given > 500, "{kept} kept, {given} given");
    }
    /// First edge rounds and quality checks taking turns over [`random_passes`], as a
    /// step makes them (vertices move between a round and the check after it), in one
    /// sequence of passes: the check takes its own verdict where the ends stood where it
    /// tested them at every pass since, else clear where they stood where a round found
    /// them clear, else none, as records of both ends' positions written here say; and it
    /// remembers what it takes from a round as its own.
    #[test]
    fn a_check_takes_a_rounds_clear_verdict_exactly_where_the_ends_did_not_move_since() {
        let mut checked: Vec<Option<([DVec3; 2], bool)>> = Vec::new();
        let mut cleared: Vec<Option<[DVec3; 2]>> = Vec::new();
        let (mut round, mut from_round, mut tested) = (false, 0, 0);
        random_passes(13, |reuse, rng, edges, positions, ends| {
            if ends.is_empty() || checked.len() != edges.len() {
                checked = vec![None; edges.len()];
                cleared = vec![None; edges.len()];
            }
            round = !round;
            reuse.begin_pass(positions, edges);
            // A verdict holds while its ends stand where they were at every pass since.
            for (e, ends) in ends.iter().enumerate() {
                if checked[e].is_some_and(|(at, _)| at != *ends) {
                    checked[e] = None;
                }
                if cleared[e].is_some_and(|at| at != *ends) {
                    cleared[e] = None;
                }
            }
            if round {
                for (e, (&edge, &ends)) in edges.iter().zip(ends).enumerate() {
                    if !reuse.clear_in_round(e, edge) {
                        let clear = rng.below(4) != 0;
                        reuse.set_round(e, clear);
                        cleared[e] = clear.then_some(ends);
                    }
                }
                return;
            }
            for (e, (&edge, &ends)) in edges.iter().zip(ends).enumerate() {
                let own = checked[e].and_then(|(at, hit)| (at == ends).then_some(hit));
                let want = own.or((cleared[e] == Some(ends)).then_some(false));
                assert_eq!(reuse.check_verdict(e, edge), want, "edge {e}");
                match want {
                    Some(hit) => {
                        from_round += usize::from(own.is_none());
                        if own.is_none() {
                            reuse.set_crossing(e, hit);
                            checked[e] = Some((ends, hit));
                        }
                    }
                    None => {
                        let hit = rng.below(2) == 1;
                        reuse.set_crossing(e, hit);
                        checked[e] = Some((ends, hit));
                        tested += 1;
                    }
                }
            }
        });
        assert!(
            from_round > 100 && tested > 300,
            "{from_round} from a round, {tested} tested"
        );
    }
}
