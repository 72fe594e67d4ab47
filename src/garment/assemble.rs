//! Assembly: the seams, Coons patches and M0 of a framework, built from its feature curves
//! (rings, open curves, contours) as they stand (\[frame\] section 4).
//!
//! The framework solve calls this once; an edit calls it again after the constraint
//! solver has moved the curves. Sample counts come from the [`Layout`](super::model::Layout) fixed when the
//! garment was built, so M0 keeps its topology whatever the edit. Given the framework
//! before the edit, a patch none of whose boundary curves changed keeps its surface
//! (it would be recomputed bit for bit the same): only the changed patches are re-surfaced.
//! What the lines and patches are is the template's business ([`super::template`]).

use super::m0::{M0, PatchGrid, restitch};
use super::model::{FeatureLine, Framework, FrameworkError, Spans};
use super::probe::BodyProbe;
use super::surface::{Surfaced, Surfacer};
use super::template;
use crate::body::index::Nearest;

/// What an assembly produced.
#[derive(Clone, Debug)]
pub struct Assembled {
    /// Seams and junction lines.
    pub lines: Vec<FeatureLine>,
    /// Patches.
    pub patches: Vec<PatchGrid>,
    /// The stitched mesh.
    pub m0: M0,
    /// Names of the patches surfaced anew (all of them without a previous framework).
    pub resurfaced: Vec<String>,
    /// The body's nearest point to the M0 vertices that are interior samples of the
    /// patches surfaced anew, where they stand (vertex, nearest point): measured while
    /// clearing them off the body.
    pub measured: Vec<(u32, Nearest)>,
    /// The contour spans the patches were surfaced from.
    pub spans: Spans,
}

impl Assembled {
    /// Moves its lines, patches, M0 and spans onto `fw` (the framework it was assembled
    /// from), leaving here what else it found (the patches surfaced anew, their
    /// measurements).
    pub fn place_on(&mut self, fw: &mut Framework) {
        fw.lines = std::mem::take(&mut self.lines);
        fw.patches = std::mem::take(&mut self.patches);
        fw.m0 = std::mem::take(&mut self.m0);
        fw.spans = std::mem::take(&mut self.spans);
    }
}

/// Builds the lines, patches and M0 of `fw` from its curves. With `previous`, patches
/// whose sides did not change are taken from it.
pub fn assemble(fw: &Framework, probe: &BodyProbe, previous: Option<&Framework>) -> Result<Assembled, FrameworkError> {
    assemble_among(fw, probe, previous.as_slice())
}

/// [`assemble`], taking each unchanged patch and contour span from the first of the
/// frameworks `previous` that has it (a dimension edit's replayed drag: the framework
/// just before, then the garment before the edit, whose patches the drag made last time);
/// M0's faces are kept from the first.
pub fn assemble_among(fw: &Framework, probe: &BodyProbe, previous: &[&Framework]) -> Result<Assembled, FrameworkError> {
    let spec = template::styled(fw.template, fw.style);
    let lines = spec.lines(fw, probe)?;
    let mut s = Surfacer::new(fw, probe, previous);
    spec.patches(&mut s, &lines)?;
    let Surfaced {
        patches,
        resurfaced,
        measured,
        spans,
    } = s.finish();
    let m0 = restitch(
        &patches,
        fw.layout.weld,
        previous.first().map(|p| (p.patches.as_slice(), &p.m0)),
    );
    let measured = at_vertices(&patches, &m0, measured);
    Ok(Assembled {
        lines,
        patches,
        m0,
        resurfaced,
        measured,
        spans,
    })
}

/// The samples' nearest points (patch, sample, nearest point) by the M0 vertex each sample
/// became, where the vertex stands where the sample does (a sample welded onto an earlier,
/// not identical one is left out).
fn at_vertices(patches: &[PatchGrid], m0: &M0, measured: Vec<(usize, usize, Nearest)>) -> Vec<(u32, Nearest)> {
    let mut first = Vec::with_capacity(patches.len());
    let mut base = 0;
    for p in patches {
        first.push(base);
        base += p.points.len();
    }
    measured
        .into_iter()
        .filter_map(|(i, k, n)| {
            let v = *m0.welds.get(first[i] + k)?;
            (m0.mesh.positions.get(v as usize) == Some(&patches[i].points[k])).then_some((v, n))
        })
        .collect()
}
