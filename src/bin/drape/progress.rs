//! Progress lines on stderr: each step's compute and logging time, solves, refusals and
//! collision figures as they happen, so a long run shows where it is.

use drape::session::{
    CollisionPart, CollisionStage, ConstraintStage, GarmentStage, M1Stage, SinkError, StageInfo, StageSink, StepEnd,
};

use crate::network::solve_line;

/// Prints each stage as it completes, so long runs show progress.
pub(crate) struct Progress;

impl StageSink for Progress {
    fn step_end(&mut self, info: &StageInfo, end: StepEnd<'_>) -> Result<(), SinkError> {
        match end {
            StepEnd::Done(m) => {
                let compute: f64 = m
                    .timings_ms
                    .iter()
                    .filter(|(k, _)| !k.starts_with("log."))
                    .map(|(_, v)| v)
                    .sum();
                let log: f64 = m
                    .timings_ms
                    .iter()
                    .filter(|(k, _)| k.starts_with("log."))
                    .map(|(_, v)| v)
                    .sum();
                // An empty sum is -0.0.
                let (compute, log) = (compute + 0.0, log + 0.0);
                for note in &m.notes {
                    eprintln!("  step {} {note}", info.step);
                }
                eprintln!(
                    "  step {} {:<10} done: compute {compute:8.1} ms, logging {log:6.1} ms",
                    info.step, info.op
                );
            }
            StepEnd::Failed(e) => eprintln!("  step {} {} FAILED: {}", info.step, info.op, e.message()),
            StepEnd::Interrupted { after } => {
                eprintln!("  interrupted by a signal after step {after}: the steps after it did not run");
            }
        }
        Ok(())
    }

    fn constraints(&mut self, info: &StageInfo, stage: ConstraintStage<'_>) -> Result<(), SinkError> {
        match stage {
            ConstraintStage::Solve {
                edit, net, solution, ..
            } => eprintln!("  step {} solve: {}", info.step, solve_line(edit, net, solution)),
            ConstraintStage::Refused { message, .. } => eprintln!("  step {} drag REFUSED: {message}", info.step),
            _ => {}
        }
        Ok(())
    }

    fn sculpt(&mut self, info: &StageInfo, stage: drape::session::SculptStage<'_>) -> Result<(), SinkError> {
        match (stage.outcome, stage.refused) {
            (Some(outcome), None) => eprintln!("  step {} {}", info.step, outcome.summary()),
            (Some(_), Some(why)) => eprintln!("  step {} sculpt REFUSED: {why}", info.step),
            (None, _) => eprintln!("  step {} sculpt taken back", info.step),
        }
        Ok(())
    }

    fn garment(&mut self, info: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        if let GarmentStage::Refused { name, message, .. } = stage {
            eprintln!("  step {} set {name} REFUSED: {message}", info.step);
        }
        Ok(())
    }

    fn collision(&mut self, info: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        if stage.part != CollisionPart::Respond {
            return Ok(());
        }
        let outcome = stage.outcome;
        let c = &outcome.collision;
        let d = &c.detection;
        eprintln!(
            "  step {} collision: {} tested, {} inert, {} patch-skipped; {} hits -> {} moved; after: {} inside, {} crossing edges, {} pierced faces",
            info.step,
            d.tested,
            d.skipped_inert,
            d.skipped_patch,
            d.hits.len(),
            c.responses.len(),
            c.quality.penetrating_vertices,
            c.quality.crossing_edges,
            c.quality.pierced_faces
        );
        if !c.quality.is_clear() {
            eprintln!(
                "  step {} WARNING: the garment is not clear of the body ({} inside, {} crossing, {} faces pierced)",
                info.step, c.quality.penetrating_vertices, c.quality.crossing_edges, c.quality.pierced_faces
            );
        }
        if let Some(v) = &outcome.verify {
            eprintln!(
                "  step {} verify: truth {} inside before, detection missed {} ({}), false hits {} (line-line {}), verdicts the skips changed {}; after: {} inside, {} crossing, {} pierced faces; quality agrees: {}, equals a full check: {}",
                info.step,
                v.inside_before,
                v.missed,
                v.missed_by,
                v.false_hits,
                v.false_line_line,
                v.skips_changed,
                v.inside_after,
                v.crossing_after,
                v.pierced_after,
                v.quality_agrees,
                v.full_check_agrees
            );
        }
        Ok(())
    }

    fn m1(&mut self, info: &StageInfo, stage: M1Stage<'_>) -> Result<(), SinkError> {
        let m1 = &stage.outcome.m1;
        let c = &stage.outcome.collision;
        eprintln!(
            "  step {} M1: {} of {} patches refined, {} faces; {} new vertices tested, {} inside; crossing edges {} -> {}; after: {} inside, {} crossing edges, {} pierced faces; {} cut line(s)",
            info.step,
            m1.selection.count(),
            m1.selection.rules.len(),
            m1.mesh.triangles.len(),
            c.tested,
            c.hits,
            c.crossing_before,
            c.edge_rounds
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", "),
            c.quality.penetrating_vertices,
            c.quality.crossing_edges,
            c.quality.pierced_faces,
            stage.outcome.stored.len()
        );
        Ok(())
    }
}
