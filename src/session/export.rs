//! `--export DIR`: the body and every mesh a step produced, as OBJ files named by step
//! and mesh (`step00_body.obj`, `step01_mannequin_polar.obj`, `step03_jumpsuit_m0.obj`, ...).
//! A garment's M0 is written after the collision response.

use std::path::PathBuf;

use super::runner::{SinkError, Stage, StageInfo, StageSink};
use crate::mesh::{TriMesh, write_obj};

/// Writes OBJ files into a folder.
pub struct ObjExporter {
    dir: PathBuf,
    /// Files written, in order.
    pub written: Vec<PathBuf>,
}

impl ObjExporter {
    /// Exports into `dir` (created if missing).
    pub fn new(dir: PathBuf) -> Result<Self, SinkError> {
        std::fs::create_dir_all(&dir).map_err(|e| SinkError(format!("{}: cannot create: {e}", dir.display())))?;
        Ok(Self {
            dir,
            written: Vec::new(),
        })
    }

    fn write(&mut self, info: &StageInfo, mesh_name: &str, mesh: &TriMesh) -> Result<(), SinkError> {
        let path = self.dir.join(format!("step{:02}_{mesh_name}.obj", info.step));
        let header = format!(
            "drape export: step {} ({}), mesh {mesh_name}; metres, y up",
            info.step, info.op
        );
        // Write then rename, so a failure never leaves half a file under the final name.
        let tmp = path.with_extension("obj.partial");
        std::fs::write(&tmp, write_obj(mesh, &header))
            .and_then(|()| std::fs::rename(&tmp, &path))
            .map_err(|e| SinkError(format!("{}: {e}", path.display())))?;
        self.written.push(path);
        Ok(())
    }
}

impl StageSink for ObjExporter {
    fn stage(&mut self, info: &StageInfo, stage: Stage<'_>) -> Result<(), SinkError> {
        match stage {
            Stage::BodyMesh(body) => self.write(info, "body", &body.mesh),
            Stage::Mannequin(result) => {
                for (name, grid) in [("mannequin_polar", &result.polar), ("mannequin_chord", &result.chord)] {
                    let mesh = TriMesh {
                        positions: grid.positions.clone(),
                        triangles: grid.triangles(),
                    };
                    self.write(info, name, &mesh)?;
                }
                Ok(())
            }
            Stage::Collision(outcome, _, crate::session::runner::CollisionPart::Respond) => {
                self.write(info, &format!("{}_m0", outcome.template), &outcome.collision.mesh)
            }
            _ => Ok(()),
        }
    }
}
