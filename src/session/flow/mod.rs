//! The garment flow the steps share, below them: a framework solved
//! ([`garment`](self::garment)), a drag solved and re-surfaced ([`drag`](self::drag)), M0
//! collided and its stages emitted ([`collide`]), M1 built on it ([`m1`](self::m1)), the pattern cut from it
//! ([`patterns`](self::patterns)), the
//! sculpts made again ([`sculpt`](self::sculpt)), the M1 a state restored from the undo
//! history gets back ([`restore`](self::restore)), and what the NURBS steps share
//! ([`nurbs`](self::nurbs)). No file here imports a step; the steps in `steps/` import from
//! here and never from each other.

pub(super) mod collide;
pub(super) mod drag;
pub(super) mod garment;
pub(super) mod layers;
pub(super) mod m1;
pub(super) mod nurbs;
pub(super) mod patterns;
pub(super) mod restore;
pub(super) mod sculpt;
