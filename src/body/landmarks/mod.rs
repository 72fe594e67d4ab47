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

mod legs;
mod neck;
mod overrides;
mod scan;
mod torso;

use glam::{DVec2, DVec3};
use thiserror::Error;

use super::BodyMesh;
use super::profile::{MeasuredLoop, loop_at};
use crate::mesh::TriMesh;
use scan::{Scan, front_z_at, nearest};

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

    /// The point as a vector, m (world frame).
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
    /// Left and right leg centroids `(y, left (x, z), right (x, z))`, m, feet to crotch.
    pub leg_axis: Vec<(f64, DVec2, DVec2)>,
    /// Torso centroid `(y, (x, z))`, m, crotch to neck.
    pub torso_axis: Vec<(f64, DVec2)>,
}

impl Landmarks {
    /// The landmark of this kind and side.
    pub fn get(&self, kind: LandmarkKind, side: Side) -> Option<&Landmark> {
        self.items.iter().find(|l| l.kind == kind && l.side == side)
    }

    /// Height `y` of a landmark (the mean of a pair), m.
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

/// Finds the landmarks of a closed, validated body mesh.
///
/// # Failures
/// [`LandmarkError`] when a body event cannot be found (no legs apart, arms touching the
/// torso all the way, no neck).
pub fn detect_landmarks(body: &BodyMesh, options: &LandmarkOptions) -> Result<Landmarks, LandmarkError> {
    let mesh = &body.mesh;
    let (lo, hi) = mesh.bounds().ok_or(LandmarkError::NoHeight)?;
    let height = hi.y - lo.y;
    if height.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(LandmarkError::NoHeight);
    }
    let mid_x = mid_plane_x(mesh, lo.x, hi.x);
    let scan = Scan {
        body,
        floor: lo.y,
        height,
    };
    let levels = options.levels.max(40);
    let eps = height * 1e-3;
    let steps = options.bisection_steps;

    // Legs, feet up to the crotch.
    let legs = legs::scan_legs(&scan, levels, mid_x)?;
    let crotch_y = legs::crotch(&scan, &legs, steps)?;
    let leg_girth = legs.girths();
    let ankle_i = legs::ankle(&leg_girth);
    let knee_i = legs::knee(&leg_girth, ankle_i, crotch_y);

    // Torso, crotch up to the neck; arms beside it.
    let (joined_y, joined_index, joined_loops) = &legs.joined;
    let t = torso::scan_torso(&scan, levels, (*joined_y, &joined_loops[*joined_index]))?;
    let armpit_y = torso::armpit(&scan, &t, levels, steps);
    let girths = t.girths();
    let waist_i = torso::waist(&girths, crotch_y, armpit_y)?;
    let hip_i = torso::hip(&t.torso, waist_i);
    let bust_i = torso::bust(&girths, waist_i, armpit_y);

    // Shoulder line and neck base from the silhouettes.
    let (torso, neck_index) = (&t.torso, t.neck_index);
    let below_loop = &torso[t.armpit_index].1;
    let (shoulder, side_neck) =
        neck::shoulders_and_side_necks(&scan, below_loop.centroid, (armpit_y, torso[neck_index].0, eps), mid_x)?;
    let front_neck = neck::front_neck(&torso[bust_i..=neck_index], mid_x)?;

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
    let leg = &legs.legs;
    push(LandmarkKind::Ankle, Side::Left, leg[ankle_i].1.front_point());
    push(LandmarkKind::Ankle, Side::Right, leg[ankle_i].2.front_point());
    push(LandmarkKind::Knee, Side::Left, leg[knee_i].1.front_point());
    push(LandmarkKind::Knee, Side::Right, leg[knee_i].2.front_point());
    let (cl, cr) = leg
        .last()
        .map_or((DVec2::ZERO, DVec2::ZERO), |(_, l, r)| (l.centroid, r.centroid));
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

    let leg_axis = leg.iter().map(|(y, l, r)| (*y, l.centroid, r.centroid)).collect();
    let torso_axis = torso[..=neck_index].iter().map(|(y, l)| (*y, l.centroid)).collect();
    let mut landmarks = Landmarks {
        items,
        mid_x,
        leg_axis,
        torso_axis,
    };
    overrides::apply_overrides(&scan, &mut landmarks, &options.overrides);
    Ok(landmarks)
}

/// The body's mid-plane `x`: the area-weighted mean `x` of its surface (the middle of its
/// bounds `lo_x..hi_x` for a mesh without area), m.
fn mid_plane_x(mesh: &TriMesh, lo_x: f64, hi_x: f64) -> f64 {
    let (mut weighted_x, mut total_area) = (0.0, 0.0);
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        let area = 0.5 * (b - a).cross(c - a).length();
        weighted_x += area * (a.x + b.x + c.x) / 3.0;
        total_area += area;
    }
    if total_area > 0.0 {
        weighted_x / total_area
    } else {
        0.5 * (lo_x + hi_x)
    }
}
