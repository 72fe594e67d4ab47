//! Horizontal section rings at the landmark heights: the torso loop, or both leg loops,
//! chosen by the tracked body axes (never the arms).

use glam::{DVec2, DVec3};
use thiserror::Error;

use super::BodyMesh;
use super::landmarks::{LandmarkKind, Landmarks, Side};
use super::profile::{MeasuredLoop, loop_at, outer_loops};

/// A closed body section at a landmark.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BodyRing {
    /// `waist`, `knee.left`, ...
    pub name: String,
    /// The landmark it belongs to (`None` for partition bounds between landmarks).
    pub landmark: Option<LandmarkKind>,
    /// Which side.
    pub side: Side,
    /// Height, m.
    pub y: f64,
    /// Points, counter-clockwise seen from above, front-most first (not repeated at the end).
    #[serde(skip)]
    pub points: Vec<DVec3>,
    /// Perimeter, m.
    pub girth: f64,
    /// Convex hull perimeter (tape measure), m.
    pub tape_girth: f64,
}

impl BodyRing {
    fn from_loop(name: String, landmark: Option<LandmarkKind>, side: Side, l: &MeasuredLoop) -> Self {
        Self {
            name,
            landmark,
            side,
            y: l.y(),
            girth: l.girth,
            tape_girth: l.tape_girth,
            points: l.points.clone(),
        }
    }
}

/// A ring that could not be cut.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("no body section for ring '{ring}' at y = {y:.4} m (the body spans {floor:.4}..{top:.4} m)")]
pub struct RingError {
    /// Ring name.
    pub ring: String,
    /// Requested height, m.
    pub y: f64,
    /// The body's lowest `y`, m.
    pub floor: f64,
    /// The body's highest `y`, m.
    pub top: f64,
}

/// Which loops a ring takes at its height.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RingPick {
    /// The two leg loops.
    Legs,
    /// The torso (or neck) loop.
    Torso,
}

/// The section loops at height `y` picked as `pick` says, named after `name`.
pub fn pick_rings(
    body: &BodyMesh,
    landmarks: &Landmarks,
    (name, kind): (&str, Option<LandmarkKind>),
    y: f64,
    pick: RingPick,
) -> Result<Vec<BodyRing>, RingError> {
    let (lo, hi) = body.mesh.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let scale = hi.y - lo.y;
    let loops = outer_loops(body, y, scale);
    let missing = || RingError {
        ring: name.to_string(),
        y,
        floor: lo.y,
        top: hi.y,
    };
    let take = |anchor: Option<DVec2>| anchor.and_then(|a| loop_at(&loops, a)).map(|i| &loops[i]);
    match pick {
        RingPick::Legs => {
            let (l, r) = landmarks.legs_at(y).ok_or_else(missing)?;
            let (Some(left), Some(right)) = (take(Some(l)), take(Some(r))) else {
                return Err(missing());
            };
            if std::ptr::eq(left, right) {
                return Err(missing());
            }
            Ok(vec![
                BodyRing::from_loop(format!("{name}.left"), kind, Side::Left, left),
                BodyRing::from_loop(format!("{name}.right"), kind, Side::Right, right),
            ])
        }
        RingPick::Torso => {
            let t = take(landmarks.torso_at(y)).ok_or_else(missing)?;
            Ok(vec![BodyRing::from_loop(name.to_string(), kind, Side::Centre, t)])
        }
    }
}

/// The rings at the landmarks: ankle and knee (both legs), crotch (just above the legs
/// join), hip, waist, bust, armpit (just below the arms join) and neck.
pub fn landmark_rings(body: &BodyMesh, landmarks: &Landmarks) -> Result<Vec<BodyRing>, RingError> {
    let (lo, hi) = body.mesh.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let eps = (hi.y - lo.y) * 2e-3;
    let specs = [
        (LandmarkKind::Ankle, 0.0, RingPick::Legs),
        (LandmarkKind::Knee, 0.0, RingPick::Legs),
        (LandmarkKind::Crotch, eps, RingPick::Torso),
        (LandmarkKind::Hip, 0.0, RingPick::Torso),
        (LandmarkKind::Waist, 0.0, RingPick::Torso),
        (LandmarkKind::Bust, 0.0, RingPick::Torso),
        (LandmarkKind::Armpit, -eps, RingPick::Torso),
        (LandmarkKind::Neck, 0.0, RingPick::Torso),
    ];
    let mut rings = Vec::new();
    for (kind, offset, pick) in specs {
        let y = landmarks.height(kind) + offset;
        rings.extend(pick_rings(body, landmarks, (kind.name(), Some(kind)), y, pick)?);
    }
    Ok(rings)
}
