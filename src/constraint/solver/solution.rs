//! What a solve did: every curve solved with its node- and curve-layer collision and
//! residuals, the passes made, what is still violated.

use glam::DVec3;

use crate::constraint::network::ConstraintNet;
use crate::garment::Framework;

/// A control point moved by the node-layer collision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeHit {
    /// Control point index.
    pub point: usize,
    /// Signed distance to the body before, m.
    pub distance: f64,
    /// Before, m (world frame).
    pub before: DVec3,
    /// After, m (world frame).
    pub after: DVec3,
}

/// The curve-layer collision of one curve.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CurveHits {
    /// Samples tested.
    pub samples: usize,
    /// Samples short of the gap before the response.
    pub short_before: usize,
    /// Largest shortfall before, m.
    pub deficit_before: f64,
    /// Largest shortfall after, m.
    pub deficit_after: f64,
    /// Response rounds made.
    pub rounds: usize,
    /// Control points the response moved.
    pub moved: Vec<usize>,
    /// Control points kept still (shared with curves solved before, split chains).
    pub pinned: Vec<usize>,
}

/// One curve solved: what drove it, what the collision did, and the residuals of the
/// constraints it touches afterwards.
#[derive(Clone, Debug, PartialEq)]
pub struct Iteration {
    /// Pass (0-based).
    pub pass: usize,
    /// Curve index in the network.
    pub curve: usize,
    /// Constraints applied from solved neighbours.
    pub driven_by: Vec<usize>,
    /// Node layer.
    pub node: Vec<NodeHit>,
    /// Curve layer.
    pub curve_layer: CurveHits,
    /// `(constraint, residual)` of every constraint touching the curve.
    pub residuals: Vec<(usize, f64)>,
    /// Constraints with curves solved before that this solve left violated.
    pub broken: Vec<usize>,
    /// The curve's control points afterwards, m (world frame).
    pub control: Vec<DVec3>,
}

/// The result of an edit.
#[derive(Clone, Debug)]
pub struct Solution {
    /// The framework with its curves solved, without its surface (no patches, M0 or
    /// cleared spans: [`Framework::without_surface`]; the assembly makes them again) and
    /// with the lines of before.
    pub framework: Framework,
    /// Every curve solve, in order.
    pub iterations: Vec<Iteration>,
    /// Passes made.
    pub passes: usize,
    /// Whether the last pass broke nothing.
    pub converged: bool,
    /// Every constraint's residual at the end, in its kind's unit (m, or rad).
    pub residuals: Vec<f64>,
    /// `(constraint, residual)` above the tolerance at the end.
    pub violations: Vec<(usize, f64)>,
    /// The dragged point (curve, control point), for a point drag.
    pub dragged: Option<(usize, usize)>,
    /// The dragged point, m: where it was, where it was asked to go, after the first pass's
    /// node layer, and after each pass.
    pub path: Vec<DVec3>,
    /// The curves solved.
    pub solved: Vec<usize>,
    /// The collision gap used, m.
    pub gap: f64,
    /// Largest shortfall of the gap left on a solved planar curve's samples, m.
    pub clearance_deficit: f64,
    /// The tolerance the constraints were solved to (a fraction of the body's height for
    /// lengths, rad for tangents; see [`crate::constraint::ConstraintNet::violated`]).
    pub tolerance: f64,
}

impl Solution {
    /// The largest residual at the end, m or rad.
    pub fn max_residual(&self) -> f64 {
        self.residuals.iter().copied().fold(0.0, f64::max)
    }

    /// One line per constraint left violated (`kind curve[-other] by residual unit`).
    pub fn violation_lines(&self, net: &ConstraintNet) -> Vec<String> {
        self.violations
            .iter()
            .map(|&(k, r)| net.constraints[k].describe(&net.curves, r))
            .collect()
    }
}
