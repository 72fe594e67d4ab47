//! Automatic body landmarks from the horizontal section profile.
//!
//! Everything is found from events and extremes of the sections, never from fixed
//! heights, so any standing body with legs and arms apart works:
//!
//! * **crotch**: scanning up from the feet, the two leg loops are tracked (each level's
//!   leg is the loop holding the previous level's leg centroid); the crotch is the height
//!   where one loop first holds both, refined by bisection.
//! * **ankle**: the smallest leg tape girth above the foot's largest; **knee**: the smallest leg girth above
//!   the calf (the first local girth maximum above the ankle).
//! * **armpit**: scanning up the torso, loops beside it of at least 2% of its area are arms;
//!   the armpit is where the last of them joins the torso loop, refined by bisection.
//! * **waist**: the smallest torso tape girth in the middle half between crotch and armpit;
//!   **hip**: the greatest buttock protrusion (rearmost torso point) below the waist;
//!   **bust**: the largest tape girth above the waist.
//! * **neck** (narrowest): the first girth minimum above the armpit that is followed by a
//!   rise of 10% (the head).
//! * **shoulder** and **side neck**: on the front silhouette (half width against height
//!   from armpit to neck), the shoulder point is the convex corner farthest outside the
//!   chord, the side neck point the concave corner farthest inside the chord from the
//!   shoulder to the neck. **front neck**: the same concave corner on the mid-sagittal
//!   front profile between bust and neck.
//!
//! Left is `+x` (the body faces `+z`, `y` up).

use glam::{DVec2, DVec3};
use thiserror::Error;

use super::profile::{MeasuredLoop, loop_at, outer_loops};
use crate::mesh::{Adjacency, TriMesh};

/// The kinds of landmark.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LandmarkKind {
    /// Narrowest leg girth.
    Ankle,
    /// Narrowest leg girth above the calf.
    Knee,
    /// Where the legs join.
    Crotch,
    /// Largest torso girth below the waist.
    Hip,
    /// Narrowest torso girth.
    Waist,
    /// Largest torso girth above the waist.
    Bust,
    /// Where the arms join the torso.
    Armpit,
    /// Narrowest neck girth.
    Neck,
    /// Jugular notch: front of the neck base.
    FrontNeck,
    /// Side of the neck base, on the shoulder line.
    SideNeck,
    /// Shoulder point (acromion), the outer end of the shoulder line.
    Shoulder,
}

impl LandmarkKind {
    /// All kinds, bottom to top.
    pub const ALL: [Self; 11] = [
        Self::Ankle,
        Self::Knee,
        Self::Crotch,
        Self::Hip,
        Self::Waist,
        Self::Bust,
        Self::Armpit,
        Self::Shoulder,
        Self::FrontNeck,
        Self::SideNeck,
        Self::Neck,
    ];

    /// The name used in sessions and the viewer.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ankle => "ankle",
            Self::Knee => "knee",
            Self::Crotch => "crotch",
            Self::Hip => "hip",
            Self::Waist => "waist",
            Self::Bust => "bust",
            Self::Armpit => "armpit",
            Self::Neck => "neck",
            Self::FrontNeck => "front_neck",
            Self::SideNeck => "side_neck",
            Self::Shoulder => "shoulder",
        }
    }

    /// The kind with this session name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Whether the landmark comes as a left/right pair.
    pub fn is_paired(self) -> bool {
        matches!(self, Self::Ankle | Self::Knee | Self::SideNeck | Self::Shoulder)
    }
}

/// Which side of the body.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// On the mid-sagittal plane.
    Centre,
    /// The body's left (`+x`).
    Left,
    /// The body's right (`-x`).
    Right,
}

/// One landmark.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Landmark {
    /// What it is.
    pub kind: LandmarkKind,
    /// Which side.
    pub side: Side,
    /// Where, in metres.
    pub point: [f64; 3],
    /// Set by the session rather than detected.
    pub overridden: bool,
}

impl Landmark {
    /// Label shown in the viewer: `waist`, `knee.left`, ...
    pub fn label(&self) -> String {
        match self.side {
            Side::Centre => self.kind.name().to_string(),
            Side::Left => format!("{}.left", self.kind.name()),
            Side::Right => format!("{}.right", self.kind.name()),
        }
    }

    /// The point as a vector.
    pub fn position(&self) -> DVec3 {
        DVec3::from_array(self.point)
    }
}

/// A session's correction of one landmark.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LandmarkOverride {
    /// Move the landmark (both sides of a pair) to this height; its point is re-measured there.
    Height(f64),
    /// Put the landmark (both sides of a pair mirrored in `x` about the body's middle) here.
    Point(DVec3),
}

/// Landmark detection settings.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LandmarkOptions {
    /// Number of section levels over the body's height. Default value: 320.
    pub levels: usize,
    /// Bisection steps for the crotch and armpit events. Default value: 16.
    pub bisection_steps: usize,
    /// Corrections from the session, applied after detection.
    pub overrides: Vec<(LandmarkKind, LandmarkOverride)>,
}

impl LandmarkOptions {
    /// Default value of [`Self::levels`].
    pub const DEFAULT_LEVELS: usize = 320;

    /// Sets [`Self::levels`].
    #[must_use]
    pub fn with_levels(mut self, levels: usize) -> Self {
        self.levels = levels;
        self
    }

    /// Sets [`Self::overrides`].
    #[must_use]
    pub fn with_overrides(mut self, overrides: Vec<(LandmarkKind, LandmarkOverride)>) -> Self {
        self.overrides = overrides;
        self
    }
}

impl Default for LandmarkOptions {
    fn default() -> Self {
        Self {
            levels: Self::DEFAULT_LEVELS,
            bisection_steps: 16,
            overrides: Vec::new(),
        }
    }
}

/// Why landmarks could not be found.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum LandmarkError {
    /// No two leg sections near the feet.
    #[error("cannot find two legs near the feet: is this a standing body with its legs apart?")]
    NoLegs,
    /// The legs never join.
    #[error("cannot find the crotch: the two leg sections never join")]
    LegsNeverJoin,
    /// No arm beside the torso.
    #[error("cannot find the armpits: no arm section separate from the torso (arms must hang apart from the body)")]
    NoArms,
    /// Crotch and armpit too close for a waist between them.
    #[error("cannot find the waist: the crotch and the armpits are too close together")]
    NoWaist,
    /// No narrowing above the shoulders.
    #[error("cannot find the neck: the torso girth above the armpits never narrows and widens again")]
    NoNeck,
    /// The body is flat or empty in height.
    #[error("the body has no height")]
    NoHeight,
}

/// The detected landmarks and the tracking that found them (used to pick ring loops).
#[derive(Clone, Debug)]
pub struct Landmarks {
    /// Every landmark, in [`LandmarkKind::ALL`] order, left before right.
    pub items: Vec<Landmark>,
    /// The body's middle `x` (area-weighted mean).
    pub mid_x: f64,
    /// Left and right leg centroids `(y, left (x, z), right (x, z))`, feet to crotch.
    pub leg_axis: Vec<(f64, DVec2, DVec2)>,
    /// Torso centroid `(y, (x, z))`, crotch to neck.
    pub torso_axis: Vec<(f64, DVec2)>,
}

impl Landmarks {
    /// The landmark of this kind and side.
    pub fn get(&self, kind: LandmarkKind, side: Side) -> Option<&Landmark> {
        self.items.iter().find(|l| l.kind == kind && l.side == side)
    }

    /// Height of a landmark (the mean of a pair).
    pub fn height(&self, kind: LandmarkKind) -> f64 {
        let ys: Vec<f64> = self
            .items
            .iter()
            .filter(|l| l.kind == kind)
            .map(|l| l.point[1])
            .collect();
        ys.iter().sum::<f64>() / ys.len().max(1) as f64
    }

    /// The neck-base plane through the front-neck and both side-neck points (the garment's
    /// neckline plane); `None` if they are collinear.
    pub fn neck_plane(&self) -> Option<crate::geom::Plane> {
        let points: Vec<DVec3> = [
            self.get(LandmarkKind::FrontNeck, Side::Centre),
            self.get(LandmarkKind::SideNeck, Side::Left),
            self.get(LandmarkKind::SideNeck, Side::Right),
        ]
        .iter()
        .map(|l| l.map(Landmark::position))
        .collect::<Option<Vec<_>>>()?;
        crate::geom::Plane::fit(&points)
    }

    /// Leg centroids at height `y` (nearest tracked level).
    pub fn legs_at(&self, y: f64) -> Option<(DVec2, DVec2)> {
        nearest(&self.leg_axis, y, |e| e.0).map(|e| (e.1, e.2))
    }

    /// Torso centroid at height `y` (nearest tracked level).
    pub fn torso_at(&self, y: f64) -> Option<DVec2> {
        nearest(&self.torso_axis, y, |e| e.0).map(|e| e.1)
    }
}

fn nearest<T>(items: &[T], y: f64, key: impl Fn(&T) -> f64) -> Option<&T> {
    items
        .iter()
        .min_by(|a, b| (key(a) - y).abs().total_cmp(&(key(b) - y).abs()))
}

struct Scan<'a> {
    mesh: &'a TriMesh,
    adjacency: &'a Adjacency,
    floor: f64,
    height: f64,
}

impl Scan<'_> {
    fn loops(&self, y: f64) -> Vec<MeasuredLoop> {
        outer_loops(self.mesh, self.adjacency, y, self.height)
    }

    fn level(&self, k: usize, levels: usize) -> f64 {
        self.floor + self.height * (k as f64 + 0.5) / levels as f64
    }

    /// Largest `t` in `[lo, hi]` where `separate(t)` still holds, given it holds at `lo`
    /// and not at `hi`.
    fn bisect(&self, mut lo: f64, mut hi: f64, steps: usize, separate: impl Fn(&[MeasuredLoop]) -> bool) -> f64 {
        for _ in 0..steps {
            let mid = 0.5 * (lo + hi);
            if separate(&self.loops(mid)) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// The `z` of the front-most crossing of a loop with the vertical plane `x = x0`.
fn front_z_at(l: &MeasuredLoop, x0: f64) -> Option<f64> {
    let n = l.flat.len();
    (0..n)
        .filter_map(|i| {
            let (a, b) = (l.flat[i], l.flat[(i + 1) % n]);
            ((a.x - x0) * (b.x - x0) <= 0.0 && a.x != b.x).then(|| a.y + (x0 - a.x) / (b.x - a.x) * (b.y - a.y))
        })
        .max_by(f64::total_cmp)
}

/// Index of the curve point farthest from the chord between its ends on the side of `side`
/// (a direction in the curve's plane); `None` for fewer than 3 points.
fn corner(curve: &[DVec2], side: DVec2) -> Option<usize> {
    let (first, last) = (*curve.first()?, *curve.last()?);
    let d = last - first;
    let mut normal = DVec2::new(d.y, -d.x).normalize_or_zero();
    if normal.dot(side) < 0.0 {
        normal = -normal;
    }
    (1..curve.len().saturating_sub(1)).max_by(|&a, &b| {
        (curve[a] - first)
            .dot(normal)
            .total_cmp(&(curve[b] - first).dot(normal))
    })
}

fn arg_extreme(values: &[(f64, f64)], range: std::ops::Range<usize>, larger: bool) -> Option<usize> {
    range.filter(|&i| i < values.len()).max_by(|&a, &b| {
        let o = values[a].1.total_cmp(&values[b].1);
        if larger { o } else { o.reverse() }
    })
}

/// Finds the landmarks of a closed, validated body mesh.
///
/// # Failures
/// [`LandmarkError`] when a body event cannot be found (no legs apart, arms touching the
/// torso all the way, no neck).
pub fn detect_landmarks(
    mesh: &TriMesh,
    adjacency: &Adjacency,
    options: &LandmarkOptions,
) -> Result<Landmarks, LandmarkError> {
    let (lo, hi) = mesh.bounds().ok_or(LandmarkError::NoHeight)?;
    let height = hi.y - lo.y;
    if height.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(LandmarkError::NoHeight);
    }
    let (mut weighted_x, mut total_area) = (0.0, 0.0);
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        let area = 0.5 * (b - a).cross(c - a).length();
        weighted_x += area * (a.x + b.x + c.x) / 3.0;
        total_area += area;
    }
    let mid_x = if total_area > 0.0 {
        weighted_x / total_area
    } else {
        0.5 * (lo.x + hi.x)
    };
    let scan = Scan {
        mesh,
        adjacency,
        floor: lo.y,
        height,
    };
    let levels = options.levels.max(40);
    let eps = height * 1e-3;

    // --- Legs, feet up to the crotch.
    let mut k = 0;
    let mut legs: Vec<(f64, MeasuredLoop, MeasuredLoop)> = Vec::new();
    while k < levels / 4 {
        let y = scan.level(k, levels);
        let loops = scan.loops(y);
        let largest = |left: bool| {
            loops
                .iter()
                .filter(|l| (l.centroid.x > mid_x) == left)
                .max_by(|a, b| a.area.total_cmp(&b.area))
                .cloned()
        };
        if let (Some(l), Some(r)) = (largest(true), largest(false)) {
            legs.push((y, l, r));
            break;
        }
        k += 1;
    }
    if legs.is_empty() {
        return Err(LandmarkError::NoLegs);
    }
    let mut joined_at = None;
    for k in k + 1..levels {
        let y = scan.level(k, levels);
        let loops = scan.loops(y);
        let Some((_, pl, pr)) = legs.last() else {
            break;
        };
        let (Some(li), Some(ri)) = (loop_at(&loops, pl.centroid), loop_at(&loops, pr.centroid)) else {
            continue;
        };
        if li == ri {
            joined_at = Some((y, li, loops));
            break;
        }
        legs.push((y, loops[li].clone(), loops[ri].clone()));
    }
    let (joined_y, joined_index, joined_loops) = joined_at.ok_or(LandmarkError::LegsNeverJoin)?;
    let (last_leg_y, last_left, last_right) = legs.last().cloned().ok_or(LandmarkError::NoLegs)?;
    let (cl, cr) = (last_left.centroid, last_right.centroid);
    let crotch_y = scan.bisect(last_leg_y, joined_y, options.bisection_steps, |loops| {
        let (a, b) = (
            loops.iter().position(|l| l.contains(cl)),
            loops.iter().position(|l| l.contains(cr)),
        );
        !(a.is_some() && a == b)
    });

    let leg_girth: Vec<(f64, f64)> = legs
        .iter()
        .map(|(y, l, r)| (*y, 0.5 * (l.tape_girth + r.tape_girth)))
        .collect();
    let n_legs = leg_girth.len();
    // The sole's slices are small too: the ankle is the narrowest leg above the foot's widest.
    let foot_i = arg_extreme(&leg_girth, 0..(n_legs / 4).max(1), true).unwrap_or(0);
    let ankle_i = arg_extreme(&leg_girth, foot_i..(n_legs * 7 / 10).max(foot_i + 1), false).unwrap_or(foot_i);
    // Calf: the first local maximum above the ankle (over a window of 1/15 of the leg);
    // knee: the narrowest leg between it and where the thigh grows past the calf. A leg
    // without a calf bulge falls back on the usual proportion, 45% from ankle to crotch.
    let g: Vec<f64> = leg_girth.iter().map(|e| e.1).collect();
    let window = (n_legs / 15).max(2);
    let calf = (ankle_i + 1..n_legs)
        .find(|&i| i >= window && i + window < n_legs && (i - window..=i + window).all(|j| g[j] <= g[i]));
    let knee_i = calf
        .and_then(|c| {
            let end = (c + 1..n_legs).find(|&j| g[j] > g[c]).unwrap_or(n_legs);
            arg_extreme(&leg_girth, c + 1..end, false)
        })
        .unwrap_or_else(|| {
            let target = leg_girth[ankle_i].0 + 0.45 * (crotch_y - leg_girth[ankle_i].0);
            leg_girth.partition_point(|e| e.0 < target).min(n_legs - 1)
        });

    // --- Torso, crotch up to the neck; arms beside it.
    let mut torso: Vec<(f64, MeasuredLoop)> = vec![(joined_y, joined_loops[joined_index].clone())];
    let mut last_arms: [Option<(usize, DVec2)>; 2] = [None, None];
    let mut k = ((joined_y - lo.y) / height * levels as f64).floor() as usize + 1;
    let mut neck: Option<usize> = None;
    let mut armpit_level: Option<usize> = None;
    let mut running_min: Option<(usize, f64)> = None;
    while k < levels {
        let y = scan.level(k, levels);
        let loops = scan.loops(y);
        let Some((_, prev)) = torso.last() else { break };
        let Some(ti) = loop_at(&loops, prev.centroid) else {
            break;
        };
        let body = loops[ti].clone();
        for (side, slot) in last_arms.iter_mut().enumerate() {
            let arm = loops.iter().enumerate().filter(|(i, l)| {
                *i != ti
                    && l.area >= 0.02 * body.area
                    && if side == 0 {
                        l.centroid.x > body.max.x
                    } else {
                        l.centroid.x < body.min.x
                    }
            });
            if let Some((_, l)) = arm.max_by(|a, b| a.1.area.total_cmp(&b.1.area)) {
                *slot = Some((torso.len(), l.centroid));
            }
        }
        torso.push((y, body));
        let index = torso.len() - 1;
        // The armpit is fixed once no arm has been seen beside the torso for a while.
        let last_seen = last_arms.iter().flatten().map(|a| a.0).max();
        if let Some(seen) = last_seen
            && index > seen
            && armpit_level.is_none()
            && index - seen > levels / 40
        {
            armpit_level = Some(seen);
        }
        if armpit_level.is_some() {
            let g = torso[index].1.tape_girth;
            match running_min {
                Some((_, m)) if g >= m => {
                    if g > 1.1 * m {
                        neck = running_min.map(|r| r.0);
                        break;
                    }
                }
                _ => running_min = Some((index, g)),
            }
        }
        k += 1;
    }
    let armpit_index = armpit_level.ok_or(LandmarkError::NoArms)?;
    let neck_index = neck.ok_or(LandmarkError::NoNeck)?;
    // Armpit height: bisection per arm between the last level with it apart and the next.
    let (below_y, below_loop) = (torso[armpit_index].0, torso[armpit_index].1.clone());
    let above_y = torso
        .get(armpit_index + 1)
        .map_or(below_y + height / levels as f64, |t| t.0);
    let mut armpit_y = above_y;
    for (seen, arm_centroid) in last_arms.iter().flatten() {
        if *seen != armpit_index {
            continue;
        }
        let torso_point = below_loop.centroid;
        let arm_point = *arm_centroid;
        let y = scan.bisect(below_y, above_y, options.bisection_steps, |loops| {
            let t = loops.iter().position(|l| l.contains(torso_point));
            t.is_none() || t != loops.iter().position(|l| l.contains(arm_point))
        });
        armpit_y = armpit_y.min(y);
    }

    let girths: Vec<(f64, f64)> = torso.iter().map(|(y, l)| (*y, l.tape_girth)).collect();
    let span = armpit_y - crotch_y;
    let index_of = |y: f64| girths.partition_point(|g| g.0 < y);
    let waist_i = arg_extreme(
        &girths,
        index_of(crotch_y + 0.25 * span)..index_of(armpit_y - 0.25 * span),
        false,
    )
    .ok_or(LandmarkError::NoWaist)?;
    // Hip: the greatest buttock protrusion (the torso's rearmost point) below the waist.
    // The widest hull is not used: with the legs apart it sits just above the crotch.
    let back: Vec<(f64, f64)> = torso.iter().map(|(y, l)| (*y, -l.min.y)).collect();
    let hip_i = arg_extreme(&back, 1..waist_i, true).unwrap_or(waist_i);
    let bust_i = arg_extreme(&girths, waist_i..index_of(armpit_y), true).unwrap_or(waist_i);

    // --- Shoulder line and neck base from the front silhouette, finely sampled.
    let neck_y = torso[neck_index].0;
    let fine = 200;
    let mut axis = torso[armpit_index].1.centroid;
    let mut silhouette: Vec<(f64, MeasuredLoop)> = Vec::with_capacity(fine + 1);
    for i in 0..=fine {
        let y = armpit_y + eps + (neck_y - armpit_y - eps) * i as f64 / fine as f64;
        let loops = scan.loops(y);
        if let Some(ti) = loop_at(&loops, axis) {
            axis = loops[ti].centroid;
            silhouette.push((y, loops[ti].clone()));
        }
    }
    let side_curve = |left: bool| -> Vec<DVec2> {
        silhouette
            .iter()
            .map(|(y, l)| DVec2::new(if left { l.max.x - mid_x } else { mid_x - l.min.x }, *y))
            .collect()
    };
    let mut shoulder = [DVec3::ZERO; 2];
    let mut side_neck = [DVec3::ZERO; 2];
    for (s, left) in [(0, true), (1, false)] {
        let curve = side_curve(left);
        let ai = corner(&curve, DVec2::new(1.0, 1.0)).ok_or(LandmarkError::NoNeck)?;
        let ni = ai + corner(&curve[ai..], DVec2::new(-1.0, -1.0)).ok_or(LandmarkError::NoNeck)?;
        let extreme = |i: usize| {
            let l = &silhouette[i].1;
            if left { l.extreme(|p| p.x) } else { l.extreme(|p| -p.x) }
        };
        shoulder[s] = extreme(ai);
        side_neck[s] = extreme(ni);
    }
    let front: Vec<(f64, f64)> = torso[bust_i..=neck_index]
        .iter()
        .filter_map(|(y, l)| front_z_at(l, mid_x).map(|z| (*y, z)))
        .collect();
    let front_curve: Vec<DVec2> = front.iter().map(|(y, z)| DVec2::new(*z, *y)).collect();
    let fi = corner(&front_curve, DVec2::new(-1.0, 0.0)).ok_or(LandmarkError::NoNeck)?;
    let front_neck = DVec3::new(mid_x, front[fi].0, front[fi].1);

    let centre_point = |l: &MeasuredLoop| {
        let y = l.y();
        DVec3::new(mid_x, y, front_z_at(l, mid_x).unwrap_or(l.max.y))
    };
    let mut items = Vec::new();
    let mut push = |kind, side, point: DVec3| {
        items.push(Landmark {
            kind,
            side,
            point: point.to_array(),
            overridden: false,
        });
    };
    push(LandmarkKind::Ankle, Side::Left, legs[ankle_i].1.front_point());
    push(LandmarkKind::Ankle, Side::Right, legs[ankle_i].2.front_point());
    push(LandmarkKind::Knee, Side::Left, legs[knee_i].1.front_point());
    push(LandmarkKind::Knee, Side::Right, legs[knee_i].2.front_point());
    push(
        LandmarkKind::Crotch,
        Side::Centre,
        DVec3::new(mid_x, crotch_y, 0.5 * (cl.y + cr.y)),
    );
    push(LandmarkKind::Hip, Side::Centre, centre_point(&torso[hip_i].1));
    push(LandmarkKind::Waist, Side::Centre, centre_point(&torso[waist_i].1));
    push(LandmarkKind::Bust, Side::Centre, centre_point(&torso[bust_i].1));
    let armpit_loop = scan.loops(armpit_y - eps);
    let armpit_point = loop_at(&armpit_loop, below_loop.centroid)
        .map_or(DVec3::new(mid_x, armpit_y, below_loop.max.y), |i| {
            centre_point(&armpit_loop[i])
        });
    push(
        LandmarkKind::Armpit,
        Side::Centre,
        DVec3::new(armpit_point.x, armpit_y, armpit_point.z),
    );
    push(LandmarkKind::Shoulder, Side::Left, shoulder[0]);
    push(LandmarkKind::Shoulder, Side::Right, shoulder[1]);
    push(LandmarkKind::FrontNeck, Side::Centre, front_neck);
    push(LandmarkKind::SideNeck, Side::Left, side_neck[0]);
    push(LandmarkKind::SideNeck, Side::Right, side_neck[1]);
    push(LandmarkKind::Neck, Side::Centre, centre_point(&torso[neck_index].1));
    items.sort_by_key(|l| (LandmarkKind::ALL.iter().position(|k| *k == l.kind), l.side));

    let leg_axis = legs.iter().map(|(y, l, r)| (*y, l.centroid, r.centroid)).collect();
    let torso_axis = torso[..=neck_index].iter().map(|(y, l)| (*y, l.centroid)).collect();
    let mut landmarks = Landmarks {
        items,
        mid_x,
        leg_axis,
        torso_axis,
    };
    apply_overrides(&scan, &mut landmarks, &options.overrides);
    Ok(landmarks)
}

/// Applies session corrections: a height re-measures the landmark's point on the body at
/// that height; a point is taken as given (mirrored for the right side of a pair).
fn apply_overrides(scan: &Scan<'_>, landmarks: &mut Landmarks, overrides: &[(LandmarkKind, LandmarkOverride)]) {
    for &(kind, correction) in overrides {
        let legs = match correction {
            LandmarkOverride::Height(y) => landmarks.legs_at(y),
            LandmarkOverride::Point(p) => landmarks.legs_at(p.y),
        };
        let torso = match correction {
            LandmarkOverride::Height(y) => landmarks.torso_at(y),
            LandmarkOverride::Point(p) => landmarks.torso_at(p.y),
        };
        let mid_x = landmarks.mid_x;
        for item in landmarks.items.iter_mut().filter(|l| l.kind == kind) {
            let point = match correction {
                LandmarkOverride::Point(p) => {
                    if item.side == Side::Right {
                        DVec3::new(2.0 * mid_x - p.x, p.y, p.z)
                    } else {
                        p
                    }
                }
                LandmarkOverride::Height(y) => {
                    let loops = scan.loops(y);
                    let anchor = match (item.side, legs, torso) {
                        (Side::Left, Some((l, _)), _) if matches!(kind, LandmarkKind::Ankle | LandmarkKind::Knee) => {
                            Some(l)
                        }
                        (Side::Right, Some((_, r)), _) if matches!(kind, LandmarkKind::Ankle | LandmarkKind::Knee) => {
                            Some(r)
                        }
                        (_, _, t) => t,
                    };
                    let found = anchor.and_then(|a| loop_at(&loops, a)).map(|i| &loops[i]);
                    match (found, item.side) {
                        (Some(l), Side::Centre) => DVec3::new(mid_x, y, front_z_at(l, mid_x).unwrap_or(l.max.y)),
                        (Some(l), Side::Left)
                            if kind.is_paired() && !matches!(kind, LandmarkKind::Ankle | LandmarkKind::Knee) =>
                        {
                            l.extreme(|p| p.x)
                        }
                        (Some(l), Side::Right)
                            if kind.is_paired() && !matches!(kind, LandmarkKind::Ankle | LandmarkKind::Knee) =>
                        {
                            l.extreme(|p| -p.x)
                        }
                        (Some(l), _) => l.front_point(),
                        (None, _) => DVec3::new(item.point[0], y, item.point[2]),
                    }
                }
            };
            item.point = point.to_array();
            item.overridden = true;
        }
    }
}
