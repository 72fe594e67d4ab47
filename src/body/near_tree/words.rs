//! Nodes stored as one byte string of their 32-bit words (little-endian), so that reading
//! them back is a copy, not a decode of every field.

use glam::{Vec3, Vec4};
use serde::de::{Error, SeqAccess, Visitor};
use serde::{Deserializer, Serializer};

use super::{Node, Pair, Wide};

/// A node as a fixed number of words.
pub trait Words: Sized {
    /// How many.
    const N: usize;
    /// Its words.
    fn put(&self, out: &mut Vec<u32>);
    /// From its words (`w.len() == N`).
    fn take(w: &[u32]) -> Self;
}

fn f(w: u32) -> f32 {
    f32::from_bits(w)
}

impl Words for Pair {
    const N: usize = 16;
    fn put(&self, out: &mut Vec<u32>) {
        for n in &self.0 {
            out.extend(n.lo.to_array().map(f32::to_bits));
            out.push(n.first);
            out.extend(n.hi.to_array().map(f32::to_bits));
            out.push(n.count);
        }
    }
    fn take(w: &[u32]) -> Self {
        let node = |w: &[u32]| Node {
            lo: Vec3::new(f(w[0]), f(w[1]), f(w[2])),
            first: w[3],
            hi: Vec3::new(f(w[4]), f(w[5]), f(w[6])),
            count: w[7],
        };
        Pair([node(&w[..8]), node(&w[8..])])
    }
}

impl Words for Wide {
    const N: usize = 28;
    fn put(&self, out: &mut Vec<u32>) {
        for v in self.lo.iter().chain(&self.hi) {
            out.extend(v.to_array().map(f32::to_bits));
        }
        out.extend(self.child);
    }
    fn take(w: &[u32]) -> Self {
        let v = |k: usize| Vec4::new(f(w[4 * k]), f(w[4 * k + 1]), f(w[4 * k + 2]), f(w[4 * k + 3]));
        Wide {
            lo: [v(0), v(1), v(2)],
            hi: [v(3), v(4), v(5)],
            child: [w[24], w[25], w[26], w[27]],
        }
    }
}

pub fn serialize<T: Words, S: Serializer>(nodes: &[T], s: S) -> Result<S::Ok, S::Error> {
    let mut w = Vec::with_capacity(nodes.len() * T::N);
    for n in nodes {
        n.put(&mut w);
    }
    let bytes: Vec<u8> = w.into_iter().flat_map(u32::to_le_bytes).collect();
    s.serialize_bytes(&bytes)
}

/// Decodes the nodes straight from the byte string (one allocation: the nodes').
struct Nodes<T>(std::marker::PhantomData<T>);

fn decode<T: Words, E: Error>(bytes: &[u8]) -> Result<Vec<T>, E> {
    if !bytes.len().is_multiple_of(4 * T::N) {
        return Err(E::custom(format!("{} bytes of tree nodes", bytes.len())));
    }
    let mut w = vec![0u32; T::N];
    Ok(bytes
        .chunks_exact(4 * T::N)
        .map(|node| {
            for (x, b) in w.iter_mut().zip(node.chunks_exact(4)) {
                *x = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            }
            T::take(&w)
        })
        .collect())
}

impl<'de, T: Words> Visitor<'de> for Nodes<T> {
    type Value = Vec<T>;
    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a byte string of tree nodes")
    }
    fn visit_bytes<E: Error>(self, v: &[u8]) -> Result<Vec<T>, E> {
        decode(v)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
        let mut bytes = Vec::new();
        while let Some(b) = seq.next_element()? {
            bytes.push(b);
        }
        decode(&bytes)
    }
}

pub fn deserialize<'de, T: Words, D: Deserializer<'de>>(d: D) -> Result<Vec<T>, D::Error> {
    d.deserialize_bytes(Nodes(std::marker::PhantomData))
}
