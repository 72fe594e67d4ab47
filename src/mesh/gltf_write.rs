//! A glTF document written back for a [`super::MeshDocument`]: only the moved vertices'
//! bytes, their normals and their accessors' bounds changed, the buffers joined into one.

use base64::Engine as _;
use glam::DMat3;
use serde_json::{Value, json};

use super::MeshFileError;
use super::file_parts::{MeshFormat, Moved};
use super::gltf_read::{GltfKeep, error};

/// The document again, as `.glb` or `.gltf` (`format`), with the vertices `job.moved` at
/// `job.positions`: their bytes (and their normals') written anew in their node's frame,
/// the bounds of their position accessors recomputed, the buffers joined into one (the
/// GLB's BIN chunk, or a `data:` URI in a `.gltf`); every other value as read.
pub(super) fn write(keep: &GltfKeep, format: MeshFormat, job: &Moved) -> Result<Vec<u8>, MeshFileError> {
    let mut buffers = keep.buffers.clone();
    let mut json = keep.json.clone();
    for block in &keep.blocks {
        let range = block.first..block.first + block.count;
        if !job.moved[range.clone()].iter().any(|&m| m) {
            continue;
        }
        let to_local = block.world.inverse();
        let normal_to_local = DMat3::from_mat4(block.world).transpose();
        let Some(l) = keep.layouts[block.accessor] else {
            continue;
        };
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for (i, v) in range.enumerate() {
            let at = l.offset + i * l.stride;
            if job.moved[v] {
                let q = to_local.transform_point3(job.positions[v]).as_vec3();
                put(&mut buffers[l.buffer], at, q.to_array());
                if let Some(n) = job.smooth[v] {
                    let n = (normal_to_local * n).normalize_or_zero().as_vec3().to_array();
                    for &na in &block.normals {
                        if let Some(nl) = keep.layouts[na] {
                            put(&mut buffers[nl.buffer], nl.offset + i * nl.stride, n);
                        }
                    }
                }
            }
            let b = &buffers[l.buffer][at..at + 12];
            for k in 0..3 {
                let x = f32::from_le_bytes([b[4 * k], b[4 * k + 1], b[4 * k + 2], b[4 * k + 3]]);
                lo[k] = lo[k].min(x);
                hi[k] = hi[k].max(x);
            }
        }
        if let Some(accessor) = json.pointer_mut(&format!("/accessors/{}", block.accessor)) {
            accessor["min"] = json!(lo);
            accessor["max"] = json!(hi);
        }
    }
    let bin = join_buffers(&mut json, &buffers);
    let out = match format {
        MeshFormat::Glb => {
            let text = serde_json::to_vec(&json).map_err(|e| error(job.name, e.to_string()))?;
            gltf::binary::Glb {
                header: gltf::binary::Header {
                    magic: *b"glTF",
                    version: 2,
                    length: 0,
                },
                json: text.into(),
                bin: Some(bin.into()),
            }
            .to_vec()
            .map_err(|e| error(job.name, format!("writing: {e}")))?
        }
        _ => {
            let encoded = base64::engine::general_purpose::STANDARD.encode(&bin);
            json["buffers"][0]["uri"] = json!(format!("data:application/octet-stream;base64,{encoded}"));
            serde_json::to_vec_pretty(&json).map_err(|e| error(job.name, e.to_string()))?
        }
    };
    Ok(out)
}

/// Writes three floats at byte `at` (in range: it was read there).
fn put(buffer: &mut [u8], at: usize, v: [f32; 3]) {
    for (k, x) in v.into_iter().enumerate() {
        buffer[at + 4 * k..at + 4 * k + 4].copy_from_slice(&x.to_le_bytes());
    }
}

/// Joins `buffers` into one (each from a multiple of four bytes), the buffer views moved
/// to it; `json` keeps one buffer (the first's name and extras, no URI).
fn join_buffers(json: &mut Value, buffers: &[Vec<u8>]) -> Vec<u8> {
    let mut starts = Vec::with_capacity(buffers.len());
    let mut bin = Vec::new();
    for b in buffers {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        starts.push(bin.len());
        bin.extend_from_slice(b);
    }
    if let Some(views) = json.get_mut("bufferViews").and_then(Value::as_array_mut) {
        for view in views {
            let b = view["buffer"].as_u64().unwrap_or(0) as usize;
            let offset = view.get("byteOffset").and_then(Value::as_u64).unwrap_or(0);
            view["buffer"] = json!(0);
            view["byteOffset"] = json!(offset + starts.get(b).copied().unwrap_or(0) as u64);
        }
    }
    let mut first = json.pointer("/buffers/0").cloned().unwrap_or_else(|| json!({}));
    if let Some(o) = first.as_object_mut() {
        o.remove("uri");
        o.insert("byteLength".into(), json!(bin.len()));
    }
    json["buffers"] = json!([first]);
    bin
}
