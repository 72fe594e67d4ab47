//! The stress report: one record per session (body, index, the session's outcome), and
//! totals per body and overall computed from the records, so that reports of shards merge
//! by taking the union of their records.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::outcome::SessionOutcome;
use super::verified::Verified;
use crate::collision::Misses;
use crate::convergence::{LOOPS, Tallies, merge_into};

/// One session's record.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Record {
    /// The body's file name.
    pub body: String,
    /// The session's index under the seed.
    pub session: u64,
    /// What became of it.
    pub outcome: SessionOutcome,
    /// Where the session was written when it found a bug (shrunk when asked).
    pub saved: Option<String>,
}

/// A stress run's report.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Report {
    /// The seed.
    pub seed: u64,
    /// Sessions per body asked for.
    pub sessions_per_body: u64,
    /// Steps per session after the garment.
    pub steps_per_session: usize,
    /// The shards these records come from (`[i, n]` each; one `[0, 1]` when unsharded).
    pub shards: Vec<[u64; 2]>,
    /// Every session run, sorted by body then index.
    pub records: Vec<Record>,
}

/// Totals over a set of records.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct Totals {
    /// Sessions.
    pub sessions: usize,
    /// Steps run (after the scene; refused ones included).
    pub steps: usize,
    /// Steps accepted (run and not refused).
    pub accepted: usize,
    /// Refused steps by reason.
    pub refused: BTreeMap<String, usize>,
    /// Sessions stopped by a failed step, by reason.
    pub failed: BTreeMap<String, usize>,
    /// Panics caught.
    pub panics: usize,
    /// Outputs with NaN or infinite values.
    pub non_finite: usize,
    /// Steps that left the garment in the body or crossing it.
    pub guarantee_failures: usize,
    /// Sessions that did not parse (generator bugs).
    pub parse_errors: usize,
    /// Constraint solves.
    pub solves: usize,
    /// Solves whose last pass still broke something.
    pub solves_not_converged: usize,
    /// The largest residual after a converged solve (m or rad).
    pub max_residual_converged: f64,
    /// Compute time per step, ms: median, 99th percentile, max.
    pub step_ms: Percentiles,
    /// Why the iterative loops stopped, by loop: converged, at the iteration limit or
    /// stalled, with the largest residuals (see [`crate::convergence::LOOPS`] for units).
    pub loops: Tallies,
    /// The collisions verified (`--verify`), summed.
    pub verified: VerifiedTotals,
}

/// [`super::verified::Verified`] summed over sessions.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct VerifiedTotals {
    /// Collisions checked.
    pub collisions: usize,
    /// Vertices checked.
    pub vertices: usize,
    /// Edges checked.
    pub edges: usize,
    /// Vertices inside before the responses (the truth).
    pub inside: usize,
    /// Detection's misses against the truth.
    pub missed: usize,
    /// Of them, by cause.
    pub missed_by: Misses,
    /// Verdicts the skips changed against a detection testing every vertex.
    pub skips_changed: usize,
    /// Detection's false hits.
    pub false_hits: usize,
    /// Steps whose quality check disagreed with the truth.
    pub wrong_quality: usize,
    /// Steps whose quality check differed from a full one.
    pub partial_differs: usize,
    /// The steps' quality checks, ms.
    pub quality_ms: Percentiles,
    /// Full checks of the same positions, ms.
    pub full_quality_ms: Percentiles,
    /// Sum of the steps' quality checks over the sum of the full ones.
    pub time_ratio: f64,
}

impl VerifiedTotals {
    /// The counts and times of `v`.
    pub fn of(v: &Verified) -> Self {
        let full: f64 = v.full_quality_ms.iter().sum();
        Self {
            collisions: v.collisions,
            vertices: v.vertices,
            edges: v.edges,
            inside: v.inside,
            missed: v.missed,
            missed_by: v.missed_by,
            skips_changed: v.skips_changed,
            false_hits: v.false_hits,
            wrong_quality: v.wrong_quality.len(),
            partial_differs: v.partial_differs.len(),
            quality_ms: Percentiles::of(&v.quality_ms),
            full_quality_ms: Percentiles::of(&v.full_quality_ms),
            time_ratio: if full > 0.0 {
                v.quality_ms.iter().sum::<f64>() / full
            } else {
                0.0
            },
        }
    }
}

/// Median, 99th percentile and maximum.
#[derive(Clone, Copy, Debug, Default, Serialize, PartialEq)]
pub struct Percentiles {
    /// Median.
    pub median: f64,
    /// 99th percentile (nearest rank).
    pub p99: f64,
    /// Maximum.
    pub max: f64,
}

impl Percentiles {
    /// Of `values` (empty gives zeros).
    pub fn of(values: &[f64]) -> Self {
        let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            return Self::default();
        }
        v.sort_by(f64::total_cmp);
        let rank = |q: f64| v[((q * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1];
        Self {
            median: rank(0.5),
            p99: rank(0.99),
            max: v[v.len() - 1],
        }
    }
}

impl Totals {
    /// Totals of `records`.
    pub fn of<'a>(records: impl IntoIterator<Item = &'a Record>) -> Self {
        let mut t = Self::default();
        let mut times = Vec::new();
        let mut verified = Verified::default();
        for r in records {
            let o = &r.outcome;
            t.sessions += 1;
            t.steps += o.steps;
            t.accepted += o.steps.saturating_sub(o.refused.len());
            for reason in &o.refused {
                *t.refused.entry(reason.clone()).or_default() += 1;
            }
            if let Some(reason) = &o.failed {
                *t.failed.entry(reason.clone()).or_default() += 1;
            }
            t.panics += usize::from(o.panic.is_some());
            t.non_finite += o.non_finite.len();
            t.guarantee_failures += o.guarantee_failures.len();
            t.parse_errors += usize::from(o.parse_error.is_some());
            for &(converged, _, residual) in &o.solves {
                t.solves += 1;
                if converged {
                    t.max_residual_converged = t.max_residual_converged.max(residual);
                } else {
                    t.solves_not_converged += 1;
                }
            }
            times.extend_from_slice(&o.step_ms);
            verified.absorb(o.verified.clone());
            merge_into(&mut t.loops, &o.loops);
        }
        t.step_ms = Percentiles::of(&times);
        t.verified = VerifiedTotals::of(&verified);
        t
    }

    /// Whether these totals hold a bug (a panic, a non-finite value, a guarantee failure, a
    /// session that did not parse).
    pub fn has_bugs(&self) -> bool {
        self.panics
            + self.non_finite
            + self.guarantee_failures
            + self.parse_errors
            + self.verified.wrong_quality
            + self.verified.partial_differs
            > 0
    }
}

/// The report with its totals, as `--json` prints it.
#[derive(Serialize)]
pub struct ReportJson<'a> {
    /// The run's settings and records.
    #[serde(flatten)]
    pub report: &'a Report,
    /// Totals per body.
    pub bodies: BTreeMap<String, Totals>,
    /// Totals over every body.
    pub overall: Totals,
}

impl Report {
    /// Totals per body, sorted by name.
    pub fn per_body(&self) -> BTreeMap<String, Totals> {
        let mut names: Vec<&str> = self.records.iter().map(|r| r.body.as_str()).collect();
        names.dedup();
        names
            .into_iter()
            .map(|b| (b.to_string(), Totals::of(self.records.iter().filter(|r| r.body == b))))
            .collect()
    }

    /// Totals over every record.
    pub fn overall(&self) -> Totals {
        Totals::of(&self.records)
    }

    /// The JSON form with its totals.
    pub fn json(&self) -> ReportJson<'_> {
        ReportJson {
            report: self,
            bodies: self.per_body(),
            overall: self.overall(),
        }
    }

    /// Joins the reports of shards of one sweep (the same seed, sessions and steps): the
    /// union of their records, sorted. A session found in two reports is kept once.
    pub fn merge(reports: Vec<Report>) -> Result<Report, String> {
        let mut it = reports.into_iter();
        let Some(mut out) = it.next() else {
            return Err("no reports to merge".into());
        };
        for r in it {
            if (r.seed, r.sessions_per_body, r.steps_per_session)
                != (out.seed, out.sessions_per_body, out.steps_per_session)
            {
                return Err(format!(
                    "reports of different sweeps: seed {} / {} sessions / {} steps against seed {} / {} / {}",
                    r.seed,
                    r.sessions_per_body,
                    r.steps_per_session,
                    out.seed,
                    out.sessions_per_body,
                    out.steps_per_session
                ));
            }
            out.shards.extend(r.shards);
            out.records.extend(r.records);
        }
        out.shards.sort_unstable();
        out.shards.dedup();
        out.records
            .sort_by(|a, b| (&a.body, a.session).cmp(&(&b.body, b.session)));
        out.records.dedup_by(|a, b| a.body == b.body && a.session == b.session);
        Ok(out)
    }

    /// Human-readable lines: per body and overall.
    pub fn text(&self) -> String {
        let mut s = String::new();
        let mut line = |name: &str, t: &Totals| {
            s.push_str(&format!(
                "{name}: {} sessions, {} steps: {} accepted, {} refused, {} sessions failed; {} panics, {} non-finite, \
                 {} guarantee failures; {} solves ({} not converged), largest residual after a converged solve {:.2e}; \
                 step ms median {:.1}, p99 {:.1}, max {:.1}\n",
                t.sessions,
                t.steps,
                t.accepted,
                t.refused.values().sum::<usize>(),
                t.failed.values().sum::<usize>(),
                t.panics,
                t.non_finite,
                t.guarantee_failures,
                t.solves,
                t.solves_not_converged,
                t.max_residual_converged,
                t.step_ms.median,
                t.step_ms.p99,
                t.step_ms.max
            ));
        };
        for (body, t) in self.per_body() {
            line(&body, &t);
        }
        let all = self.overall();
        line("overall", &all);
        let v = &all.verified;
        if v.collisions > 0 {
            s.push_str(&format!(
                "verified: {} collisions ({} vertices, {} edges) against the brute-force truth: {} inside before the responses, detection missed {} \
                 ({}), false hits {}, verdicts the skips changed {}; the quality check wrong on {} steps, the partial check unlike a full one on {} steps; \
                 quality check ms median {:.2} (full {:.2}), max {:.2} (full {:.2}), {:.2}x the full check's time in all\n",
                v.collisions,
                v.vertices,
                v.edges,
                v.inside,
                v.missed,
                v.missed_by,
                v.false_hits,
                v.skips_changed,
                v.wrong_quality,
                v.partial_differs,
                v.quality_ms.median,
                v.full_quality_ms.median,
                v.quality_ms.max,
                v.full_quality_ms.max,
                v.time_ratio
            ));
        }
        if !all.refused.is_empty() {
            s.push_str("refused, by reason:\n");
            for (reason, n) in &all.refused {
                s.push_str(&format!("  {n:>5}  {reason}\n"));
            }
        }
        if !all.failed.is_empty() {
            s.push_str("failed, by reason:\n");
            for (reason, n) in &all.failed {
                s.push_str(&format!("  {n:>5}  {reason}\n"));
            }
        }
        if !all.loops.is_empty() {
            s.push_str(&loops_table(&all.loops));
        }
        for r in self.records.iter().filter(|r| r.outcome.is_bug()) {
            s.push_str(&format!(
                "BUG {} session {}: {}{}\n",
                r.body,
                r.session,
                bug_summary(&r.outcome),
                r.saved.as_deref().map_or(String::new(), |f| format!(" (session: {f})"))
            ));
        }
        s
    }
}

/// Why the loops stopped, one line per loop: stops by reason, the most iterations and the
/// largest residuals, with the residual's unit.
pub fn loops_table(loops: &Tallies) -> String {
    let mut s = format!(
        "loops: {:<31} {:>9} {:>9} {:>8} {:>6} {:>11} {:>11}  residual\n",
        "name", "converged", "limit", "stalled", "iters", "max conv.", "max other"
    );
    for (name, t) in loops {
        let unit = LOOPS.iter().find(|(n, _)| n == name).map_or("", |(_, u)| u);
        s.push_str(&format!(
            "       {name:<31} {:>9} {:>9} {:>8} {:>6} {:>11.2e} {:>11.2e}  {unit}{}\n",
            t.converged,
            t.iteration_limit,
            t.stalled,
            t.max_iterations,
            t.max_residual_converged,
            t.max_residual_not_converged,
            if t.non_finite > 0 {
                format!(" ({} NaN or infinite)", t.non_finite)
            } else {
                String::new()
            }
        ));
    }
    s
}

/// The kind of bug an outcome holds, in words.
pub fn bug_summary(o: &SessionOutcome) -> String {
    let mut parts = Vec::new();
    if let Some(p) = &o.panic {
        parts.push(format!("panic: {p}"));
    }
    if let Some(e) = &o.parse_error {
        parts.push(format!("did not parse: {e}"));
    }
    if !o.non_finite.is_empty() {
        parts.push(format!("non-finite: {}", o.non_finite.join("; ")));
    }
    if !o.guarantee_failures.is_empty() {
        parts.push(format!(
            "garment left in the body after step(s) {:?}",
            o.guarantee_failures
        ));
    }
    if !o.verified.wrong_quality.is_empty() {
        parts.push(format!(
            "the quality check disagreed with the brute-force truth after step(s) {:?}",
            o.verified.wrong_quality
        ));
    }
    if !o.verified.partial_differs.is_empty() {
        parts.push(format!(
            "the partial quality check differed from a full one after step(s) {:?}",
            o.verified.partial_differs
        ));
    }
    parts.join("; ")
}

#[cfg(test)]
mod tests {
    use super::Percentiles;

    #[test]
    fn percentiles_by_nearest_rank() {
        let v: Vec<f64> = (1..=200).map(f64::from).collect();
        let p = Percentiles::of(&v);
        assert_eq!((p.median, p.p99, p.max), (100.0, 198.0, 200.0));
        assert_eq!(Percentiles::of(&[]).max, 0.0);
    }
}
