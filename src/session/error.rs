//! Why a session stopped, typed: the step that failed and its cause, told apart by kind so
//! the command line can exit with the right code (see [`FailureKind::exit_code`]).

use std::path::PathBuf;

use thiserror::Error;

use crate::body::BodyError;
use crate::constraint::EditError;
use crate::garment::FrameworkError;
use crate::mannequin::MannequinError;

/// What kind of failure stopped a run. The command line's exit codes follow it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FailureKind {
    /// The input cannot be used as given: a malformed session, flag or body file. Exit 2.
    BadInput,
    /// A valid step failed at run time (a section that misses the body, a dimension out of
    /// its range, nothing to undo). Exit 1.
    StepFailed,
    /// drape's own output failed: a file that cannot be written, a viewer that cannot be
    /// reached. Exit 3.
    Internal,
}

impl FailureKind {
    /// The process exit code: 2 bad input, 1 a step failed, 3 internal or I/O failure
    /// (0 is success).
    pub fn exit_code(self) -> u8 {
        match self {
            Self::BadInput => 2,
            Self::StepFailed => 1,
            Self::Internal => 3,
        }
    }
}

/// Why a drag or a replayed drag could not be made; the garment stays as it was.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DragRefusal {
    /// The constraint solver refused the edit (an unknown point, a self-crossing curve).
    #[error(transparent)]
    Solve(#[from] EditError),
    /// The solved curves cannot be surfaced.
    #[error("the edited curves cannot be surfaced: {0}")]
    Surface(#[source] FrameworkError),
    /// The drag went further than the curves can follow: the solve ended with a
    /// constraint still unmet, and the curves no longer close up into patches.
    #[error(
        "the drag goes further than the curves can follow: the {kind} constraint of {curves} is still {residual:.4} {unit} off after the solve: edit refused"
    )]
    Unmet {
        /// The constraint's kind.
        kind: &'static str,
        /// Its curve, or its two curves (`'chest' and 'right_strap'`).
        curves: String,
        /// Its residual after the solve.
        residual: f64,
        /// The residual's unit (m or rad).
        unit: &'static str,
    },
}

/// Why a step failed.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum StepError {
    /// The body cannot be loaded or analysed.
    #[error(transparent)]
    Body(#[from] BodyError),
    /// The mannequin study failed.
    #[error(transparent)]
    Mannequin(#[from] MannequinError),
    /// A section plane misses the body.
    #[error("section '{name}' at y = {y:.4} m cuts nothing: the body spans {lo:.4}..{hi:.4} m")]
    SectionMisses {
        /// The section's name.
        name: String,
        /// Its height, m.
        y: f64,
        /// The body's lowest point, m.
        lo: f64,
        /// The body's highest point, m.
        hi: f64,
    },
    /// The garment's framework cannot be solved (a dimension out of range, a ring that
    /// cannot be cut).
    #[error(transparent)]
    Framework(#[from] FrameworkError),
    /// A drag made before a dimension change cannot be made again after it.
    #[error("replaying drag {index} of {count} after the change: {source}")]
    Replay {
        /// Which drag (1-based).
        index: usize,
        /// Of how many.
        count: usize,
        /// Why it was refused.
        #[source]
        source: Box<DragRefusal>,
    },
    /// A garment step came before any garment was built.
    #[error("no garment to {verb}: a 'garment' step must come first")]
    NoGarment {
        /// What the step wanted to do (`change`, `drag`).
        verb: &'static str,
    },
    /// `drag` or `set` on a garment from a file (the parser refuses it; a step made by hand
    /// may not).
    #[error(
        "the garment '{name}' is a mesh from a file: it has no {what} ('{verb}' needs a garment built from a template; sculpt pushes or pulls its surface)"
    )]
    FileGarment {
        /// The garment's name.
        name: String,
        /// The step (`drag`, `set`).
        verb: &'static str,
        /// What it lacks.
        what: &'static str,
    },
    /// `undo` with nothing to take back.
    #[error("nothing to undo: no drag, set, cut or sculpt step of the current garment ran")]
    NothingToUndo,
    /// `undo` past the oldest edit kept ([`super::RunOptions::undo_limit`]).
    #[error(
        "nothing more to undo: the session keeps the last {0} edits for undo (--undo-limit), and the ones before were dropped"
    )]
    UndoLimit(usize),
    /// `move` names a part no `nurbs` step added (the parser refuses it; a step made by hand
    /// may not).
    #[error("no NURBS part '{0}': add it with a 'nurbs' step first")]
    NoNurbsPart(String),
    /// A NURBS part's file cannot be read or is not a valid surface.
    #[error("NURBS part '{name}' from {}: {message}", path.display())]
    NurbsFile {
        /// The part.
        name: String,
        /// Its file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A garment file (`garment mesh`) cannot be read, or cannot be collided as it is (a
    /// non-manifold edge, other units, apart from the body).
    #[error("garment '{name}' from {}: {message}", path.display())]
    GarmentFile {
        /// The garment's name.
        name: String,
        /// Its file.
        path: PathBuf,
        /// What is wrong (naming the line and column, or the element).
        message: String,
    },
    /// A sculpt names a control point the garment does not have.
    #[error("the garment has no control point '{0}'")]
    NoControlPoint(String),
    /// A sculpt that cannot be made (its pick too far from the garment).
    #[error("sculpt: {0}")]
    Sculpt(#[from] crate::sculpt::SculptError),
    /// A step names a garment the session does not wear (the parser refuses it; a step made
    /// by hand may not).
    #[error("no garment '{name}': the garments worn are {worn}")]
    NoSuchGarment {
        /// The name.
        name: String,
        /// The garments worn, innermost first.
        worn: String,
    },
    /// A garment worn over another is not a surface the layers can keep in order.
    #[error("layers: {0}")]
    Layer(#[from] crate::layers::LayerError),
    /// Sinks failed (the recording, the export), at these stages.
    #[error("{}", join(.0))]
    Sinks(Vec<(&'static str, SinkError)>),
}

fn join(errors: &[(&'static str, SinkError)]) -> String {
    let each: Vec<String> = errors.iter().map(|(stage, e)| format!("{stage}: {e}")).collect();
    each.join("; ")
}

impl StepError {
    /// Bad input, a failed step, or drape's own failure.
    pub fn kind(&self) -> FailureKind {
        match self {
            Self::Body(BodyError::File(_) | BodyError::Mesh(_)) | Self::NurbsFile { .. } | Self::GarmentFile { .. } => {
                FailureKind::BadInput
            }
            Self::Sinks(_) => FailureKind::Internal,
            _ => FailureKind::StepFailed,
        }
    }
}

/// A step that failed at run time, where it was written, and why.
#[derive(Debug, Error)]
#[error("{session}:{line}: step {step} ({op}) failed: {source}")]
pub struct RunError {
    /// Session name.
    pub session: String,
    /// Line of the step (1 for the scene).
    pub line: usize,
    /// Step index (0 is the scene).
    pub step: usize,
    /// Operation keyword (`log` for the sinks' failures, reported after the last step).
    pub op: &'static str,
    /// The cause.
    #[source]
    pub source: StepError,
}

impl RunError {
    /// What went wrong, without the place.
    pub fn message(&self) -> String {
        self.source.to_string()
    }

    /// Bad input, a failed step, or drape's own failure.
    pub fn kind(&self) -> FailureKind {
        self.source.kind()
    }
}

/// Why a sink could not take a stage. These are failures of drape's own output (a file that
/// cannot be written, a viewer that went away), never of the session's input.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SinkError {
    /// A file or folder could not be written.
    #[error("{}: cannot {action}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What was attempted (`write`, `create`, `rename`).
        action: &'static str,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The logging backend (Rerun) failed.
    #[error("{what}: {source}")]
    Backend {
        /// What was being done (`rerun`, `rerun flush`).
        what: &'static str,
        /// The backend's error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
}
