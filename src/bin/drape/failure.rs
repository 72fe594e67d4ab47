//! How a command fails: bad input or drape's own failure, each with its exit code.

use drape::session::FailureKind;

/// A command's failure: what kind (the exit code follows it) and the error with its context.
pub(crate) struct Failure {
    pub(crate) kind: FailureKind,
    pub(crate) error: anyhow::Error,
}

pub(crate) type Result<T> = std::result::Result<T, Failure>;

/// Sorts an error into bad input or drape's own failure.
pub(crate) trait Classify<T> {
    /// The input cannot be used (exit 2).
    fn bad_input(self) -> Result<T>;
    /// drape's own output failed (exit 3).
    fn internal(self) -> Result<T>;
}

impl<T, E: Into<anyhow::Error>> Classify<T> for std::result::Result<T, E> {
    fn bad_input(self) -> Result<T> {
        self.map_err(|e| Failure {
            kind: FailureKind::BadInput,
            error: e.into(),
        })
    }

    fn internal(self) -> Result<T> {
        self.map_err(|e| Failure {
            kind: FailureKind::Internal,
            error: e.into(),
        })
    }
}
