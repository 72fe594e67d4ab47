//! Sessions: the text format, its parser, and the runner that turns steps into stages.

pub mod export;
pub mod format;
pub mod metrics;
pub mod runner;

pub use format::{Change, Op, ParseError, Scene, Session, Step, Units, parse_session};
pub use metrics::StepMetrics;
pub use runner::{
    CollisionOutcome, CollisionPart, GarmentPart, RingStep, RunError, RunOptions, RunReport, Stage, StageInfo,
    StageSink, run_session,
};

/// The built-in demo session (the same text as `assets/sessions/demo.drape`).
pub const DEMO_SESSION: &str = include_str!("../../assets/sessions/demo.drape");

/// The name the demo session is reported under.
pub const DEMO_SESSION_NAME: &str = "assets/sessions/demo.drape";
