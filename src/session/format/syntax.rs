//! The syntax tree of a session: what a parse produces and the runner reads.

use super::statements::Statement;
use thiserror::Error;

use crate::body::{BodySource, LandmarkKind, LandmarkOverride};
use crate::constraint::{Edit, SolverOptions};
use crate::garment::{ContourKind, Fit, Style, TemplateKind};
use crate::m1::{CutPlane, M1Options};
use crate::mannequin::MannequinOptions;

/// A parse or validation error at a place in the session text.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{file}:{line}:{column}: {message}")]
pub struct ParseError {
    /// Session file name.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// What was expected.
    pub message: String,
}

/// Units of the body file's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Kilometres (a body scaled by 1e-3).
    Kilometres,
    /// Metres.
    Metres,
    /// Centimetres.
    Centimetres,
    /// Millimetres.
    Millimetres,
}

impl Units {
    /// Factor to metres.
    pub fn scale(self) -> f64 {
        match self {
            Self::Kilometres => 1000.0,
            Self::Metres => 1.0,
            Self::Centimetres => 0.01,
            Self::Millimetres => 0.001,
        }
    }

    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Kilometres => "km",
            Self::Metres => "m",
            Self::Centimetres => "cm",
            Self::Millimetres => "mm",
        }
    }
}

/// The scene header.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The body.
    pub body: BodySource,
    /// 1-based line of the `body` statement (1, the header, when the body is the default):
    /// where a scene that fails to load is reported.
    pub body_line: usize,
    /// Units of the body file.
    pub units: Units,
    /// Landmark corrections, in file order.
    pub landmarks: Vec<(LandmarkKind, LandmarkOverride)>,
    /// Constraint solver settings (`solver chains=iterate|split passes=N`).
    pub solver: SolverOptions,
    /// M1 settings (`m1 ...`); `None`: no M1, and none of its work.
    pub m1: Option<M1Options>,
    /// Pattern pieces after every step that collides the garment (`patterns`), when set.
    pub patterns: Option<crate::pattern::PatternOptions>,
    /// What the recording gets (`log detail=all|final|metrics`); `None`: the command
    /// line's choice (all by default).
    pub log: Option<LogDetail>,
}

/// How much of a run goes into its recording.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LogDetail {
    /// Every stage (the default).
    #[default]
    All,
    /// The body's mesh and, per step, the final meshes (M0 after its collision, M1, the cut
    /// lines, the fit map), the metrics and the log.
    Final,
    /// The metrics and the log only.
    Metrics,
}

impl LogDetail {
    /// Name in sessions and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::All => "all",
            Self::Final => "final",
            Self::Metrics => "metrics",
        }
    }

    /// From its name.
    pub fn from_name(name: &str) -> Option<Self> {
        [Self::All, Self::Final, Self::Metrics]
            .into_iter()
            .find(|d| d.name() == name)
    }
}

/// One operation.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// Refine the analytic dress form both ways and measure against its true surface.
    Mannequin(MannequinOptions),
    /// Cut the body with a horizontal plane.
    Section {
        /// Name for the viewer.
        name: String,
        /// Height, m.
        y: f64,
    },
    /// Build a garment from a template: framework and M0.
    Garment {
        /// Template.
        template: TemplateKind,
        /// Sleeves and collar.
        style: Style,
        /// Contour fit.
        fit: Fit,
        /// How contours pass through their points.
        contours: ContourKind,
        /// Segments per anchor arc in M0.
        resolution: usize,
        /// Its name and the garment it is worn over.
        layer: Layer,
    },
    /// A garment mesh from a file (made by another tool) as the garment: its M0 as read,
    /// collided with the body, certified, refined into M1, sculpted and cut like a
    /// template's; it has no control points or dimensions (no `drag`, no `set`).
    GarmentMesh {
        /// The OBJ file.
        path: std::path::PathBuf,
        /// The garment's name (files, the log; default the file's stem).
        name: String,
        /// The gap a moved vertex stands off the skin, m (default
        /// [`crate::import::CheckOptions`]' 0.002).
        ease: f64,
        /// The file's units, as a factor to metres.
        scale: f64,
        /// The garment it is worn over (`over=NAME`), if any.
        over: Option<String>,
    },
    /// Change a dimension of the current garment and solve again.
    Set {
        /// Dimension name.
        name: String,
        /// The change.
        change: Change,
    },
    /// Drag a control point or a whole curve of the current garment.
    Drag(Edit),
    /// Go back to the state before the last garment step.
    Undo,
    /// Draw a style (cut) line on M1 with a plane.
    Cut {
        /// Its name.
        name: String,
        /// The plane.
        plane: CutPlane,
    },
    /// A cut line through picked points of the garment (a seam of its pattern).
    CutThrough {
        /// Its name.
        name: String,
        /// The points, m (each taken to the garment's nearest vertex).
        points: Vec<glam::DVec3>,
    },
    /// Add a NURBS part from a `.nurbs` file, collided with the body and the other parts.
    Nurbs {
        /// Its name.
        name: String,
        /// The file.
        path: std::path::PathBuf,
    },
    /// Move a NURBS part; refused when it would then collide.
    Move {
        /// The part.
        name: String,
        /// Translation, m.
        by: glam::DVec3,
        /// Turn about the vertical through the part's centre, degrees.
        turn_deg: f64,
    },
    /// Push or pull the garment's surface (its latest mesh: a sculpt, M1 or M0), refine
    /// where the drag stretched it and collide what changed with the body.
    Sculpt {
        /// Where the pick is.
        at: SculptAt,
        /// The drag (its `at` is set from [`SculptAt`] when the step runs).
        drag: crate::sculpt::Drag,
        /// Refinement settings.
        options: crate::sculpt::SculptOptions,
    },
}

/// A template garment's name and the garment it is worn over.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// Its name (`name=`, default the template's): what edits name it by (`drag
    /// inner:waist.front`) and what its files and entities are called.
    pub name: String,
    /// The garment it is worn over (`over=NAME`, the outermost so far); `None`: it replaces
    /// every garment so far (a session's first garment, or a new start).
    pub over: Option<String>,
}

/// Where a sculpt picks the garment.
#[derive(Clone, Debug, PartialEq)]
pub enum SculptAt {
    /// A point in space, m (snapped to the nearest point of the garment).
    Point(glam::DVec3),
    /// A control point of the garment (`waist.front`): the sculpt follows it when the
    /// garment is rebuilt, and the session works on any body.
    Control(String),
}

/// A dimension change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Change {
    /// Add to the current value (`+0.04`, `-0.02`).
    By(f64),
    /// Set the value (`0.74`).
    To(f64),
}

impl Change {
    /// The new value from the current one (the dimension's unit: m, or a fraction).
    pub fn apply(self, current: f64) -> f64 {
        match self {
            Self::By(d) => current + d,
            Self::To(v) => v,
        }
    }
}

impl Op {
    /// The statement the operation was written as.
    pub fn statement(&self) -> Statement {
        match self {
            Self::Mannequin(_) => Statement::Mannequin,
            Self::Section { .. } => Statement::Section,
            Self::Garment { .. } | Self::GarmentMesh { .. } => Statement::Garment,
            Self::Set { .. } => Statement::Set,
            Self::Drag(_) => Statement::Drag,
            Self::Undo => Statement::Undo,
            Self::Cut { .. } | Self::CutThrough { .. } => Statement::Cut,
            Self::Nurbs { .. } => Statement::Nurbs,
            Self::Move { .. } => Statement::Move,
            Self::Sculpt { .. } => Statement::Sculpt,
        }
    }

    /// The operation's keyword (from the statement table).
    pub fn keyword(&self) -> &'static str {
        self.statement().keyword()
    }
}

/// A step and where it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// 1-based line in the session file.
    pub line: usize,
    /// What to do.
    pub op: Op,
    /// The garment an edit names (`drag outer:waist.front`); `None`: the outermost one.
    pub garment: Option<String>,
}

/// A parsed, validated session.
#[derive(Clone, Debug, PartialEq)]
pub struct Session {
    /// File name (for messages and the recording's name).
    pub name: String,
    /// Scene header.
    pub scene: Scene,
    /// Steps in order.
    pub steps: Vec<Step>,
}
