//! drape's integration tests, one binary with thematic modules.

// A test may unwrap: a panic is its failure report.
#![allow(clippy::unwrap_used)]

mod suite;
