//! Rings kept between builds. A ring is a function of its inputs and the ring settings
//! alone ([`GarmentRing::build`]), so a build (a dimension edit solving the framework again)
//! whose ring has the same inputs, bit for bit, as one the build before made takes that ring
//! as it was built (before any drag moved it) instead of building it again.

use glam::DVec3;

use super::{GarmentRing, RingBuildError, RingInput, RingOptions};
use crate::garment::anchors::AnchorSpec;
use crate::garment::ease::Ease;
use crate::geom::Plane;

/// A ring as a build made it from its inputs, with those inputs.
#[derive(Clone, Debug)]
pub struct BuiltRing {
    name: String,
    plane: Plane,
    raw: Vec<Vec<DVec3>>,
    anchors: Vec<AnchorSpec>,
    mid_x: f64,
    ease: Ease,
    target: Option<f64>,
    options: RingOptions,
    /// The ring built from them.
    pub ring: GarmentRing,
}

impl BuiltRing {
    /// Whether `input` and `options` are the inputs this ring was built from, bit for bit.
    pub fn made_from(&self, input: &RingInput<'_>, options: &RingOptions) -> bool {
        self.name == input.name
            && same_plane(&self.plane, &input.plane)
            && self.anchors == input.anchors
            && self.mid_x.to_bits() == input.mid_x.to_bits()
            && ease_bits(self.ease) == ease_bits(input.ease)
            && self.target.map(f64::to_bits) == input.target.map(f64::to_bits)
            && self.options == *options
            && self.raw.len() == input.raw.len()
            && self.raw.iter().zip(&input.raw).all(|(a, b)| same_points(a, b))
    }
}

/// Builds the ring of `input`, or takes the one of `previous` built from the same inputs:
/// the ring with its inputs, and whether it was taken.
pub fn build_or_keep(
    input: RingInput<'_>,
    options: &RingOptions,
    previous: &[BuiltRing],
) -> Result<(BuiltRing, bool), RingBuildError> {
    let kept = previous.iter().find(|b| b.made_from(&input, options));
    let ring = match kept {
        Some(b) => b.ring.clone(),
        None => GarmentRing::build(&input, options)?,
    };
    let built = BuiltRing {
        name: input.name.to_string(),
        plane: input.plane,
        raw: input.raw,
        anchors: input.anchors.to_vec(),
        mid_x: input.mid_x,
        ease: input.ease,
        target: input.target,
        options: *options,
        ring,
    };
    Ok((built, kept.is_some()))
}

fn same_plane(a: &Plane, b: &Plane) -> bool {
    same_points(&[a.normal], &[b.normal]) && a.offset.to_bits() == b.offset.to_bits()
}

fn same_points(a: &[DVec3], b: &[DVec3]) -> bool {
    let bits = |p: &DVec3| p.to_array().map(f64::to_bits);
    a.len() == b.len() && a.iter().zip(b).all(|(p, q)| bits(p) == bits(q))
}

fn ease_bits(e: Ease) -> (bool, [u64; 4]) {
    match e {
        Ease::Uniform(g) => (false, [g.to_bits(); 4]),
        Ease::PerDirection {
            front,
            left,
            back,
            right,
        } => (true, [front, left, back, right].map(f64::to_bits)),
    }
}
