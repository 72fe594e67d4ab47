//! Sculpting (\[sculpt\], docs/design.md section 8): free-form pushes and pulls on a mesh, refined
//! only where the drag stretched it.
//!
//! Data flow of one sculpt: [`displace`] (pick the nearest point of the mesh, move the
//! vertices within the radius by the peak times the [`Falloff`]; the faces with a moved
//! corner are the region) -> [`refine`] (adaptive Loop subdivision with red-green closure
//! of the region, until no region face has an edge longer than epsilon) -> (in a session)
//! the collision of what changed with the body, by M1's machinery
//! ([`crate::m1::collide_refined`]). [`compare()`] runs the same drag with no subdivision,
//! with uniform Loop to the same epsilon, and adaptively, and measures all three.
//!
//! Nothing here logs: [`crate::viz`] draws the results.

pub mod adaptive;
pub mod compare;
pub mod drag;
pub mod falloff;
pub mod loop_rules;
pub mod make;
pub mod measure;
pub mod options;

pub use adaptive::{AdaptiveOptions, Level, Refined, refine};
pub use compare::{Comparison, Variant, compare};
pub use drag::{Displacement, Drag, Pick, STOP_TOLERANCE_M, displace, displace_clear_of, pick};
pub use falloff::Falloff;
pub use loop_rules::{UniformStep, boundary_vertex, edge_point, interior_vertex, loop_beta, uniform_step};
pub use make::{Sculpt, longest_edge, sculpt, sculpt_clear_of};
pub use measure::{Measures, measure};
pub use options::{SculptError, SculptOptions};
