//! What a jumpsuit is cut as: with or without its legs (the shirt), its sleeves and collar.

use crate::garment::model::{Collar, Sleeves, Style};

/// Rings of the jumpsuit, top to bottom.
pub const RINGS: [&str; 11] = [
    "neckline",
    "chest",
    "bust",
    "waist",
    "hip",
    "left_thigh",
    "right_thigh",
    "left_knee",
    "right_knee",
    "left_hem",
    "right_hem",
];

/// Contours of the jumpsuit.
pub const CONTOURS: [&str; 10] = [
    "centre_front",
    "centre_back",
    "front_left",
    "side_left",
    "back_left",
    "inner_left",
    "front_right",
    "side_right",
    "back_right",
    "inner_right",
];

/// The jumpsuit template, and without its legs the shirt.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Jumpsuit {
    /// The legs, the crotch and the junction (the shirt has none: its hem is the hip ring).
    pub legs: bool,
    /// Sleeves and collar.
    pub style: Style,
}

impl Jumpsuit {
    /// The jumpsuit, or without its legs the shirt, with `style`.
    pub const fn new(legs: bool, sleeves: Sleeves, collar: Collar) -> Self {
        Self {
            legs,
            style: Style { sleeves, collar },
        }
    }

    /// The bodice's rings (the shirt's: the jumpsuit's above the legs).
    pub(super) fn body_rings(&self) -> &'static [&'static str] {
        if self.legs { &RINGS } else { &RINGS[..5] }
    }
}

impl Default for Jumpsuit {
    fn default() -> Self {
        Self::new(true, Sleeves::None, Collar::None)
    }
}
