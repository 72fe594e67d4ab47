//! Surfacing: each four-sided region of a framework as a bilinearly blended Coons patch on
//! the layout's fixed grid (\[frame\] section 4), its interior samples cleared off the body
//! like the contour spans, kept from the previous framework when none of its boundary curves
//! changed; and the lookups a template's patches use.

use std::cell::RefCell;

use glam::DVec3;

use super::contour::{Contour, clear_inner};
use super::m0::{CurveRef, PatchGrid};
use super::model::{FeatureLine, Framework, FrameworkError, Layout, Span, Spans};
use super::open_curve::OpenCurve;
use super::probe::BodyProbe;
use super::ring::GarmentRing;
use crate::body::index::Nearest;
use crate::body::nearby::Nearby;
use crate::par::par_map_owned;

/// A framework error: `what` is wrong with curve `curve`.
pub fn missing(curve: &str, what: &str) -> FrameworkError {
    FrameworkError::Section {
        curve: curve.to_string(),
        what: what.to_string(),
    }
}

/// Ring `name` of `fw`.
pub fn ring<'r>(fw: &'r Framework, name: &str) -> Result<&'r GarmentRing, FrameworkError> {
    fw.ring(name)
        .ok_or_else(|| missing(name, "ring missing from the framework"))
}

/// `n + 1` samples of ring `name` from anchor `from` to anchor `to` (see
/// [`GarmentRing::arc`]).
pub fn arc(fw: &Framework, name: &str, from: &str, to: &str, n: usize) -> Result<Vec<DVec3>, FrameworkError> {
    ring(fw, name)?
        .arc(from, to, n)
        .ok_or_else(|| missing(name, &format!("anchors {from} and {to} missing")))
}

/// Anchor `a` of ring `name`, m.
pub fn anchor(fw: &Framework, name: &str, a: &str) -> Result<DVec3, FrameworkError> {
    ring(fw, name)?
        .anchor(a)
        .map(|x| x.point)
        .ok_or_else(|| missing(name, &format!("anchor {a} missing")))
}

/// Joins sample runs (m) that share their end points.
pub fn join(parts: &[Vec<DVec3>]) -> Vec<DVec3> {
    let mut out: Vec<DVec3> = Vec::new();
    for p in parts {
        if out.is_empty() {
            out.extend_from_slice(p);
        } else {
            out.extend_from_slice(&p[1..]);
        }
    }
    out
}

/// Samples `v` (m) in reverse order.
pub fn reversed(mut v: Vec<DVec3>) -> Vec<DVec3> {
    v.reverse();
    v
}

/// Contour `name` of `fw`.
pub fn contour<'c>(fw: &'c Framework, name: &str) -> Result<&'c Contour, FrameworkError> {
    fw.contours
        .iter()
        .find(|c| c.name == name)
        .ok_or_else(|| missing(name, "contour missing from the framework"))
}

/// Where contour `name` passes ring `from`.
pub fn through_at(c: &Contour, from: &str) -> Result<usize, FrameworkError> {
    c.through
        .iter()
        .position(|t| t.split('.').next() == Some(from))
        .ok_or_else(|| missing(&c.name, &format!("does not pass ring {from}")))
}

/// Open curve `name` of `fw`.
pub fn open<'c>(fw: &'c Framework, name: &str) -> Result<&'c OpenCurve, FrameworkError> {
    fw.open_curves
        .iter()
        .find(|c| c.name == name)
        .ok_or_else(|| missing(name, "open curve missing from the framework"))
}

/// The samples of line `name` among `lines`.
pub fn line<'l>(lines: &'l [FeatureLine], name: &str) -> Result<&'l [DVec3], FrameworkError> {
    lines
        .iter()
        .find(|l| l.name == name)
        .map(|l| l.points.as_slice())
        .ok_or_else(|| missing(name, "line missing"))
}

/// The patch-surfacing context: clearance for contour spans, and the frameworks before
/// whose unchanged patches are kept.
pub struct Surfacer<'a> {
    fw: &'a Framework,
    probe: &'a BodyProbe,
    layout: &'a Layout,
    previous: &'a [&'a Framework],
    /// The patches kept, in order; a patch surfaced anew stands here as a placeholder
    /// until [`Self::finish`] clears it (see `fresh`).
    patches: Vec<PatchGrid>,
    resurfaced: Vec<String>,
    /// The patches surfaced anew, their interiors not yet cleared: (index, Coons grid).
    fresh: Vec<(usize, PatchGrid)>,
    /// The contour spans cleared so far (a span bounds two patches).
    spans: RefCell<Spans>,
}

/// What a [`Surfacer`] made.
pub struct Surfaced {
    /// The patches made (or kept).
    pub patches: Vec<PatchGrid>,
    /// The names of those surfaced anew.
    pub resurfaced: Vec<String>,
    /// The body's nearest point to the interior samples of those, where they stand (the
    /// clearing measured them: the collision need not measure them again).
    /// (patch, sample, nearest point).
    pub measured: Vec<(usize, usize, Nearest)>,
    /// The contour spans the patches were surfaced from.
    pub spans: Spans,
}

impl<'a> Surfacer<'a> {
    /// Surfaces `fw`; patches and spans whose samples are those of one of the frameworks
    /// `previous` are taken from the first such.
    pub fn new(fw: &'a Framework, probe: &'a BodyProbe, previous: &'a [&'a Framework]) -> Self {
        Self {
            fw,
            probe,
            layout: &fw.layout,
            previous,
            patches: Vec::new(),
            resurfaced: Vec::new(),
            fresh: Vec::new(),
            spans: RefCell::new(Spans::new()),
        }
    }

    /// The framework being surfaced.
    pub fn framework(&self) -> &'a Framework {
        self.fw
    }

    /// Its layout (sample counts).
    pub fn layout(&self) -> &'a Layout {
        self.layout
    }

    /// What was made ([`Surfaced`]): the patches surfaced anew cleared off the body, and
    /// relaxed where the clearing moved them, on all cores (each patch on its own, the
    /// results in patch order: the same on any number of threads).
    pub fn finish(mut self) -> Surfaced {
        let (probe, gap, scale) = (self.probe, self.layout.clearance, self.layout.height);
        let fresh = std::mem::take(&mut self.fresh);
        let done = par_map_owned(fresh, 2, |(i, mut grid)| {
            // The blend of four boundaries that stand off the body can still dip into it
            // where the body bulges between them (the inner thigh and the belly over a tall
            // crotch junction): interior samples stand the clearance off, as contour spans
            // do.
            let Cleared {
                moved,
                mut found,
                balls,
            } = clear_interior(&mut grid, probe, gap);
            if moved.contains(&true) {
                relax(&mut grid, &moved, &mut found, balls, probe, gap, scale);
            }
            (i, grid, found)
        });
        // (A vertex two patches' samples weld into stands where both do: the same nearest
        // point, whichever comes first.)
        let mut measured = Vec::new();
        for (i, grid, found) in done {
            measured.extend(sampled(i, &found));
            self.patches[i] = grid;
        }
        Surfaced {
            patches: self.patches,
            resurfaced: self.resurfaced,
            measured,
            spans: self.spans.into_inner(),
        }
    }

    /// Samples of contour `name` from its point on ring `from` up to the next one, inner
    /// samples cleared off the body.
    ///
    /// A span is cleared once an assembly (it bounds two patches), and taken from the
    /// previous framework when its samples before clearing and the clearance are the same:
    /// the same cleared samples, as clearing depends on nothing else.
    pub fn span(&self, name: &str, from: &str, n: usize) -> Result<Vec<DVec3>, FrameworkError> {
        let c = contour(self.fw, name)?;
        let key = (name.to_string(), through_at(c, from)?, n);
        if let Some(span) = self.spans.borrow().get(&key) {
            return Ok(span.cleared.clone());
        }
        let raw = c.span(key.1, n, None);
        let kept = self.previous.iter().find_map(|old| {
            let same = old.layout.clearance == self.layout.clearance;
            same.then(|| old.spans.get(&key)).flatten().filter(|s| s.raw == raw)
        });
        let span = match kept {
            Some(span) => span.clone(),
            None => Span {
                cleared: clear_inner(&raw, self.probe, self.layout.clearance),
                raw,
            },
        };
        let cleared = span.cleared.clone();
        self.spans.borrow_mut().insert(key, span);
        Ok(cleared)
    }

    /// The control points of contour `name` that shape its span from ring `from`.
    pub fn span_ref(&self, name: &str, from: &str) -> Result<CurveRef, FrameworkError> {
        let c = contour(self.fw, name)?;
        let k = through_at(c, from)?;
        Ok(CurveRef {
            curve: name.to_string(),
            first: k.saturating_sub(1),
            last: k + 2,
        })
    }

    /// Surfaces one patch, or keeps the previous one when its four sides and the clearance
    /// are the same: a patch is the Coons blend of its sides, cleared and relaxed against
    /// the same body, so it depends on nothing else.
    pub fn patch(&mut self, name: &str, sides: [&[DVec3]; 4], curves: Vec<CurveRef>) -> Result<(), FrameworkError> {
        if self.keep(name, &curves, |p| p.sides_are(sides)) {
            return Ok(());
        }
        let grid = PatchGrid::coons(name, sides, self.layout.weld)?.with_curves(curves);
        self.surface(name, grid);
        Ok(())
    }

    /// Surfaces one three-sided patch (see [`PatchGrid::triangle`]), or keeps the previous
    /// one when its three sides and the clearance are the same.
    pub fn triangle(&mut self, name: &str, sides: [&[DVec3]; 3], curves: Vec<CurveRef>) -> Result<(), FrameworkError> {
        if self.keep(name, &curves, |p| p.triangle_sides_are(sides)) {
            return Ok(());
        }
        let grid = PatchGrid::triangle(name, sides, self.layout.weld)?.with_curves(curves);
        self.surface(name, grid);
        Ok(())
    }

    /// Keeps the patch `name` of the first framework before whose clearance, and whose
    /// patch's curves and sides (`same_sides`), are the same; whether it did.
    fn keep(&mut self, name: &str, curves: &[CurveRef], same_sides: impl Fn(&PatchGrid) -> bool) -> bool {
        let kept = self.previous.iter().find_map(|old| {
            let same = old.layout.clearance == self.layout.clearance;
            same.then(|| old.patches.iter().find(|p| p.name == name))
                .flatten()
                .filter(|p| p.curves == curves && same_sides(p))
        });
        if let Some(p) = kept {
            self.patches.push(p.clone());
        }
        kept.is_some()
    }

    /// Keeps a new patch, to be cleared off the body by [`Self::finish`].
    fn surface(&mut self, name: &str, grid: PatchGrid) {
        self.fresh.push((self.patches.len(), grid));
        self.patches.push(PatchGrid::default());
        self.resurfaced.push(name.to_string());
    }
}

/// The samples of patch `patch` whose nearest body point `found` holds: (patch, sample,
/// nearest point).
fn sampled(patch: usize, found: &[Option<Nearest>]) -> impl Iterator<Item = (usize, usize, Nearest)> + '_ {
    found
        .iter()
        .enumerate()
        .filter_map(move |(k, n)| n.map(|n| (patch, k, n)))
}

/// What [`clear_interior`] did to each sample of a patch.
struct Cleared {
    /// Whether it moved.
    moved: Vec<bool>,
    /// The body's nearest point where it ends.
    found: Vec<Option<Nearest>>,
    /// For a sample moved, the ball [`BodyProbe::clear_near`] keeps about where it ends.
    balls: Vec<Option<Nearby>>,
}

/// Clears every interior sample of `grid` off the body by `gap` (m).
fn clear_interior(grid: &mut PatchGrid, probe: &BodyProbe, gap: f64) -> Cleared {
    let mut out = Cleared {
        moved: vec![false; grid.points.len()],
        found: vec![None; grid.points.len()],
        balls: vec![None; grid.points.len()],
    };
    for k in grid.interior().iter().map(|point| point.index) {
        let (p, n, ball) = probe.clear_keeping_ball(grid.points[k], gap);
        out.moved[k] = p != grid.points[k];
        grid.points[k] = p;
        out.found[k] = n;
        out.balls[k] = ball.filter(|_| out.moved[k] && n.is_some());
    }
    out
}

/// Most rounds of relaxation of a cleared patch.
pub const RELAX_ROUNDS: usize = 12;

/// Evens out the samples the clearing moved: clearing sends each sample to its own nearest
/// skin, so samples over a fold bunch on its lips and leave long edges across it. Each round
/// moves every moved sample half way to its four neighbours' mean, within the patch's
/// tangent plane there (so the patch does not flatten), and clears it again; the samples
/// the clearing left alone keep the Coons blend and hold the rest in place. Stops early
/// once no sample moves more than 1e-4 of `scale` (m) in a round. `found` follows the
/// body's nearest point to each sample moved; `near` holds each moved sample's ball, about
/// where the clearing left it.
fn relax(
    grid: &mut PatchGrid,
    moved: &[bool],
    found: &mut [Option<Nearest>],
    mut near: Vec<Option<Nearby>>,
    probe: &BodyProbe,
    gap: f64,
    scale: f64,
) {
    let interior = grid.interior();
    let mut before = Vec::new();
    for _ in 0..RELAX_ROUNDS {
        before.clone_from(&grid.points);
        let mut most: f64 = 0.0;
        for point in &interior {
            let (k, around) = (point.index, point.around());
            if !moved[k] {
                continue;
            }
            let p = before[k];
            let (l, r, d, u) = (
                before[around[0]],
                before[around[1]],
                before[around[2]],
                before[around[3]],
            );
            let n = (r - l).cross(u - d).normalize_or_zero();
            let lap = if around.len() == 4 {
                0.25 * (l + r + d + u) - p
            } else {
                around.iter().map(|&a| before[a]).sum::<DVec3>() / around.len() as f64 - p
            };
            let tangential = lap - n * lap.dot(n);
            let (q, n) = probe.clear_near(p + 0.5 * tangential, gap, &mut near[k]);
            most = most.max(q.distance(p));
            grid.points[k] = q;
            found[k] = n;
        }
        if most <= 1e-4 * scale {
            break;
        }
    }
}
