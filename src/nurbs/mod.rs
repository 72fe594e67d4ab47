//! NURBS surfaces and their collision ([nurbs], docs/design.md section 9): rational tensor-product
//! B-spline surfaces of any degree on clamped knot vectors ([`surface`]), evaluated by de
//! Boor's algorithm with derivatives; subdivided by knot insertion ([`split`]) into
//! sub-surfaces that together are exactly the original; bounded by 14-direction hulls
//! ([`hull`]) in a hierarchy ([`tree`]); and measured against each other ([`distance`]):
//! the paper's control-point distance and the true surface distance beside it.

pub mod distance;
pub mod experiment;
pub mod file;
pub mod hull;
pub mod scene;
pub mod split;
pub mod surface;
pub mod tree;

pub use distance::{
    ControlDistance, LeafPair, Refined, SurfaceDistance, coverage, nearest_control_points, net_deviation, pairs_within,
    refine, surface_distance,
};
pub use experiment::{Experiment, ExperimentOptions, Placement, Recommendation, place, run_experiment, shipped_pair};
pub use file::{NamedSurface, NurbsFileError};
pub use hull::{AXES, Kdop};
pub use scene::{BodyHulls, Contact, NurbsOptions, NurbsPart, collide_body, collide_parts};
pub use split::{insert_knot, middle_parameter, quarter, split_at};
pub use surface::{Direction, NurbsError, NurbsSurface, SurfaceJet};
pub use tree::{HullNode, HullTree, PairVisitor, Patch, PatchTree, descend};
