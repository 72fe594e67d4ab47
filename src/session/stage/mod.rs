//! The stage contract: what a step hands on, and the trait of whoever takes it.
//!
//! A step computes plain data and emits it stage by stage: a [`Stage`] (the data, borrowed)
//! with a [`StageInfo`] (its step, the step's operation, a global stage counter and the
//! stage's name). Whoever wants the stages implements [`StageSink`]: the Rerun logger in
//! [`crate::viz`], the OBJ exporter in [`super::export`], the command line's progress
//! lines, tests. The sink trait has one method per family of stages, each doing nothing by
//! default, so a sink implements only the families it cares about and a new family (a new
//! step kind's stages) changes no existing sink.
//!
//! This module is the only thing the sinks import from the session; they never see the
//! runner.

mod families;
mod sink;

pub use families::{
    BodyStage, CollisionOutcome, CollisionPart, CollisionStage, ConstraintStage, GarmentPart, GarmentStage, LayerPair,
    Layered, M1Outcome, M1Stage, NurbsStage, PatternStage, RingStep, SculptOutcome, SculptStage, SectionCut,
};
pub use sink::StageSink;

use super::error::RunError;
use super::metrics::StepMetrics;
use crate::mannequin::MannequinResult;

/// Where a stage sits: its step and its global stage number.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StageInfo {
    /// Step index (0 is the scene).
    pub step: usize,
    /// The step's operation keyword (`scene`, `garment`, `drag`, ...).
    pub op: &'static str,
    /// Global stage counter, one per stage over the whole session (the `stage` timeline).
    pub stage: u64,
    /// Stage name (`body.load`, `garment.m0`, `collision.response`, ...).
    pub name: &'static str,
    /// The garment the stage is of when it is worn over another (`None`: the innermost or
    /// only garment, or a stage of no garment).
    pub layer: Option<String>,
}

/// The data of one stage, by family.
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub enum Stage<'a> {
    /// The scene's body: mesh, landmarks, rings, partitions.
    Body(BodyStage<'a>),
    /// The mannequin refined and measured against its true surface.
    Mannequin(&'a MannequinResult),
    /// The [nurbs] L/T experiment.
    NurbsExperiment(&'a crate::nurbs::Experiment),
    /// The NURBS parts of a scene after a `nurbs` or `move` step, with their contacts.
    Nurbs(NurbsStage<'a>),
    /// A horizontal section of the body.
    Section(SectionCut<'a>),
    /// The garment framework and its mesh M0.
    Garment(GarmentStage<'a>),
    /// The mesh-layer collision of a step's M0.
    Collision(CollisionStage<'a>),
    /// The constraint layer: the network, a solve, a refusal.
    Constraints(ConstraintStage<'a>),
    /// M1, the display mesh: the refined patches, its collision, the cut lines.
    M1(M1Stage<'a>),
    /// The pattern pieces of a step's garment.
    Patterns(PatternStage<'a>),
    /// A sculpt of the garment: the drag, the adaptive refinement, its collision.
    Sculpt(SculptStage<'a>),
    /// A garment worn over others: the push out in front of them and the gaps.
    Layers(&'a Layered),
    /// The same drag with no, uniform and adaptive subdivision (`drape sculpt-compare`).
    SculptCompare(&'a crate::sculpt::Comparison),
    /// The end of a step: done with its metrics, or failed.
    Step(StepEnd<'a>),
}

/// The end of a step.
#[derive(Clone, Copy, Debug)]
pub enum StepEnd<'a> {
    /// The step finished with these metrics.
    Done(&'a StepMetrics),
    /// The step failed; everything before it stands.
    Failed(&'a RunError),
    /// The run was stopped (a signal) after step `after`; the steps after it did not run.
    Interrupted {
        /// The last step that finished.
        after: usize,
    },
}
