//! Solver settings: how closed chains are handled, pass and round limits, the tolerance and
//! the collision gap.

use crate::garment::RingOptions;

/// How closed chains are handled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Chains {
    /// Move the first element of the chain and solve again (the default).
    #[default]
    Iterate,
    /// Split the chain's curves at their shared points so it is open; one pass.
    Split,
}

impl Chains {
    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Iterate => "iterate",
            Self::Split => "split",
        }
    }

    /// From the session spelling.
    pub fn from_name(s: &str) -> Option<Self> {
        [Self::Iterate, Self::Split].into_iter().find(|c| c.name() == s)
    }
}

/// Solver settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverOptions {
    /// Closed chains (default iterate).
    pub chains: Chains,
    /// Most passes over the network (default 8).
    pub passes: usize,
    /// A constraint is met when its residual is at most this: a fraction of the body's height
    /// for a residual in metres, radians for an angle (default 6e-7: about a micrometre on a
    /// 1.6 m body; coincident points are copied and meet exactly).
    pub tolerance: f64,
    /// Rounds of the curve-layer response per curve (default 4).
    pub response_rounds: usize,
    /// The curve-layer response aims this fraction of the gap beyond it (default 0.05), so
    /// that a closed chain is not re-broken by a shortfall of a few micrometres.
    pub response_margin: f64,
    /// The collision gap as a fraction of the garment's ease (default 0.5, as the mesh
    /// layer), at least `min_gap` of the body's height (default 0.002).
    pub gap_fraction: f64,
    /// Floor of the collision gap, as a fraction of the body's height (default 0.002).
    pub min_gap: f64,
    /// Ring refitting.
    pub ring: RingOptions,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            chains: Chains::Iterate,
            passes: 8,
            tolerance: 6e-7,
            response_rounds: 4,
            response_margin: 0.05,
            gap_fraction: 0.5,
            min_gap: 0.002,
            ring: RingOptions::default(),
        }
    }
}
