//! Data parallelism over independent items, results in input order (so output does not
//! depend on the number of threads): vertex and edge checks, the ground truth.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

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

/// Chunks per worker of a parallel map of heavy items: the workers take them as they
/// finish the last, so items of uneven cost (M1's patches, a garment's patches) even out.
const CHUNKS_PER_THREAD: usize = 4;

/// `f(0..n)` on all cores, in order, a run of neighbouring items per worker (queries that
/// follow one another warm-start each other). Small inputs (fewer than 256 items) run on
/// the calling thread.
pub fn par_map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    map_in_chunks(n, (256, 1), f)
}

/// [`par_map`] for items heavy enough to share out from `min` of them on, and of uneven
/// cost: shared out in smaller runs that the workers take as they finish the last.
pub fn par_map_from<T: Send>(n: usize, min: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    map_in_chunks(n, (min, CHUNKS_PER_THREAD), f)
}

/// `f(0..n)` in `per_thread` chunks per worker, from `min` items on.
fn map_in_chunks<T: Send>(n: usize, (min, per_thread): (usize, usize), f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let threads = threads();
    if threads <= 1 || n < min.max(2) {
        return (0..n).map(f).collect();
    }
    let chunk = n.div_ceil(threads * per_thread);
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
    let chunk = items.len().div_ceil(threads * CHUNKS_PER_THREAD);
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

/// The worker pool of `threads` threads, made the first time that many are asked for and
/// kept (a parallel map costs a task, not a thread spawned).
fn pool(threads: usize) -> Option<Arc<rayon::ThreadPool>> {
    static POOLS: Mutex<BTreeMap<usize, Arc<rayon::ThreadPool>>> = Mutex::new(BTreeMap::new());
    let mut pools = POOLS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(p) = pools.get(&threads) {
        return Some(Arc::clone(p));
    }
    let made = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|k| format!("drape-worker-{k}"))
        .build()
        .ok()?;
    let made = Arc::new(made);
    pools.insert(threads, Arc::clone(&made));
    Some(made)
}

/// `run` on each chunk, as tasks of the worker pool, the results joined in chunk order.
fn in_chunks<C: Send, T: Send>(chunks: Vec<C>, run: impl Fn(C) -> Vec<T> + Sync) -> Vec<T> {
    use rayon::iter::{IntoParallelIterator, ParallelIterator};
    // Loop stops reported on the workers are merged back into this thread's collector, in
    // chunk order.
    let collecting = convergence::collecting();
    let each = |chunk: C| {
        if collecting {
            convergence::collect_here(|| run(chunk))
        } else {
            (run(chunk), convergence::Collected::new())
        }
    };
    let done: Vec<(Vec<T>, convergence::Collected)> = match pool(threads()) {
        Some(pool) => pool.install(|| chunks.into_par_iter().map(each).collect()),
        None => chunks.into_iter().map(each).collect(),
    };
    let mut out = Vec::new();
    for (items, stops) in done {
        convergence::absorb(&stops);
        out.extend(items);
    }
    out
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
