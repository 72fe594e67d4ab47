//! `garment mesh "FILE"`: a garment mesh from another tool as the session's garment. The
//! file is read with everything its tool needs kept, welded and oriented away from the
//! body (each repair noted), its faces grouped into regions (file group by body partition),
//! and its mesh, as M0, collided with the body like a template's M0: certified, with M1,
//! the clearance map, sculpts and cut lines after it. It has no control points or
//! dimensions, so `drag` and `set` do not apply to it.

use std::path::Path;
use std::sync::Arc;

use serde::Serialize;

use crate::import::{ImportNotes, ImportedGarment, face_regions};
use crate::mesh::MeshDocument;
use crate::session::emit::StepScope;
use crate::session::error::StepError;
use crate::session::flow::collide::collide_new;
use crate::session::flow::garment::body_probe;
use crate::session::options::StepContext;
use crate::session::state::{FileGarment, GarmentState, SessionState};

/// What reading the garment found.
#[derive(Serialize)]
struct FileFigures<'a> {
    /// The garment's name.
    garment: &'a str,
    /// The file's vertices, faces, repairs and parts.
    import: &'a ImportNotes,
    /// M0: the welded vertices and the triangles the collision uses.
    m0_vertices: usize,
    m0_faces: usize,
    m0_edges: usize,
    /// The face regions M1's selection judges (file group by body partition).
    regions: &'a [String],
}

/// `garment mesh "FILE" name=N ease=E units=U` (`scale`: metres per file unit).
pub(super) fn run(
    scope: &mut StepScope<'_, '_, '_>,
    state: &mut SessionState,
    cx: &StepContext<'_>,
    (path, name): (&Path, &str),
    ease: f64,
    scale: f64,
) -> Result<(), StepError> {
    let fail = |message: String| StepError::GarmentFile {
        name: name.to_string(),
        path: path.to_path_buf(),
        message,
    };
    let limit = cx.options.input_limit();
    let mut doc = scope
        .timed("garment.read", || MeshDocument::read(path, scale, limit))
        .map_err(|e| fail(e.to_string()))?;
    let frame = cx.options.body_frame;
    if !frame.is_identity() {
        doc.reorient(frame.to_drape());
    }
    let index = body_probe(scope, &state.body, &mut state.probe, cx).index();
    let imported = scope
        .timed("garment.import", || {
            ImportedGarment::new(doc, &state.body.mesh.mesh, index)
        })
        .map_err(|e| fail(e.to_string()))?;
    let (face_region, regions) = face_regions(&imported, index);
    let imported = imported.with_face_patches(&face_region, regions.len());
    for line in imported.notes.lines() {
        scope.note(format!("{name}: {line}"));
    }
    let m = &imported.mesh;
    scope.record(&FileFigures {
        garment: name,
        import: &imported.notes,
        m0_vertices: m.mesh.positions.len(),
        m0_faces: m.mesh.triangles.len(),
        m0_edges: m.edges.len(),
        regions: &regions,
    });
    state.history.clear();
    let standard = imported.mesh.mesh.positions.clone();
    let mut next = GarmentState::from_file(FileGarment {
        name: name.to_string(),
        imported: Arc::new(imported),
        regions,
        ease,
    });
    // M1's stretch rule compares with the garment as read.
    next.standard = Some(Arc::new(standard));
    if let Some(probe) = &state.probe {
        collide_new(scope, &state.body, probe.index(), &mut next, cx);
    }
    state.garment = Some(next);
    Ok(())
}
