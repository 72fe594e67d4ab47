//! The only module that knows Rerun: recording targets, the default blueprint, and the
//! [`RerunLogger`] sink that turns stage results into Rerun archetypes.
//!
//! Entity tree: `body/mesh`, `body/landmarks`, `body/rings/<name>`,
//! `body/partitions/<A..G>`, `mannequin/{measured,polar,chord}`, `section/<name>`,
//! `garment/planes/<name>`, `garment/sections/<ring>` (body sections),
//! `garment/curves/rings/<ring>` (the ring at its current sub-step, `/points` its samples),
//! `garment/curves/contours/<name>`, `garment/curves/lines/<name>`,
//! `garment/curves/straightened`, `garment/control_points` (labelled), `garment/patches`,
//! `garment/m0/mesh/<part>` and `garment/m0/edges/<part>` (M0 in parts of whole patches,
//! each sent only when it changed, see the `parts` module; after response at the
//! `collision.response` stage; `garment/m0/muted` for a garment worn under another),
//! `garment/clearance/<part>`, `garment/m1/{mesh,edges,new_vertices}/<part>`,
//! `garment/edit/moves`, `collision/mesh/hits/<A..G>` (+ `/depth`),
//! `collision/response/<rule>` (arrows), `collision/mesh/remaining`,
//! `collision/mesh/crossing_edges`, `constraints/network/{links,curves}` (green met, red
//! violated), `constraints/solve/{curve,control,node_hits}` (per solver iteration),
//! `constraints/drag/{path,points}`, `metrics/<unit>/...` (scalars, one folder per unit; a step's figures one row per unit and op, `metrics/<unit>/step/<op>`), `log` (text per stage).
//! `nurbs/{near,crossing}/{leaf,butterfly}/{surface,net}`, `nurbs/<scene>/hulls/<side>` and
//! `nurbs/near/closest/{control,true}` (the [nurbs] experiment, per `level`).
//! `garment/sculpt` (+ `/edges`), `sculpt/{pick,radius,direction,displacement}`,
//! `sculpt/levels/<k>` (active faces per adaptive level) and
//! `sculpt_compare/{none,uniform,adaptive}` (`drape sculpt-compare`).
//! A garment worn over another logs its own entities under `layers/<name>/` (its
//! `garment/**`, `collision/**`, `constraints/**`, `sculpt/**` and `patterns/**`), and
//! `layer_gaps/<name>` (its gap in front of the garment under it; the garment under it
//! muted in place of its M0). The Garment view shows all of `layers/**`.
//! Timelines: `step`, `stage`, `iter` (solver iterations over the session) and `level`
//! (subdivision levels of the [nurbs] experiment).

pub mod blueprint;
mod body;
mod collision;
pub mod colors;
mod columns;
mod constraints;
mod draw;
mod figures;
mod garment;
mod layers;
pub mod logger;
mod m1;
mod mannequin;
mod nurbs;
mod parts;
mod patterns;
pub mod recording;
pub mod replay;
pub mod rrd_index;
mod sculpt;
mod series;
pub mod session_file;
pub mod target;

pub use blueprint::{check_garment_blueprint, default_blueprint, layered_blueprint, nurbs_blueprint, sculpt_blueprint};
pub use logger::{LogOptions, RerunLogger};
pub use rerun::RecordingStream;
pub use rerun::blueprint::Blueprint;
pub use target::{
    KeptFile, RecordingTarget, ViewerFlush, WebViewerError, open_file_recording, open_recording, open_recording_kept,
    serve_web_viewer,
};

/// The Rerun application id of every drape recording.
pub const APP_ID: &str = "drape";
