//! drape's integration tests, one binary with thematic modules.

mod suite;
