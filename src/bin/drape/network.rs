//! `drape constraints`: the constraint network of every garment a session builds, and each
//! drag's outcome.

use std::path::Path;
use std::process::ExitCode;

use drape::session::{ConstraintStage, RunOptions, SinkError, StageInfo, StageSink, StepEnd, run_session};

use crate::failure::Result;
use crate::load_session;

/// Prints the constraint network of each garment built and each drag's outcome.
pub(crate) struct NetworkPrinter;

impl StageSink for NetworkPrinter {
    fn constraints(&mut self, info: &StageInfo, stage: ConstraintStage<'_>) -> std::result::Result<(), SinkError> {
        match stage {
            ConstraintStage::Network(fw, net) => {
                println!("step {} ({}):", info.step, info.op);
                println!(
                    "{}",
                    net.describe(fw, drape::constraint::SolverOptions::default().tolerance)
                );
            }
            ConstraintStage::Solve {
                edit, net, solution, ..
            } => println!("step {}: {}", info.step, solve_line(edit, net, solution)),
            ConstraintStage::Refused { message, .. } => println!("step {}: refused: {message}", info.step),
            _ => {}
        }
        Ok(())
    }

    fn step_end(&mut self, info: &StageInfo, end: StepEnd<'_>) -> std::result::Result<(), SinkError> {
        if let StepEnd::Failed(e) = end {
            println!("step {} FAILED: {}", info.step, e.message());
        }
        Ok(())
    }
}

pub(crate) fn solve_line(
    edit: &drape::constraint::Edit,
    net: &drape::constraint::ConstraintNet,
    s: &drape::constraint::Solution,
) -> String {
    let worst = s.max_residual();
    let violations = s.violation_lines(net);
    format!(
        "{edit}: {} iteration(s), {} pass(es), {}; largest residual {worst:.2e}{}",
        s.iterations.len(),
        s.passes,
        if s.converged { "converged" } else { "NOT converged" },
        if violations.is_empty() {
            String::new()
        } else {
            format!("; violated: {}", violations.join(", "))
        }
    )
}

pub(crate) fn constraints(path: Option<&Path>) -> Result<ExitCode> {
    let session = load_session(path)?;
    let mut printer = NetworkPrinter;
    let report = run_session(&session, &RunOptions::default(), &mut [&mut printer]);
    Ok(report
        .error
        .map_or(ExitCode::SUCCESS, |e| ExitCode::from(e.kind().exit_code())))
}
