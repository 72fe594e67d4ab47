//! Face regions of a garment from a file, where it has no patches: each face goes to the
//! region of its file group and of the body partition (A-G) its centre's height falls in,
//! so that M1's selection rules judge a shoulder apart from a hip even in a one-group file.

use std::collections::BTreeMap;

use super::garment::ImportedGarment;
use crate::collision::BodyIndex;

/// The regions of `garment`'s faces: per triangle its region, and the regions' names
/// (`GROUP/LETTER`; `GROUP` is `default` for the faces before any `g` or `o` line), in
/// the order of (group, partition), the same for the same file and body.
pub fn face_regions(garment: &ImportedGarment, index: &BodyIndex) -> (Vec<u32>, Vec<String>) {
    let mesh = &garment.mesh.mesh;
    let keys: Vec<(u32, usize)> = (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            let y = (a.y + b.y + c.y) / 3.0;
            let group = garment.mesh.face_patch.get(t).copied().unwrap_or(0);
            (group, index.partition_at(y).unwrap_or(usize::MAX))
        })
        .collect();
    let mut ids: BTreeMap<(u32, usize), u32> = keys.iter().map(|k| (*k, 0)).collect();
    let mut names = Vec::with_capacity(ids.len());
    for (k, ((group, partition), id)) in ids.iter_mut().enumerate() {
        *id = k as u32;
        let group = match garment.doc.contents.groups.get(*group as usize).map(String::as_str) {
            None | Some("") => "default",
            Some(g) => g,
        };
        let letter = index.partitions.get(*partition).map_or("-", |p| p.id.letter());
        names.push(format!("{group}/{letter}"));
    }
    let face_region = keys.iter().map(|k| ids[k]).collect();
    (face_region, names)
}
