//! What a stress run watches while a session runs: every mesh and curve a step hands to the
//! sinks checked for NaN and infinite values, each constraint solve's outcome and residual,
//! and each step's compute time.

use super::verified::Verified;
use crate::session::{
    CollisionPart, CollisionStage, ConstraintStage, GarmentPart, GarmentStage, M1Stage, SinkError, StageInfo,
    StageSink, StepEnd,
};

/// The timings of `--verify`'s checks: not the step's own work, left out of its time.
const VERIFICATION: [&str; 3] = ["collision.verify", "collision.quality_full", "m1.verify"];

/// A non-finite value seen in a step's output.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NonFinite {
    /// Step index.
    pub step: usize,
    /// Where: the stage and the array.
    pub place: String,
}

/// A constraint solve's outcome.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOutcome {
    /// Step index.
    pub step: usize,
    /// The last pass broke nothing.
    pub converged: bool,
    /// Passes made.
    pub passes: usize,
    /// Largest residual at the end (m or rad, by constraint kind).
    pub max_residual: f64,
}

/// The watcher: a [`StageSink`] that keeps what a stress report needs.
#[derive(Clone, Debug, Default)]
pub struct Watch {
    /// Non-finite values, in the order seen.
    pub non_finite: Vec<NonFinite>,
    /// Every solve.
    pub solves: Vec<SolveOutcome>,
    /// Compute milliseconds of every finished step after the scene (logging and `--verify`'s
    /// checks excluded).
    pub step_ms: Vec<f64>,
    /// The collisions checked against the truth (runs with `verify`).
    pub verified: Verified,
    /// The verification of the collision the current step showed.
    pending: Option<Verified>,
}

fn check<'a>(out: &mut Vec<NonFinite>, step: usize, place: &str, values: impl IntoIterator<Item = &'a glam::DVec3>) {
    if values.into_iter().any(|p| !p.is_finite()) {
        out.push(NonFinite {
            step,
            place: place.to_string(),
        });
    }
}

impl StageSink for Watch {
    fn garment(&mut self, info: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        if let GarmentStage::Part(fw, part) = stage {
            match part {
                GarmentPart::Curves => {
                    for ring in &fw.rings {
                        if !(ring.girth.is_finite() && ring.spline.length().is_finite()) {
                            self.non_finite.push(NonFinite {
                                step: info.step,
                                place: format!("garment.curves ring {}", ring.name),
                            });
                        }
                    }
                }
                GarmentPart::Mesh => {
                    check(
                        &mut self.non_finite,
                        info.step,
                        "garment.m0 positions",
                        &fw.m0.mesh.positions,
                    );
                }
                _ => {}
            }
        }
        Ok(())
    }

    fn collision(&mut self, info: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        let c = &stage.outcome.collision;
        match stage.part {
            CollisionPart::Detect => check(
                &mut self.non_finite,
                info.step,
                "collision input positions",
                &stage.outcome.garment.mesh.positions,
            ),
            CollisionPart::Respond => {
                check(
                    &mut self.non_finite,
                    info.step,
                    "collision output positions",
                    &c.mesh.positions,
                );
                // Counted at the step's end, if the step made it (an undo shows the
                // collision of an earlier step again).
                self.pending = stage.outcome.verify.as_ref().map(|v| Verified {
                    collisions: 1,
                    vertices: c.mesh.positions.len(),
                    edges: stage.outcome.garment.edges.len(),
                    inside: v.inside_before,
                    missed: v.missed,
                    missed_by: v.missed_by,
                    skips_changed: v.skips_changed,
                    false_hits: v.false_hits,
                    wrong_quality: if v.quality_agrees { vec![] } else { vec![info.step] },
                    partial_differs: if v.full_check_agrees { vec![] } else { vec![info.step] },
                    quality_ms: Vec::new(),
                    full_quality_ms: Vec::new(),
                });
                let q = &c.quality;
                if !(q.max_depth_m.is_finite() && q.max_move_m.is_finite() && q.max_stretch.is_finite()) {
                    self.non_finite.push(NonFinite {
                        step: info.step,
                        place: "collision quality figures".into(),
                    });
                }
            }
        }
        Ok(())
    }

    fn m1(&mut self, info: &StageInfo, stage: M1Stage<'_>) -> Result<(), SinkError> {
        check(
            &mut self.non_finite,
            info.step,
            "m1 positions",
            &stage.outcome.collision.positions,
        );
        Ok(())
    }

    fn constraints(&mut self, info: &StageInfo, stage: ConstraintStage<'_>) -> Result<(), SinkError> {
        if let ConstraintStage::Solve { solution, .. } = stage {
            let max_residual = solution.max_residual();
            if !max_residual.is_finite() {
                self.non_finite.push(NonFinite {
                    step: info.step,
                    place: "constraint residuals".into(),
                });
            }
            self.solves.push(SolveOutcome {
                step: info.step,
                converged: solution.converged,
                passes: solution.passes,
                max_residual,
            });
        }
        Ok(())
    }

    fn step_end(&mut self, info: &StageInfo, end: StepEnd<'_>) -> Result<(), SinkError> {
        let pending = self.pending.take();
        if let StepEnd::Done(m) = end
            && info.step > 0
        {
            let ms: f64 = m
                .timings_ms
                .iter()
                .filter(|(k, _)| !k.starts_with("log.") && !VERIFICATION.contains(&k.as_str()))
                .map(|(_, v)| v)
                .sum();
            self.step_ms.push(ms);
            if let (Some(mut p), Some(step), Some(full)) = (
                pending,
                m.timings_ms.get("collision.quality"),
                m.timings_ms.get("collision.quality_full"),
            ) {
                p.quality_ms.push(*step);
                p.full_quality_ms.push(*full);
                self.verified.absorb(p);
            }
        }
        Ok(())
    }
}
