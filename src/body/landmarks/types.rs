//! The landmarks' types: their kinds, a found landmark, the session's overrides, the
//! settings, the errors and the set of a body's landmarks.

use glam::{DVec2, DVec3};
use thiserror::Error;

use super::scan::nearest;

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
    /// The arm's bend between shoulder and wrist (the outer point of its section there).
    Elbow,
    /// Narrowest arm girth above the hand (the outer point of its section there).
    Wrist,
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

    /// The arm's kinds, shoulder to hand (found when an arm hangs apart from the body; not in
    /// [`Self::ALL`], whose order is the heights').
    pub const ARMS: [Self; 2] = [Self::Elbow, Self::Wrist];

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
            Self::Elbow => "elbow",
            Self::Wrist => "wrist",
        }
    }

    /// The kind with this session name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().chain(Self::ARMS).find(|k| k.name() == name)
    }

    /// Whether the landmark comes as a left/right pair.
    pub fn is_paired(self) -> bool {
        matches!(
            self,
            Self::Ankle | Self::Knee | Self::SideNeck | Self::Shoulder | Self::Elbow | Self::Wrist
        )
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
    /// Each arm's centre line (left, right): the shoulder point, then its sections' centroids
    /// down to the wrist; empty where the arm was not found.
    pub arm_axis: [ArmAxis; 2],
}

/// An arm's centre line, the sleeve's axis.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ArmAxis {
    /// The shoulder point, then the centroids of the arm's sections down to the wrist, m.
    pub points: Vec<DVec3>,
    /// The elbow's point on it (index into `points`).
    pub elbow: usize,
}

impl ArmAxis {
    /// The line's direction at point `k` (unit; zero on a line of one point).
    pub fn direction(&self, k: usize) -> DVec3 {
        let n = self.points.len();
        if n < 2 {
            return DVec3::ZERO;
        }
        let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
        (self.points[b] - self.points[a]).normalize_or_zero()
    }

    /// Its length along the line, shoulder to wrist, m.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| w[0].distance(w[1])).sum()
    }
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
