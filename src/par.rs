//! Data parallelism over independent items, results in input order (so output does not
//! depend on the number of threads): vertex and edge checks, the ground truth.

use std::sync::atomic::{AtomicUsize, Ordering};

use crate::convergence;

/// Worker threads set by [`set_threads`] (0: one per core).
static THREADS: AtomicUsize = AtomicUsize::new(0);

/// Sets the number of worker threads of every later parallel map in this process (`0`:
/// one per core, the default; at most 16). Results do not depend on it: each item is
/// computed alone and the outputs come back in input order.
pub fn set_threads(n: usize) {
    THREADS.store(n, Ordering::Relaxed);
}

/// The number of worker threads a parallel map uses now.
pub fn threads() -> usize {
    match THREADS.load(Ordering::Relaxed) {
        0 => std::thread::available_parallelism().map_or(1, |t| t.get()),
        n => n,
    }
    .min(16)
}

/// `f(0..n)` on all cores, in order. Small inputs (fewer than 256 items) run on the
/// calling thread.
pub fn par_map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    par_map_from(n, 256, f)
}

/// [`par_map`] for items heavy enough to share out from `min` of them on.
pub fn par_map_from<T: Send>(n: usize, min: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let threads = threads();
    if threads <= 1 || n < min.max(2) {
        return (0..n).map(f).collect();
    }
    let chunk = n.div_ceil(threads);
    // Loop stops reported on the workers are merged back into this thread's collector.
    let collecting = convergence::collecting();
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..n)
            .step_by(chunk)
            .map(|start| {
                let f = &f;
                s.spawn(move || {
                    let run = || (start..(start + chunk).min(n)).map(f).collect::<Vec<T>>();
                    if collecting {
                        convergence::collect_here(run)
                    } else {
                        (run(), convergence::Collected::new())
                    }
                })
            })
            .collect();
        let mut out = Vec::with_capacity(n);
        for h in handles {
            let (items, stops) = h.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
            convergence::absorb(&stops);
            out.extend(items);
        }
        out
    })
}
