//! [`StageSink`]: whoever takes the stages, one method per family, each doing nothing by
//! default.

use super::families::{
    BodyStage, CollisionStage, ConstraintStage, GarmentStage, M1Stage, NurbsStage, PatternStage, SculptStage,
    SectionCut,
};
use super::{Stage, StageInfo, StepEnd};
use crate::mannequin::MannequinResult;
use crate::session::error::SinkError;

/// Takes stages as a session produces them. Every method has a default that does nothing:
/// implement the families you need.
pub trait StageSink {
    /// Takes one stage. The default hands it to the method of its family; a sink that acts
    /// on every stage (the Rerun logger sets its timelines) overrides this and calls
    /// [`Stage::dispatch`] itself.
    fn stage(&mut self, info: &StageInfo, stage: Stage<'_>) -> Result<(), SinkError> {
        stage.dispatch(info, self)
    }

    /// The scene's body stages.
    fn body(&mut self, _info: &StageInfo, _stage: BodyStage<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// The mannequin study.
    fn mannequin(&mut self, _info: &StageInfo, _result: &MannequinResult) -> Result<(), SinkError> {
        Ok(())
    }

    /// The [nurbs] L/T experiment.
    fn nurbs_experiment(&mut self, _info: &StageInfo, _result: &crate::nurbs::Experiment) -> Result<(), SinkError> {
        Ok(())
    }

    /// The NURBS parts.
    fn nurbs(&mut self, _info: &StageInfo, _stage: NurbsStage<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// A body section.
    fn section(&mut self, _info: &StageInfo, _cut: SectionCut<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// The garment stages.
    fn garment(&mut self, _info: &StageInfo, _stage: GarmentStage<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// A garment worn over others.
    fn layers(&mut self, _info: &StageInfo, _layered: &super::Layered) -> Result<(), SinkError> {
        Ok(())
    }

    /// The collision stages.
    fn collision(&mut self, _info: &StageInfo, _stage: CollisionStage<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// The constraint-layer stages.
    fn constraints(&mut self, _info: &StageInfo, _stage: ConstraintStage<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// M1: the display mesh of a step.
    fn m1(&mut self, _info: &StageInfo, _stage: M1Stage<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// The pattern pieces.
    fn patterns(&mut self, _info: &StageInfo, _stage: PatternStage<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// A sculpt of the garment.
    fn sculpt(&mut self, _info: &StageInfo, _stage: SculptStage<'_>) -> Result<(), SinkError> {
        Ok(())
    }

    /// The sculpt comparison.
    fn sculpt_compare(&mut self, _info: &StageInfo, _cmp: &crate::sculpt::Comparison) -> Result<(), SinkError> {
        Ok(())
    }

    /// The end of a step.
    fn step_end(&mut self, _info: &StageInfo, _end: StepEnd<'_>) -> Result<(), SinkError> {
        Ok(())
    }
}

/// A borrowed sink is a sink (so a wrapper can hold `&mut` of another).
impl<S: StageSink + ?Sized> StageSink for &mut S {
    fn stage(&mut self, info: &StageInfo, stage: Stage<'_>) -> Result<(), SinkError> {
        (**self).stage(info, stage)
    }
}

impl Stage<'_> {
    /// Hands the stage to the sink's method for its family.
    pub fn dispatch<S: StageSink + ?Sized>(self, info: &StageInfo, sink: &mut S) -> Result<(), SinkError> {
        match self {
            Self::Body(s) => sink.body(info, s),
            Self::Mannequin(r) => sink.mannequin(info, r),
            Self::NurbsExperiment(r) => sink.nurbs_experiment(info, r),
            Self::Nurbs(s) => sink.nurbs(info, s),
            Self::Section(c) => sink.section(info, c),
            Self::Garment(s) => sink.garment(info, s),
            Self::Collision(s) => sink.collision(info, s),
            Self::Constraints(s) => sink.constraints(info, s),
            Self::M1(s) => sink.m1(info, s),
            Self::Patterns(s) => sink.patterns(info, s),
            Self::Sculpt(s) => sink.sculpt(info, s),
            Self::Layers(l) => sink.layers(info, l),
            Self::SculptCompare(c) => sink.sculpt_compare(info, c),
            Self::Step(e) => sink.step_end(info, e),
        }
    }
}
