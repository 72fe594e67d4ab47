//! A sink that keeps what a session's steps made: per step the pattern, the collided mesh
//! and the framework it came from (to cut the same pattern again), and the refused
//! patterns. Shared by the pattern tests and the pattern benchmark (`#[path]`).

use std::path::Path;

use drape::garment::Framework;
use drape::pattern::{CutLine, Pattern, PatternInput};
use drape::session::{
    CollisionPart, CollisionStage, GarmentPart, GarmentStage, PatternStage, RunOptions, SinkError, StageInfo,
    StageSink, parse_session, run_session,
};
use glam::DVec3;

/// A step's collided mesh: step, positions, triangles, the patch of each triangle, the
/// positions before the collision.
pub type StepMesh = (usize, Vec<DVec3>, Vec<[u32; 3]>, Vec<u32>, Vec<DVec3>);

/// What a session's steps made.
#[derive(Default)]
pub struct Collect {
    /// Per step, its pattern.
    pub patterns: Vec<(usize, Pattern)>,
    /// Per step, its collided mesh.
    pub meshes: Vec<StepMesh>,
    /// Per step, the framework its mesh came from.
    pub frameworks: Vec<(usize, Framework)>,
    /// The refused patterns, with their step.
    pub failures: Vec<String>,
}

impl Collect {
    /// The framework of the last mesh made at or before `step`.
    pub fn framework(&self, step: usize) -> &Framework {
        &self
            .frameworks
            .iter()
            .rev()
            .find(|f| f.0 <= step)
            .expect("a framework")
            .1
    }

    /// The pattern input of the last collided mesh at or before `step`, with `curves` (its
    /// framework's `curve_polylines()`) and `cuts`.
    pub fn input<'a>(
        &'a self,
        step: usize,
        curves: &'a [(String, Vec<DVec3>)],
        cuts: &'a [CutLine],
    ) -> PatternInput<'a> {
        let (_, positions, triangles, face_patch, surfaced) =
            self.meshes.iter().rev().find(|m| m.0 <= step).expect("a collided mesh");
        let fw = self.framework(step);
        PatternInput {
            template: fw.template.name(),
            positions,
            triangles,
            face_patch,
            surfaced: Some(surfaced),
            patch_names: &fw.m0.patch_names,
            curves,
            cuts,
        }
    }
}

impl StageSink for Collect {
    fn patterns(&mut self, info: &StageInfo, stage: PatternStage<'_>) -> Result<(), SinkError> {
        match stage.result {
            Ok(p) => self.patterns.push((info.step, p.clone())),
            Err(e) => self.failures.push(format!("step {}: {e}", info.step)),
        }
        Ok(())
    }

    fn collision(&mut self, info: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        if stage.part == CollisionPart::Respond {
            let o = stage.outcome;
            self.meshes.push((
                info.step,
                o.collision.mesh.positions.clone(),
                o.garment.mesh.triangles.clone(),
                o.garment.face_patch.to_vec(),
                o.garment.mesh.positions.clone(),
            ));
        }
        Ok(())
    }

    fn garment(&mut self, info: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        if let GarmentStage::Part(fw, GarmentPart::Mesh) = stage {
            self.frameworks.push((info.step, fw.clone()));
        }
        Ok(())
    }
}

/// Runs a session (on `body` instead of its own, if given) into a [`Collect`].
pub fn run(text: &str, body: Option<&Path>) -> Collect {
    let session = parse_session(text, "patterns.drape", Path::new(".")).expect("parses");
    let options = RunOptions {
        body_override: body.map(Path::to_path_buf),
        ..RunOptions::default()
    };
    let mut collect = Collect::default();
    let report = run_session(&session, &options, &mut [&mut collect]);
    assert!(report.error.is_none(), "{:?}", report.error);
    collect
}
