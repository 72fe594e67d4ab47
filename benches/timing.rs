//! The timer shared by the benchmarks: medians of repeated runs, in one process.

pub use drape::bench::median_ms;
