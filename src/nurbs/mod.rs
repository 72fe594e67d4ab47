//! NURBS surfaces and their collision ([nurbs], DESIGN section 9): rational tensor-product
//! B-spline surfaces of any degree on clamped knot vectors ([`surface`]), evaluated by de
//! Boor's algorithm, and subdivided by knot insertion ([`split`]) into sub-surfaces that
//! together are exactly the original.

pub mod split;
pub mod surface;

pub use split::{insert_knot, middle_parameter, quarter, split_at};
pub use surface::{Direction, NurbsError, NurbsSurface};
