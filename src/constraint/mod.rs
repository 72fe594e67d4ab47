//! The node and constraint layers (\[collide\] section 2, \[frame\] section 3): the constraint
//! kinds and their residuals, the network CNet built for a template, the self-crossing
//! check, and the solver that brings the framework back to a valid state after an edit.

pub mod crossing;
pub mod curves;
pub mod kinds;
pub mod network;
pub mod solver;

pub use crossing::{Crossing, self_crossings, self_crossings_brute};
pub use curves::{CurveKind, CurveNode};
pub use kinds::{Constraint, Kind};
pub use network::{ConstraintNet, NetworkOptions};
pub use solver::{
    Chains, CurveHits, Edit, EditError, Iteration, NodeHit, Solution, SolverOptions, Target, point_names, solve,
};
