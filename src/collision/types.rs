//! The types the collision's files share: a penetrating vertex ([`Hit`]), a vertex's
//! distance as the quality check measures it ([`VertexDistance`]), and the one tolerance for
//! "inside" ([`SKIN`]). Below every other file of the folder.

use glam::DVec3;

use crate::body::DetectionMethod;
use crate::body::index::{BodyIndex, Nearest};

/// A penetrating vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Garment vertex.
    pub vertex: u32,
    /// Index of its partition in [`BodyIndex::partitions`].
    pub partition: usize,
    /// The test that found it.
    pub method: DetectionMethod,
    /// Depth below the skin, m.
    pub depth: f64,
    /// Nearest body point (point-face) or the crossing in the section (line-line), m (world
    /// frame).
    pub foot: DVec3,
    /// Outward unit body normal there (world frame).
    pub normal: DVec3,
    /// Body triangle (point-face only).
    pub triangle: Option<u32>,
}

/// The one tolerance for "inside", as a fraction of the body's height: a point nearer the
/// body's surface than this (1.7 pm on a 1.7 m body, a thousand times the rounding of a
/// distance) is on the skin, neither inside nor out. The quality check, the brute-force truth
/// ([`super::verify::ground_truth`]) and the response (whose target gap is at least
/// [`super::ResponseOptions::min_ease`] of the height, far outside it, with an ease of 0
/// too) share it.
pub const SKIN: f64 = 1e-12;

/// No body triangle: none within reach, or not measured.
pub const NO_TRIANGLE: u32 = u32::MAX;

/// A vertex's distance as the quality check measures it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexDistance {
    /// Signed distance, m (negative inside; a fifth of the body's height where no body
    /// point is nearer).
    pub signed: f64,
    /// The nearest body triangle ([`NO_TRIANGLE`] where none is within that reach).
    pub triangle: u32,
}

/// How far the quality check looks for the body: a fifth of its height.
pub(crate) fn check_reach(index: &BodyIndex) -> f64 {
    0.2 * index.height
}

impl VertexDistance {
    /// The quality check's distance of `p`, whose nearest body point `nearest` was found
    /// looking at least as far as the check does ([`BodyIndex::nearest`] answers the same
    /// with any reach that holds the winner).
    pub fn from_nearest(index: &BodyIndex, p: DVec3, nearest: Option<&Nearest>) -> Self {
        let reach = check_reach(index);
        match nearest {
            Some(n) if n.distance <= reach => Self {
                signed: n.signed(p),
                triangle: n.triangle,
            },
            _ => Self {
                signed: reach,
                triangle: NO_TRIANGLE,
            },
        }
    }
}
