//! The shipped bodies the benchmarks run on (shared through `#[path]`).

use std::path::PathBuf;

/// Every `assets/bodies/*.obj`, in name order.
pub fn shipped_bodies() -> Vec<PathBuf> {
    let mut bodies: Vec<PathBuf> = std::fs::read_dir("assets/bodies")
        .expect("assets/bodies")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    bodies.sort();
    bodies
}
