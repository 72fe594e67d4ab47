//! `--export DIR`: the body and every mesh a step produced, as OBJ files named by step
//! and mesh (`step00_body.obj`, `step01_mannequin_polar.obj`, `step03_jumpsuit_m0.obj`, ...).
//! A garment's M0 is written after the collision response, and its M1 (when the scene has
//! one) beside it after M1's (`step03_jumpsuit_m1.obj`). A garment read from a file
//! (`garment mesh`) is written as that file: its structure, groups, UVs and materials kept,
//! only the moved vertices changed.

use std::path::PathBuf;

use super::error::SinkError;
use super::stage::{BodyStage, CollisionPart, CollisionStage, M1Stage, StageInfo, StageSink};
use crate::import::ImportedGarment;
use crate::mannequin::MannequinResult;
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
        std::fs::create_dir_all(&dir).map_err(|source| SinkError::Io {
            path: dir.clone(),
            action: "create",
            source,
        })?;
        Ok(Self {
            dir,
            written: Vec::new(),
        })
    }

    fn write(&mut self, info: &StageInfo, mesh_name: &str, mesh: &TriMesh) -> Result<(), SinkError> {
        let header = format!(
            "drape export: step {} ({}), mesh {mesh_name}; metres, y up",
            info.step, info.op
        );
        self.write_text(info, mesh_name, &write_obj(mesh, &header))
    }

    /// A garment read from a file, written back as that file (in its format) with its
    /// collided positions: the vertices the collision moved get new coordinates (and their
    /// normals are made again), everything else is the input's, in the file's own axes.
    fn write_file_garment(
        &mut self,
        info: &StageInfo,
        name: &str,
        file: &ImportedGarment,
        positions: &[glam::DVec3],
    ) -> Result<(), SinkError> {
        let (at, moved) = file.file_positions(positions);
        let bytes = file.doc.write(&at, &moved).map_err(|e| SinkError::Io {
            path: self.dir.join(format!(
                "step{:02}_{name}_m0.{}",
                info.step,
                file.doc.format.extension()
            )),
            action: "write",
            source: std::io::Error::other(e.to_string()),
        })?;
        self.write_file(info, &format!("{name}_m0"), file.doc.format.extension(), &bytes)
    }

    fn write_text(&mut self, info: &StageInfo, mesh_name: &str, text: &str) -> Result<(), SinkError> {
        self.write_file(info, mesh_name, "obj", text.as_bytes())
    }

    fn write_file(&mut self, info: &StageInfo, mesh_name: &str, extension: &str, text: &[u8]) -> Result<(), SinkError> {
        let path = self.dir.join(format!("step{:02}_{mesh_name}.{extension}", info.step));
        // Write then rename, so a failure never leaves half a file under the final name.
        let tmp = path.with_extension(format!("{extension}.partial"));
        std::fs::write(&tmp, text)
            .and_then(|()| std::fs::rename(&tmp, &path))
            .map_err(|source| SinkError::Io {
                path: path.clone(),
                action: "write",
                source,
            })?;
        self.written.push(path);
        Ok(())
    }
}

impl StageSink for ObjExporter {
    fn body(&mut self, info: &StageInfo, stage: BodyStage<'_>) -> Result<(), SinkError> {
        match stage {
            BodyStage::Mesh(body) => self.write(info, "body", &body.mesh),
            _ => Ok(()),
        }
    }

    fn mannequin(&mut self, info: &StageInfo, result: &MannequinResult) -> Result<(), SinkError> {
        for (name, grid) in [("mannequin_polar", &result.polar), ("mannequin_chord", &result.chord)] {
            let mesh = TriMesh {
                positions: grid.positions.clone(),
                triangles: grid.triangles(),
            };
            self.write(info, name, &mesh)?;
        }
        Ok(())
    }

    fn collision(&mut self, info: &StageInfo, stage: CollisionStage<'_>) -> Result<(), SinkError> {
        match stage.part {
            CollisionPart::Respond => {
                let outcome = stage.outcome;
                match &outcome.source {
                    Some(file) => self.write_file_garment(info, &outcome.name, file, &outcome.collision.mesh.positions),
                    None => self.write(info, &format!("{}_m0", outcome.name), &outcome.collision.mesh),
                }
            }
            CollisionPart::Detect => Ok(()),
        }
    }

    fn m1(&mut self, info: &StageInfo, stage: M1Stage<'_>) -> Result<(), SinkError> {
        let mesh = TriMesh {
            positions: stage.outcome.collision.positions.clone(),
            triangles: stage.outcome.m1.mesh.triangles.clone(),
        };
        self.write(info, &format!("{}_m1", stage.m0.name), &mesh)
    }

    fn sculpt(&mut self, info: &StageInfo, stage: crate::session::SculptStage<'_>) -> Result<(), SinkError> {
        match stage.outcome {
            Some(outcome) if stage.refused.is_none() => {
                let name = info
                    .layer
                    .as_ref()
                    .map_or("garment_sculpt".into(), |l| format!("{l}_sculpt"));
                self.write(info, &name, &outcome.mesh())
            }
            _ => Ok(()),
        }
    }
}

/// `--patterns DIR`: every step's pattern pieces as DXF, SVG, JSON and one OBJ per piece
/// (`step03_jumpsuit_patterns.dxf`, `step03_jumpsuit_panel_torso.front_left.obj`, ...).
pub struct PatternExporter {
    dir: PathBuf,
    /// Files written, in order.
    pub written: Vec<PathBuf>,
}

impl PatternExporter {
    /// Exports into `dir` (created when the first pattern is written).
    pub fn new(dir: PathBuf) -> Self {
        Self {
            dir,
            written: Vec::new(),
        }
    }
}

impl StageSink for PatternExporter {
    fn patterns(&mut self, info: &StageInfo, stage: crate::session::stage::PatternStage<'_>) -> Result<(), SinkError> {
        let Ok(pattern) = stage.result else {
            return Ok(());
        };
        let prefix = format!("step{:02}_{}", info.step, stage.garment);
        let files = crate::pattern::export::write_all(&self.dir, &prefix, pattern).map_err(|e| SinkError::Backend {
            what: "pattern export",
            source: Box::new(e),
        })?;
        self.written.extend(files);
        Ok(())
    }
}
