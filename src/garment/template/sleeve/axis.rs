//! The sleeve's axis: the arm's centre line (shoulder point, elbow, wrist) as a polyline of
//! two segments, lifted from the arm by the sleeve angle (a turn about the shoulder point
//! in the vertical plane through the upper arm), and the points and directions along it by
//! arc length from the shoulder point.

use glam::{DQuat, DVec3};

use crate::body::ArmAxis;

/// A sleeve's axis: shoulder point, elbow and wrist, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SleeveAxis {
    /// The shoulder point (the axis' start), m.
    pub shoulder: DVec3,
    /// The elbow, m.
    pub elbow: DVec3,
    /// The wrist, m.
    pub wrist: DVec3,
}

impl SleeveAxis {
    /// The arm's axis as found on the body; `None` for an arm without an elbow between its
    /// ends.
    pub fn of_arm(arm: &ArmAxis) -> Option<Self> {
        let (first, last) = (arm.points.first()?, arm.points.last()?);
        let elbow = arm.points.get(arm.elbow)?;
        (arm.elbow > 0 && arm.elbow + 1 < arm.points.len()).then_some(Self {
            shoulder: *first,
            elbow: *elbow,
            wrist: *last,
        })
    }

    /// The axis lifted by `angle` radians about the shoulder point, in the vertical plane
    /// through the upper arm (positive: the elbow rises, away from the torso's side).
    pub fn lifted(&self, angle: f64) -> Self {
        let upper = self.elbow - self.shoulder;
        // The turn's axis: horizontal, across the upper arm; its sign makes a positive
        // angle raise the elbow.
        let across = upper.cross(DVec3::Y).normalize_or_zero();
        if across == DVec3::ZERO || angle == 0.0 {
            return *self;
        }
        let q = DQuat::from_axis_angle(across, angle);
        // A positive angle must raise the elbow, a negative one lower it.
        let q = if ((q * upper).y - upper.y) * angle >= 0.0 {
            q
        } else {
            DQuat::from_axis_angle(-across, angle)
        };
        Self {
            shoulder: self.shoulder,
            elbow: self.shoulder + q * upper,
            wrist: self.shoulder + q * (self.wrist - self.shoulder),
        }
    }

    /// Length of the upper arm (shoulder to elbow), m.
    pub fn upper(&self) -> f64 {
        self.shoulder.distance(self.elbow)
    }

    /// Length shoulder to elbow to wrist, m.
    pub fn length(&self) -> f64 {
        self.upper() + self.elbow.distance(self.wrist)
    }

    /// The point `s` along the axis from the shoulder point (beyond the wrist, on along the
    /// forearm), m.
    pub fn point(&self, s: f64) -> DVec3 {
        let upper = self.upper();
        if s <= upper {
            self.shoulder + (self.elbow - self.shoulder).normalize_or_zero() * s
        } else {
            self.elbow + (self.wrist - self.elbow).normalize_or_zero() * (s - upper)
        }
    }

    /// The axis' unit direction at `s` (down the arm): the upper arm's to the elbow, the
    /// forearm's beyond.
    pub fn direction(&self, s: f64) -> DVec3 {
        if s < self.upper() {
            (self.elbow - self.shoulder).normalize_or_zero()
        } else {
            (self.wrist - self.elbow).normalize_or_zero()
        }
    }

    /// Where a point lies along the upper arm, m from the shoulder point (its projection).
    pub fn along_upper(&self, p: DVec3) -> f64 {
        (p - self.shoulder).dot((self.elbow - self.shoulder).normalize_or_zero())
    }
}
