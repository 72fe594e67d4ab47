//! Why the iterative loops stop: every solver pass loop, Gauss-Newton, secant and bisection
//! loop reports, when it ends, whether it converged, ran into its iteration limit or
//! stalled (could make no more progress short of its tolerance), after how many iterations
//! and with which residual (in the loop's own unit, named in [`LOOPS`]).
//!
//! Reports cost nothing unless a caller collects them: [`collect`] runs a closure with a
//! collector on the current thread and returns the tallies per loop; [`crate::par`] hands
//! the collector on to its worker threads and merges their tallies back, so the figures do
//! not depend on the number of threads. `drape stress` collects per session and aggregates.

use std::cell::RefCell;
use std::collections::BTreeMap;

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Why a loop stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The residual reached the loop's tolerance.
    Converged,
    /// The iterations ran out first.
    IterationLimit,
    /// No further progress was possible short of the tolerance (a line search found no
    /// better point, a step changed nothing, a singular system).
    Stalled,
}

/// The loops that report, with the unit of their residual.
pub const LOOPS: [(&str, &str); 17] = [
    ("bridge.bisection", "m, bracket width along the bridging direction"),
    (
        "constraint.passes",
        "m or rad, largest constraint residual after the solve",
    ),
    (
        "constraint.layers.joint_rounds",
        "m, longest push of the last round made",
    ),
    ("constraint.layers.push_out", "m, bracket width"),
    ("constraint.limits.hold", "m, longest push of the last round made"),
    ("collision.push.bisection", "m, bracket width"),
    ("collision.push.secant", "m, distance from the ease"),
    ("collision.push.settle", "m, distance from the ease"),
    ("garment.ease.bisection", "m, bracket width"),
    ("garment.probe.clear", "m, shortfall from the gap"),
    ("garment.resample.bisection", "m, bracket width of the chord"),
    ("garment.ring.girth_secant", "m, girth minus its target"),
    ("landmarks.bisection", "m, bracket width in height"),
    ("mannequin.gauss_newton", "parameter units, length of the last step"),
    ("nurbs.distance.newton", "parameter units, length of the last step"),
    ("nurbs.pose.bisection", "m, bracket width of the lift"),
    ("sculpt.stop.bisection", "m, bracket width along the offset"),
];

/// What one loop's stops added up to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Tally {
    /// Stops by convergence.
    pub converged: u64,
    /// Stops at the iteration limit.
    pub iteration_limit: u64,
    /// Stalls.
    pub stalled: u64,
    /// Stops with a NaN or infinite residual (also counted by reason).
    pub non_finite: u64,
    /// The most iterations one run of the loop made.
    pub max_iterations: u64,
    /// The largest residual of a converged stop.
    pub max_residual_converged: f64,
    /// The largest finite residual of a stop that did not converge.
    pub max_residual_not_converged: f64,
}

impl Tally {
    /// All stops.
    pub fn stops(&self) -> u64 {
        self.converged + self.iteration_limit + self.stalled
    }

    fn add(&mut self, stop: Stop, iterations: usize, residual: f64) {
        match stop {
            Stop::Converged => self.converged += 1,
            Stop::IterationLimit => self.iteration_limit += 1,
            Stop::Stalled => self.stalled += 1,
        }
        self.max_iterations = self.max_iterations.max(iterations as u64);
        let residual = residual.abs();
        if !residual.is_finite() {
            self.non_finite += 1;
        } else if stop == Stop::Converged {
            self.max_residual_converged = self.max_residual_converged.max(residual);
        } else {
            self.max_residual_not_converged = self.max_residual_not_converged.max(residual);
        }
    }

    /// Adds `other`'s stops to these.
    pub fn merge(&mut self, other: &Tally) {
        self.converged += other.converged;
        self.iteration_limit += other.iteration_limit;
        self.stalled += other.stalled;
        self.non_finite += other.non_finite;
        self.max_iterations = self.max_iterations.max(other.max_iterations);
        self.max_residual_converged = self.max_residual_converged.max(other.max_residual_converged);
        self.max_residual_not_converged = self.max_residual_not_converged.max(other.max_residual_not_converged);
    }
}

/// Tallies by loop name, sorted.
pub type Tallies = BTreeMap<String, Tally>;

/// Adds every tally of `from` into `into`.
pub fn merge_into(into: &mut Tallies, from: &Tallies) {
    for (name, t) in from {
        into.entry(name.clone()).or_default().merge(t);
    }
}

/// Tallies as collected on one thread, keyed by the loops' static names.
pub(crate) type Collected = BTreeMap<&'static str, Tally>;

thread_local! {
    static COLLECTOR: RefCell<Option<Collected>> = const { RefCell::new(None) };
}

/// Reports that loop `name` (one of [`LOOPS`]) stopped for `stop` after `iterations` with
/// `residual`. Does nothing unless a collector runs on this thread.
pub fn record(name: &'static str, stop: Stop, iterations: usize, residual: f64) {
    debug_assert!(LOOPS.iter().any(|(n, _)| *n == name), "loop {name} is not in LOOPS");
    COLLECTOR.with(|c| {
        if let Some(t) = c.borrow_mut().as_mut() {
            t.entry(name).or_default().add(stop, iterations, residual);
        }
    });
}

/// Whether a collector runs on this thread.
pub fn collecting() -> bool {
    COLLECTOR.with(|c| c.borrow().is_some())
}

/// Restores the collector that ran before, also when the closure panics.
struct Restore(Option<Collected>);

impl Drop for Restore {
    fn drop(&mut self) {
        let before = self.0.take();
        COLLECTOR.with(|c| *c.borrow_mut() = before);
    }
}

/// Runs `f` with a fresh collector on this thread; returns its result and the stops it
/// reported. A collector that ran before is restored afterwards (the stops are not added
/// to it).
pub fn collect<R>(f: impl FnOnce() -> R) -> (R, Tallies) {
    let (out, got) = collect_here(f);
    (out, got.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
}

/// [`collect`] with the tallies as collected (for worker threads, see [`absorb`]).
pub(crate) fn collect_here<R>(f: impl FnOnce() -> R) -> (R, Collected) {
    let restore = Restore(COLLECTOR.with(|c| c.borrow_mut().replace(BTreeMap::new())));
    let out = f();
    let got = COLLECTOR.with(|c| c.borrow_mut().take()).unwrap_or_default();
    drop(restore);
    (out, got)
}

/// Adds a worker thread's `collected` stops to the collector running on this thread, if
/// one does ([`crate::par`] merges its workers back so).
pub(crate) fn absorb(collected: &Collected) {
    COLLECTOR.with(|c| {
        if let Some(t) = c.borrow_mut().as_mut() {
            for (name, tally) in collected {
                t.entry(name).or_default().merge(tally);
            }
        }
    });
}

/// A value a bisection can halve: a number, or a point on a segment.
pub trait Halve: Copy + PartialEq {
    /// The middle of `a` and `b`.
    fn middle(a: Self, b: Self) -> Self;
    /// The distance between `a` and `b`.
    fn width(a: Self, b: Self) -> f64;
}

impl Halve for f64 {
    fn middle(a: Self, b: Self) -> Self {
        0.5 * (a + b)
    }
    fn width(a: Self, b: Self) -> f64 {
        (b - a).abs()
    }
}

impl Halve for DVec3 {
    fn middle(a: Self, b: Self) -> Self {
        a.lerp(b, 0.5)
    }
    fn width(a: Self, b: Self) -> f64 {
        a.distance(b)
    }
}

/// How a bisection runs and when it counts as converged.
#[derive(Clone, Copy, Debug)]
pub struct Bisection {
    /// Its name in the tallies (one of [`LOOPS`]).
    pub name: &'static str,
    /// Most halvings.
    pub steps: usize,
    /// Bracket width at which it has converged (the unit of the bracket).
    pub tolerance: f64,
    /// Stop as soon as the bracket is that narrow; otherwise halve on to `steps` (or to
    /// the resolution of floating point) and only judge by the tolerance.
    pub stop_at_tolerance: bool,
}

impl Bisection {
    /// Narrows `[lo, hi]` around the point where `below` turns from true (at `lo`) to false
    /// (at `hi`) and reports the stop; returns the final bracket. It also stops, converged,
    /// when the bracket cannot be split in floating point any more (every later halving
    /// would change nothing).
    pub fn run<T: Halve>(&self, mut lo: T, mut hi: T, mut below: impl FnMut(T) -> bool) -> (T, T) {
        let mut done = 0;
        let mut resolved = false;
        while done < self.steps {
            let mid = T::middle(lo, hi);
            if mid == lo || mid == hi {
                resolved = true;
                break;
            }
            if below(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
            done += 1;
            if self.stop_at_tolerance && T::width(lo, hi) <= self.tolerance {
                break;
            }
        }
        let width = T::width(lo, hi);
        let stop = if resolved || width <= self.tolerance {
            Stop::Converged
        } else {
            Stop::IterationLimit
        };
        record(self.name, stop, done, width);
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bisection_finds_a_square_root_and_reports_convergence() {
        let b = Bisection {
            name: "garment.ease.bisection",
            steps: 200,
            tolerance: 1e-12,
            stop_at_tolerance: true,
        };
        let ((lo, hi), t) = collect(|| b.run(1.0, 2.0, |x: f64| x * x < 2.0));
        assert!((lo - 2f64.sqrt()).abs() <= 1e-12 && (hi - 2f64.sqrt()).abs() <= 1e-12);
        let tally = t["garment.ease.bisection"];
        assert_eq!((tally.converged, tally.iteration_limit), (1, 0));
        // 2^-n <= 1e-12 first at n = 40.
        assert_eq!(tally.max_iterations, 40);
    }

    #[test]
    fn a_short_bisection_reports_its_limit_and_residual() {
        let b = Bisection {
            name: "landmarks.bisection",
            steps: 10,
            tolerance: 1e-9,
            stop_at_tolerance: false,
        };
        let (_, t) = collect(|| b.run(0.0, 1.0, |x: f64| x < 0.3));
        let tally = t["landmarks.bisection"];
        assert_eq!((tally.converged, tally.iteration_limit), (0, 1));
        assert_eq!(tally.max_residual_not_converged, 1.0 / 1024.0);
    }

    #[test]
    fn nothing_is_kept_without_a_collector_and_nesting_restores_the_outer_one() {
        record("garment.probe.clear", Stop::Stalled, 3, 1.0);
        let ((_, inner), outer) = collect(|| {
            record("garment.probe.clear", Stop::Converged, 1, 0.0);
            let inner = collect(|| record("garment.probe.clear", Stop::Stalled, 2, 0.5));
            record("garment.probe.clear", Stop::Converged, 1, 0.0);
            inner
        });
        assert_eq!(inner["garment.probe.clear"].stalled, 1);
        assert_eq!(outer["garment.probe.clear"].converged, 2);
        assert_eq!(outer["garment.probe.clear"].stalled, 0);
        assert!(!collecting());
    }
}
