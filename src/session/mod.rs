//! Sessions: the text format and its parser, the stage contract, and the runner that turns
//! steps into stages.
//!
//! * [`format`](mod@format): the session text (syntax tree, lexer, parser).
//! * [`stage`]: what steps emit and the [`StageSink`] trait of whoever takes it.
//! * [`runner`]: [`run_session`], a short driver over the steps in `steps/` (one file per
//!   step kind), with the session's state and undo history in `state`.
//! * [`metrics`]: per-step figures for `--metrics`; [`error`]: why a run stopped.
//! * [`export`]: the OBJ exporter, a sink.

pub mod emit;
pub mod error;
pub mod export;
mod flow;
pub mod format;
pub mod metrics;
pub mod options;
pub mod runner;
pub mod stage;
mod state;
mod steps;
mod wear;

pub use emit::Shortfall;
pub use error::{DragRefusal, FailureKind, RunError, SinkError, StepError};
pub use format::{Change, Layer, LogDetail, Op, ParseError, Scene, SculptAt, Session, Step, Units, parse_session};
pub use metrics::StepMetrics;
pub use options::{DEFAULT_UNDO_LIMIT, RunOptions};
pub use runner::{LiveSession, RunReport, run_session};
pub use stage::{
    BodyStage, CollisionOutcome, CollisionPart, CollisionStage, ConstraintStage, GarmentPart, GarmentStage, LayerPair,
    Layered, M1Outcome, M1Stage, NurbsStage, PatternStage, RingStep, SculptOutcome, SculptStage, SectionCut, Stage,
    StageInfo, StageSink, StepEnd,
};

/// The built-in demo session (the same text as `assets/sessions/demo.drape`).
pub const DEMO_SESSION: &str = include_str!("../../assets/sessions/demo.drape");

/// The name the demo session is reported under.
pub const DEMO_SESSION_NAME: &str = "assets/sessions/demo.drape";
