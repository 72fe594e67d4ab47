//! Nearest points for a point that moves a little between searches (a garment sample being
//! relaxed: a dozen rounds of small moves, each cleared off the body again): the shell
//! triangles that can hold the nearest point of any point within a ball are gathered once
//! from the tree, and each search inside the ball scans only those.
//!
//! Why the scan gives the full search's answer: let `c` be the ball's centre, `d(c)` its
//! distance to the body and `r` the ball's radius. For `p` within `r` of `c`,
//! `d(p) <= d(c) + r`, so every triangle as near `p` as its nearest point (the winner and
//! every tie) lies within `d(p) + r <= d(c) + 2r` of `c`: the triangles gathered (every box
//! within that reach, widened by the boxes' slack and a relative 1e-9 for rounding). The
//! scan picks the winner as the tree search does ([`BodyIndex::nearest_among`]: least
//! distance, then lowest triangle index, then the same exact side), so the answers are the
//! same, bit for bit.

use glam::DVec3;

use super::index::{BodyIndex, Nearest};
use crate::geom::closest::closest_on_triangle;

thread_local! {
    /// Each thread's list of the triangles a ball gathers, kept from ball to ball.
    static GATHERED: std::cell::RefCell<Vec<(f64, u32, [DVec3; 3])>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The shell triangles that can hold the nearest point of any point within `room` of
/// `centre` (see the module's text), nearest `centre` first.
#[derive(Clone, Debug, PartialEq)]
pub struct Nearby {
    centre: DVec3,
    room: f64,
    /// Each triangle's distance from the centre, the triangle and its corners; ascending.
    triangles: Vec<(f64, u32, [DVec3; 3])>,
}

impl Nearby {
    /// How many triangles it holds.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether none (an empty body).
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }
}

impl BodyIndex {
    /// The triangles a search from any point within `room` (m) of `centre` needs; `found` is
    /// the nearest point to `centre` ([`Self::nearest`] with no limit).
    pub fn nearby(&self, centre: DVec3, found: &Nearest, room: f64) -> Nearby {
        self.nearby_within(centre, found.distance, room)
    }

    /// [`Self::nearby`] knowing only that the body lies within `distance` (m) of `centre`
    /// (the distance to some body point, at least the nearest one's): the triangles
    /// gathered are those [`Self::nearby`] gathers and maybe more, and the scans' answers
    /// are the same. One pass over the tree instead of a search and then the pass.
    pub fn nearby_within(&self, centre: DVec3, distance: f64, room: f64) -> Nearby {
        let reach = (distance + 2.0 * room) * (1.0 + 1e-9) + self.slack;
        // Gathered into this thread's scratch list, which keeps its room from ball to
        // ball, and handed out at its length: one allocation a ball.
        let triangles = GATHERED.with_borrow_mut(|gathered| {
            gathered.clear();
            // Every box within the reach: the bound never tightens.
            self.near
                .within(centre.as_vec3(), (reach * reach) as f32, |t, corners| {
                    let (foot, _) = closest_on_triangle(centre, *corners);
                    let distance = centre.distance(foot);
                    if distance <= reach {
                        gathered.push((distance, t, *corners));
                    }
                });
            gathered.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            gathered.to_vec()
        });
        Nearby {
            centre,
            room,
            triangles,
        }
    }

    /// The nearest point to `p` (as [`Self::nearest`] with no limit finds it) when `p` lies
    /// within the room of `near`; `None` when it lies outside (search the whole tree).
    ///
    /// The triangles are measured nearest the centre first, and the scan stops at the first
    /// whose distance from the centre, less `p`'s from the centre, exceeds the best distance
    /// (by a relative 1e-9 for rounding): no triangle after it can be as near.
    pub fn nearest_nearby(&self, near: &Nearby, p: DVec3) -> Option<Nearest> {
        let moved = p.distance(near.centre);
        if moved > near.room {
            return None;
        }
        let mut best: Option<(f64, u32, DVec3, crate::geom::closest::Feature)> = None;
        for &(from_centre, t, corners) in &near.triangles {
            if let Some((d, ..)) = best
                && from_centre - moved > d + 1e-9 * (from_centre + moved + d)
            {
                break;
            }
            let (foot, feature) = closest_on_triangle(p, corners);
            let distance = p.distance(foot);
            if best.is_none_or(|(d, bt, ..)| distance < d || (distance == d && t < bt)) {
                best = Some((distance, t, foot, feature));
            }
        }
        let (distance, t, foot, feature) = best?;
        Some(self.settle(p, self.at_feature(t, foot, feature, distance)))
    }

    /// [`Self::nearest_nearby`] at the ball's centre, with no scan: the triangles are held
    /// by their distance from the centre and then their index, the order in which the scan
    /// picks its winner, so the first one wins.
    pub fn nearest_at_centre(&self, near: &Nearby) -> Option<Nearest> {
        let &(distance, t, corners) = near.triangles.first()?;
        let (foot, feature) = closest_on_triangle(near.centre, corners);
        Some(self.settle(near.centre, self.at_feature(t, foot, feature, distance)))
    }
}
