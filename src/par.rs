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
    let ranges = (0..n)
        .step_by(chunk)
        .map(|start| start..(start + chunk).min(n))
        .collect();
    in_chunks(ranges, |range| range.map(&f).collect())
}

/// [`par_map_from`] over owned `items`, each moved into `f` (none copied).
pub fn par_map_owned<I: Send, T: Send>(items: Vec<I>, min: usize, f: impl Fn(I) -> T + Sync) -> Vec<T> {
    let threads = threads();
    if threads <= 1 || items.len() < min.max(2) {
        return items.into_iter().map(f).collect();
    }
    let chunk = items.len().div_ceil(threads);
    let mut rest = items;
    let mut chunks = Vec::new();
    while rest.len() > chunk {
        let tail = rest.split_off(chunk);
        chunks.push(rest);
        rest = tail;
    }
    chunks.push(rest);
    in_chunks(chunks, |items| items.into_iter().map(&f).collect())
}

/// `run` on each chunk, a thread each, the results joined in chunk order.
fn in_chunks<C: Send, T: Send>(chunks: Vec<C>, run: impl Fn(C) -> Vec<T> + Sync) -> Vec<T> {
    // Loop stops reported on the workers are merged back into this thread's collector.
    let collecting = convergence::collecting();
    std::thread::scope(|s| {
        let handles: Vec<_> = chunks
            .into_iter()
            .map(|chunk| {
                let run = &run;
                s.spawn(move || {
                    if collecting {
                        convergence::collect_here(|| run(chunk))
                    } else {
                        (run(chunk), convergence::Collected::new())
                    }
                })
            })
            .collect();
        let mut out = Vec::new();
        for h in handles {
            let (items, stops) = h.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
            convergence::absorb(&stops);
            out.extend(items);
        }
        out
    })
}

#[cfg(test)]
mod tests {
    use super::{par_map_from, par_map_owned};

    /// Owned items come back mapped in input order, as a plain map gives them, for every
    /// length around the chunk boundaries (on the default workers: one per core).
    #[test]
    fn owned_items_map_in_input_order() {
        for n in 0..40 {
            let items: Vec<String> = (0..n).map(|k| format!("item {k}")).collect();
            let want: Vec<usize> = items.iter().map(|s| s.len() * 7 + s.as_bytes()[5] as usize).collect();
            let got = par_map_owned(items, 2, |s| s.len() * 7 + s.as_bytes()[5] as usize);
            assert_eq!(got, want, "{n} items");
            assert_eq!(par_map_from(n, 2, |k| k * k), (0..n).map(|k| k * k).collect::<Vec<_>>());
        }
    }
}
