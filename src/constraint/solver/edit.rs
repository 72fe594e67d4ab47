//! Edits of the framework's curves (a control point or a whole curve dragged), the names
//! that can be dragged, and why an edit is refused.

use glam::DVec3;
use thiserror::Error;

use crate::constraint::curves::{self, CurveKind};
use crate::constraint::network::ConstraintNet;
use crate::garment::Framework;

/// Where a drag goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// Move by this vector, m.
    By(DVec3),
    /// Move to this point, m.
    To(DVec3),
}

/// An edit of the framework's curves.
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// Drag a named control point (`waist.front`, `crotch.point`, `left_strap.top`).
    Point {
        /// Point name.
        name: String,
        /// Where to.
        target: Target,
    },
    /// Drag a whole curve by a vector.
    Curve {
        /// Curve name.
        name: String,
        /// The move, m.
        by: DVec3,
    },
}

impl std::fmt::Display for Edit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = |d: DVec3| format!("({:.3}, {:.3}, {:.3})", d.x, d.y, d.z);
        match self {
            Self::Point {
                name,
                target: Target::By(d),
            } => write!(f, "drag {name} by {} m", v(*d)),
            Self::Point {
                name,
                target: Target::To(p),
            } => write!(f, "drag {name} to {} m", v(*p)),
            Self::Curve { name, by } => write!(f, "drag curve {name} by {} m", v(*by)),
        }
    }
}

/// Why an edit cannot be made. The framework is left as it was.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum EditError {
    /// No such control point.
    #[error("unknown control point '{name}': expected one of {known}")]
    UnknownPoint {
        /// Asked.
        name: String,
        /// What exists.
        known: String,
    },
    /// No such curve.
    #[error("unknown curve '{name}': expected one of {known}")]
    UnknownCurve {
        /// Asked.
        name: String,
        /// What exists.
        known: String,
    },
    /// A coordinate is not finite.
    #[error("the drag of '{0}' is not a finite vector")]
    NotFinite(String),
    /// The edit would make a curve cross itself.
    #[error(
        "curve '{curve}' would cross itself (segments {i} and {j} meet at ({x:.4}, {y:.4}, {z:.4}) m, cutting off a loop of {loop_length:.4} m): edit refused",
        x = at.x, y = at.y, z = at.z
    )]
    SelfCrossing {
        /// Curve.
        curve: String,
        /// First segment.
        i: usize,
        /// Second segment.
        j: usize,
        /// Where.
        at: DVec3,
        /// Loop length, m.
        loop_length: f64,
    },
    /// A whole ring dragged out of its band (past the ring next to it on one of its
    /// contours, or off the body's height).
    #[error(
        "ring '{curve}' dragged to y = {y:.4} m would leave its band, {lo:.4}..{hi:.4} m between {below} and {above}: edit refused"
    )]
    OutOfBand {
        /// Ring.
        curve: String,
        /// Where it would go (mean height of its control points), m.
        y: f64,
        /// Lowest allowed, m.
        lo: f64,
        /// Highest allowed, m.
        hi: f64,
        /// What is below (a control point, or the floor).
        below: String,
        /// What is above.
        above: String,
    },
    /// A whole ring of a type-I part (a sleeve's) dragged out of its band along its axis
    /// (past the ring next to it on one of its contours).
    #[error(
        "ring '{curve}' dragged to {at:.4} m along its axis would leave its band, {lo:.4}..{hi:.4} m between {below} and {above} (measured up the sleeve along the ring's normal): edit refused"
    )]
    OutOfAxialBand {
        /// Ring.
        curve: String,
        /// Where it would go (mean of its control points along its plane's normal), m.
        at: f64,
        /// Least allowed, m.
        lo: f64,
        /// Most allowed, m.
        hi: f64,
        /// What is below (towards the hand).
        below: String,
        /// What is above (towards the shoulder).
        above: String,
    },
    /// A whole ring dragged off the part of the body it goes around (the leg a hem goes
    /// round, the torso a waist goes round): that part passes through the ring's plane
    /// outside the ring, so the garment between it and the next ring would pass through the
    /// body.
    #[error(
        "ring '{curve}' dragged by ({:.3}, {:.3}, {:.3}) m would no longer go around the body: the body's section at y = {y:.4} m, centred at (x, z) = ({:.4}, {:.4}) m, would lie {off:.4} m outside it, so the garment would pass through the body: edit refused",
        by.x, by.y, by.z, centre.x, centre.y
    )]
    OffTheBody {
        /// Ring.
        curve: String,
        /// The drag, m.
        by: DVec3,
        /// The height of the section left out, m.
        y: f64,
        /// Its centre `(x, z)`, m.
        centre: glam::DVec2,
        /// How far the centre lies from the dragged ring's control polygon, m.
        off: f64,
    },
    /// A point dragged through the body.
    #[error(
        "'{point}' would pass through the body (in at ({:.4}, {:.4}, {:.4}), out at ({:.4}, {:.4}, {:.4}) m): edit refused",
        entry.x, entry.y, entry.z, exit.x, exit.y, exit.z
    )]
    ThroughBody {
        /// The point (or the apex of a dragged open curve).
        point: String,
        /// Where the path enters the body, m.
        entry: DVec3,
        /// Where it leaves, m.
        exit: DVec3,
    },
    /// A point dragged deep into the body, nearer another part of the surface than the way it
    /// came in.
    #[error(
        "'{point}' would end {depth:.4} m inside the body, nearest its surface at ({:.4}, {:.4}, {:.4}) m, {:.4} m from where it went in: edit refused",
        nearest.x, nearest.y, nearest.z, nearest.distance(*entry)
    )]
    DeepInside {
        /// The point.
        point: String,
        /// How deep, m.
        depth: f64,
        /// Where the path enters the body, m.
        entry: DVec3,
        /// The surface point nearest the end, m.
        nearest: DVec3,
    },
    /// The edit folds a curve onto itself: two consecutive control points would meet.
    #[error(
        "curve '{curve}' would fold onto itself: its control points {} and {} would meet at ({:.4}, {:.4}, {:.4}) m: edit refused",
        points[0], points[1], at.x, at.y, at.z
    )]
    Folds {
        /// Curve.
        curve: String,
        /// The two control points.
        points: [usize; 2],
        /// Where they meet, m.
        at: DVec3,
    },
    /// A curve cannot be refitted.
    #[error("curve '{curve}' cannot be refitted: {message}")]
    Refit {
        /// Curve.
        curve: String,
        /// Why.
        message: String,
    },
}

/// Every draggable point name with its (curve, control point).
pub fn point_names(fw: &Framework, net: &ConstraintNet) -> Vec<(String, usize, usize)> {
    let mut out = Vec::new();
    for (k, c) in net.curves.iter().enumerate() {
        match c.kind {
            CurveKind::Ring => {
                for a in &fw.rings[c.index].anchors {
                    out.push((format!("{}.{}", c.name, a.name), k, a.control));
                }
            }
            CurveKind::Open => {
                let apex = fw.open_curves[c.index].apex_name;
                out.push((format!("{}.{apex}", c.name), k, curves::points(fw, c).len() / 2));
            }
            CurveKind::Contour => {}
        }
    }
    out
}
