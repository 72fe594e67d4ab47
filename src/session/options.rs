//! What a run is given: the command line's settings ([`RunOptions`]) and what every step
//! may read ([`StepContext`]).

use std::path::PathBuf;

use super::format::Session;
use crate::body::{LandmarkOptions, PartitionOptions};
use crate::collision::CollisionOptions;

/// Run settings from the command line.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Replaces the session's body (`--body`).
    pub body_override: Option<PathBuf>,
    /// The axes of the body's file (`--up`, `--front`; default drape's own: y up, facing
    /// +z): the body is turned into drape's frame on load.
    pub body_frame: crate::body::Frame,
    /// Landmark detection settings (overrides come from the session).
    pub landmarks: LandmarkOptions,
    /// Partition settings.
    pub partitions: PartitionOptions,
    /// Collision settings.
    pub collision: CollisionOptions,
    /// Check every collision against the brute-force ground truth (`--verify`; slow).
    pub verify: bool,
    /// The largest body file read, bytes (`--max-input-mb`; default
    /// [`crate::input::DEFAULT_MAX_INPUT_BYTES`]; 0 means the default).
    pub max_input_bytes: u64,
    /// Set (by a signal handler) to end the run after the current step: the steps after it
    /// do not run, an `interrupted` stage says where it stopped, and the report has
    /// [`RunReport::interrupted`].
    pub stop: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    /// Where body indexes are kept between runs (`--index-cache`); `None`: built every run.
    pub index_cache: Option<crate::body::index_cache::IndexCache>,
    /// Build M1 whole at every step (`--full-m1`): subdivide M0 again and collide every
    /// refined patch, nothing taken from the step before: the same M1, to compare (default
    /// off).
    pub full_m1: bool,
    /// How many edits `undo` can take back (`--undo-limit`; default [`DEFAULT_UNDO_LIMIT`];
    /// 0 means the default): the oldest states are dropped past it, since each holds the
    /// garment whole (about 24 MB an edit for the demo's jumpsuit at resolution 24 with M1).
    pub undo_limit: usize,
}

/// How many edits `undo` can take back by default.
pub const DEFAULT_UNDO_LIMIT: usize = 32;

impl RunOptions {
    /// The largest file a step reads, bytes ([`Self::max_input_bytes`], its default for 0).
    pub fn input_limit(&self) -> u64 {
        match self.max_input_bytes {
            0 => crate::input::DEFAULT_MAX_INPUT_BYTES,
            n => n,
        }
    }

    /// How many edits `undo` can take back ([`Self::undo_limit`], its default for 0).
    pub fn undo_limit(&self) -> usize {
        match self.undo_limit {
            0 => DEFAULT_UNDO_LIMIT,
            n => n,
        }
    }
}

/// What every step may read: the session and the run's settings.
pub(in crate::session) struct StepContext<'a> {
    /// The session (its scene settings: the solver).
    pub(in crate::session) session: &'a Session,
    /// Run settings from the command line.
    pub(in crate::session) options: &'a RunOptions,
    /// The garments under the one the step works on, innermost first (none: it is the
    /// innermost or only one).
    pub(in crate::session) below: &'a [crate::session::flow::layers::Below],
}
