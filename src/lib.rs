//! # drape
//!
//! Garment edit sessions against a body, every stage logged to Rerun.
//!
//! ## The pipeline
//!
//! A **session** ([`session`]) names a body and an ordered list of steps. The runner loads
//! the **body** ([`body`]): an OBJ mesh ([`mesh`]) validated and repaired, its landmarks
//! found from the section profile, rings cut at the landmark heights, and partitions A-G
//! with their collision method and response rule. Each step then computes plain data
//! (for example the [`mannequin`] refinement compared with its true surface) and hands it
//! to a [`session::StageSink`]. The only sink that knows Rerun is in [`viz`]; the metrics
//! file and the mesh export are others. Geometry never depends on logging, so every
//! stage can be tested and benchmarked alone.
//!
//! ## Design and papers
//!
//! `docs/design.md` is the specification the code follows. Doc comments cite its sections
//! (`docs/design.md` section N) and the papers its methods come from by short name:
//! \[collide\] (the four-layer garment model and its collision), \[frame\] (the
//! feature-line framework), \[nurbs\] (NURBS surface collision), \[spline\] (the
//! mannequin's cubic splines) and \[sculpt\] (adaptive subdivision for sculpting), with
//! their full references there.
//!
//! ## Units and frames
//!
//! Metres, `y` up, the body faces `+z`, its left is `+x`. Angles in radians.

#![warn(missing_docs)]

pub mod bench;
pub mod body;
pub mod collision;
pub mod constraint;
pub mod convergence;
pub mod garment;
pub mod geom;
pub mod import;
pub mod input;
pub mod layers;
pub mod m1;
pub mod mannequin;
pub mod mesh;
pub mod nurbs;
pub mod par;
pub mod pattern;
pub mod sculpt;
pub mod session;
pub mod stress;
pub mod viz;
