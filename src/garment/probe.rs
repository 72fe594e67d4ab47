//! Clearance against the body for the feature curves that no section gives (shoulder
//! seams, the crotch junction, contour spans between rings): their samples are moved out
//! along the way out of the body until they stand `gap` off the skin. The queries are the
//! body index's (exact nearest point and pseudo-normal sign), the same the collision uses.

use glam::DVec3;

use crate::body::Body;
use crate::body::index::{BodyIndex, Nearest};
use crate::body::nearby::Nearby;
use crate::body::slices::SliceOptions;
use crate::convergence::{Stop, record};

/// Most passes of [`BodyProbe::clear`].
const CLEAR_PASSES: usize = 4;

/// The radius of [`BodyProbe::clear_near`]'s ball, in clearances.
const NEARBY_ROOM: f64 = 0.5;

/// A body prepared for clearance queries: it owns the body's one [`BodyIndex`].
#[derive(Debug)]
pub struct BodyProbe {
    index: BodyIndex,
}

impl BodyProbe {
    /// Prepares `body` (its index with the default slices).
    pub fn new(body: &Body) -> Self {
        Self::from_index(BodyIndex::new(body, &SliceOptions::default()))
    }

    /// Wraps an index already built.
    pub fn from_index(index: BodyIndex) -> Self {
        Self { index }
    }

    /// The body index (for the collision).
    pub fn index(&self) -> &BodyIndex {
        &self.index
    }

    /// The nearest surface point and the signed distance (negative inside); `None` for a
    /// body with no triangles.
    pub fn nearest(&self, p: DVec3) -> Option<(DVec3, f64, DVec3)> {
        self.index
            .nearest(p, f64::INFINITY)
            .map(|n| (n.foot, n.signed(p), n.normal))
    }

    /// Signed distance of `p` to the body surface, m (negative inside); infinite with no body.
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        self.nearest(p).map_or(f64::INFINITY, |(_, d, _)| d)
    }

    /// Moves `p` out until it stands at least `gap` (m) off the body: from the nearest surface
    /// point along the way out. A few passes settle points near concave creases. Points
    /// already `gap` away are returned unchanged (bit for bit).
    pub fn clear(&self, p: DVec3, gap: f64) -> DVec3 {
        self.clear_measuring(p, gap).0
    }

    /// [`Self::clear`], with the body's nearest point to the point returned (every pass
    /// measures where it stands, the last one where it stops): `None` for a body with no
    /// triangles.
    pub fn clear_measuring(&self, p: DVec3, gap: f64) -> (DVec3, Option<Nearest>) {
        self.clear_with(p, gap, |q, _| self.index.nearest_next(q, f64::INFINITY))
    }

    /// [`Self::clear_measuring`], and for a point the clearing moved, the ball
    /// [`Self::clear_near`] keeps about where it stops ([`Self::nearby`]): a point moved
    /// stands at most `gap` off the skin point it was moved from, so each pass after the
    /// first gathers the ball about where it stands at once and finds the nearest point
    /// in it, instead of searching the tree and then gathering the ball. The same answers.
    pub fn clear_keeping_ball(&self, p: DVec3, gap: f64) -> (DVec3, Option<Nearest>, Option<Nearby>) {
        let room = NEARBY_ROOM * gap;
        let mut ball: Option<Nearby> = None;
        let (q, n) = self.clear_with(p, gap, |q, within| {
            if let Some(n) = ball.as_ref().and_then(|b| self.index.nearest_nearby(b, q)) {
                return Some(n);
            }
            match within {
                None => self.index.nearest_next(q, f64::INFINITY),
                Some(d) => {
                    let near = self.index.nearby_within(q, d, room);
                    let n = self.index.nearest_at_centre(&near);
                    ball = Some(near);
                    n
                }
            }
        });
        (q, n, ball)
    }

    /// [`Self::clear_measuring`] for a point that moves a little between calls (a sample
    /// being relaxed): `near` keeps the triangles that can be nearest within a ball about
    /// where it last stood ([`Nearby`]), gathered again wherever it leaves the ball; the
    /// same answers as the full search.
    pub fn clear_near(&self, p: DVec3, gap: f64, near: &mut Option<Nearby>) -> (DVec3, Option<Nearest>) {
        let room = NEARBY_ROOM * gap;
        self.clear_with(p, gap, |q, _| {
            if let Some(n) = near.as_ref().and_then(|b| self.index.nearest_nearby(b, q)) {
                return Some(n);
            }
            let n = self.index.nearest(q, f64::INFINITY)?;
            *near = Some(self.index.nearby(q, &n, room));
            Some(n)
        })
    }

    /// The triangles a search from anywhere within `room` (m) of `centre` needs
    /// ([`Nearby`], after one full search at the centre); `None` for a body with no
    /// triangles.
    pub fn ball(&self, centre: DVec3, room: f64) -> Option<Nearby> {
        let found = self.index.nearest(centre, f64::INFINITY)?;
        Some(self.index.nearby(centre, &found, room))
    }

    /// [`Self::signed_distance`], scanning the triangles of `near` where `p` lies within
    /// its ball (the same answer).
    pub fn signed_distance_near(&self, p: DVec3, near: Option<&Nearby>) -> f64 {
        near.and_then(|b| self.index.nearest_nearby(b, p))
            .or_else(|| self.index.nearest(p, f64::INFINITY))
            .map_or(f64::INFINITY, |n| n.signed(p))
    }

    /// [`Self::clear`], each pass's nearest point found by `search`, given the point and,
    /// after the first pass, its distance from the skin point it was moved from (the body
    /// lies at least that near).
    fn clear_with(
        &self,
        p: DVec3,
        gap: f64,
        mut search: impl FnMut(DVec3, Option<f64>) -> Option<Nearest>,
    ) -> (DVec3, Option<Nearest>) {
        let mut q = p;
        let mut stop = (Stop::IterationLimit, CLEAR_PASSES, 0.0);
        let mut last: Option<Nearest> = None;
        for pass in 0..=CLEAR_PASSES {
            let within = last.map(|n| q.distance(n.foot));
            last = search(q, within);
            let Some(n) = last else {
                stop = (Stop::Converged, pass, 0.0);
                break;
            };
            let d = n.signed(q);
            if d >= gap * (1.0 - 1e-9) {
                stop = (Stop::Converged, pass, 0.0);
                break;
            }
            if pass == CLEAR_PASSES {
                stop.2 = gap - d;
                break;
            }
            let mut out = (q - n.foot) * d.signum();
            if out.length_squared() <= 1e-24 {
                out = n.normal;
            }
            q = n.foot + out.normalize_or_zero() * gap;
        }
        if stop.1 > 0 {
            record("garment.probe.clear", stop.0, stop.1, stop.2);
        }
        (q, last)
    }
}
