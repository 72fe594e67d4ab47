//! Layers: a garment over another. The outer garment's surface is kept in front of the
//! inner one's (on the side away from the body), with the fabric's thickness between them,
//! and certified exactly: no outer vertex behind the inner surface, no outer edge through an
//! inner face, no inner edge through an outer face.

pub mod certificate;
pub mod orient;
pub mod push;
pub mod surface;

pub use certificate::{LayerCounts, certify_layers};
pub use orient::{away_from_body, facing};
pub use push::{Outward, PushOptions, PushReport, push_outside, push_outside_along};
pub use surface::{LayerError, LayerSurface, Nearest};
