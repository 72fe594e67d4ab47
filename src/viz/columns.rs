//! Rerun component batches made straight from the logger's words: points and vectors
//! (three `f32` each), triangles (three `u32`) and line strips, each one Arrow array over
//! the words as they are, in place of Rerun's element-by-element serialization of a list of
//! points (a copy into its own types, then into the array). The arrays are those Rerun makes
//! for the same values, bit for bit: the same data types, no nulls.

use std::sync::Arc;

use rerun::external::arrow::array::{Array, ArrayRef, FixedSizeListArray, ListArray, PrimitiveArray};
use rerun::external::arrow::buffer::{OffsetBuffer, ScalarBuffer};
use rerun::external::arrow::datatypes::{DataType, Field, Float32Type, UInt32Type};
use rerun::{ComponentDescriptor, SerializedComponentBatch};

/// Triples of `values` (of type `item`), as Rerun's `Vec3D` and `UVec3D` are laid out.
fn triples(values: ArrayRef, item: DataType) -> FixedSizeListArray {
    FixedSizeListArray::new(Arc::new(Field::new("item", item, false)), 3, values, None)
}

/// `f32`s from their bits.
fn floats(words: impl Iterator<Item = u32>) -> ArrayRef {
    let values: Vec<f32> = words.map(f32::from_bits).collect();
    Arc::new(PrimitiveArray::<Float32Type>::new(ScalarBuffer::from(values), None))
}

/// Points or vectors (`Position3D`, `Vector3D`) from their words: the bits of each one's x, y
/// and z in turn.
pub(super) fn vec3s(descriptor: ComponentDescriptor, words: &[u32]) -> SerializedComponentBatch {
    let values = floats(words.iter().copied());
    SerializedComponentBatch::new(Arc::new(triples(values, DataType::Float32)), descriptor)
}

/// Triangles (`TriangleIndices`) from their words, three corners each.
pub(super) fn triangles(descriptor: ComponentDescriptor, words: &[u32]) -> SerializedComponentBatch {
    let values: ArrayRef = Arc::new(PrimitiveArray::<UInt32Type>::new(
        ScalarBuffer::from(words.to_vec()),
        None,
    ));
    SerializedComponentBatch::new(Arc::new(triples(values, DataType::UInt32)), descriptor)
}

/// Colours (`Color`, RGBA packed with red in the most significant byte), each opaque.
pub(super) fn colors(descriptor: ComponentDescriptor, rgb: impl Iterator<Item = [u8; 3]>) -> SerializedComponentBatch {
    let packed: Vec<u32> = rgb.map(|[r, g, b]| u32::from_be_bytes([r, g, b, 255])).collect();
    let values: ArrayRef = Arc::new(PrimitiveArray::<UInt32Type>::new(ScalarBuffer::from(packed), None));
    SerializedComponentBatch::new(values, descriptor)
}

/// Line strips (`LineStrip3D`): strip `k` passes the points `vertices[start[k]..start[k +
/// 1]]` of `points` (the words of each point's x, y and z in turn).
pub(super) fn strips(
    descriptor: ComponentDescriptor,
    (start, vertices): (&[u32], &[u32]),
    points: &[u32],
) -> SerializedComponentBatch {
    let values = floats((vertices.iter()).flat_map(|&v| {
        let at = 3 * v as usize;
        [points[at], points[at + 1], points[at + 2]]
    }));
    let offsets = OffsetBuffer::<i32>::from_lengths(start.windows(2).map(|w| (w[1] - w[0]) as usize));
    let inner = triples(values, DataType::Float32);
    let item = Arc::new(Field::new("item", inner.data_type().clone(), false));
    let list = ListArray::new(item, offsets, Arc::new(inner), None);
    SerializedComponentBatch::new(Arc::new(list), descriptor)
}

#[cfg(test)]
mod tests {
    use rerun::{LineStrips3D, Mesh3D};

    use super::*;

    fn words(points: &[[f32; 3]]) -> Vec<u32> {
        points.iter().flat_map(|p| p.map(f32::to_bits)).collect()
    }

    /// The arrays equal those Rerun's own serialization makes from the same values, with
    /// awkward floats among them (a negative zero, a subnormal, the largest `f32`).
    #[test]
    fn the_batches_are_those_rerun_makes_of_the_same_values() {
        let points = [
            [0.0, -0.0, 1.5],
            [f32::MIN_POSITIVE / 4.0, f32::MAX, -3.25],
            [7.0, 8.0, 9.0],
            [1e-30, -1e30, 0.1],
        ];
        let w = words(&points);
        let mine = vec3s(Mesh3D::descriptor_vertex_positions(), &w);
        let theirs = Mesh3D::new(points).vertex_positions.expect("positions");
        assert_eq!(mine, theirs);
        let faces = [[0u32, 1, 2], [2, 3, 0], [u32::MAX, 5, 6]];
        let mine = triangles(Mesh3D::descriptor_triangle_indices(), faces.as_flattened());
        let theirs = (Mesh3D::update_fields().with_triangle_indices(faces)).triangle_indices;
        assert_eq!(Some(mine), theirs);
        let rgb = [[0u8, 0, 0], [255, 255, 255], [1, 2, 3], [250, 128, 7]];
        let mine = colors(Mesh3D::descriptor_vertex_colors(), rgb.into_iter());
        let theirs = (Mesh3D::update_fields().with_vertex_colors(rgb)).vertex_colors;
        assert_eq!(Some(mine), theirs);
        // Strips of 3, 0, 1 and 2 points over the points above.
        let (start, vertices) = ([0u32, 3, 3, 4, 6], [0u32, 1, 2, 3, 3, 0]);
        let mine = strips(LineStrips3D::descriptor_strips(), (&start, &vertices), &w);
        let lists: Vec<Vec<[f32; 3]>> = (start.windows(2))
            .map(|s| {
                vertices[s[0] as usize..s[1] as usize]
                    .iter()
                    .map(|&v| points[v as usize])
                    .collect()
            })
            .collect();
        let theirs = LineStrips3D::new(lists).strips.expect("strips");
        assert_eq!(mine, theirs);
    }
}
