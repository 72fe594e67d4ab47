//! The only module that knows Rerun: recording targets, the default blueprint, and the
//! [`RerunLogger`] sink that turns stage results into Rerun archetypes.
//!
//! Entity tree: `body/mesh`, `body/landmarks`, `body/rings/<name>`,
//! `body/partitions/<A..G>`, `mannequin/{measured,polar,chord}`, `section/<name>`,
//! `metrics/...` (scalars), `log` (text per stage). Timelines: `step` and `stage`.

pub mod blueprint;
pub mod colors;
pub mod logger;
pub mod target;

pub use blueprint::default_blueprint;
pub use logger::{LogOptions, RerunLogger};
pub use target::{RecordingTarget, open_recording};

/// The Rerun application id of every drape recording.
pub const APP_ID: &str = "drape";
