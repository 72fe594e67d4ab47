//! Solving a garment's framework on a body (\[frame\] sections 2-4): the template solves its
//! curves in a [`BuildCtx`] (see [`super::solve`]), then the framework is surfaced into its
//! patches and M0.

use std::sync::Arc;

use super::assemble::{Assembled, assemble};
use super::m0::M0;
use super::model::{Dimensions, Fit, Framework, FrameworkError, Style, TemplateKind};
use super::probe::BodyProbe;
use super::solve::{BuildCtx, FrameworkOptions, Parts};
use super::template;
use crate::body::Body;
use crate::body::index::Nearest;

/// Solves the framework of `template` on `body` with the session's dimensions.
pub fn build_framework(
    body: &Body,
    probe: &BodyProbe,
    template: TemplateKind,
    dims: &Dimensions,
    options: &FrameworkOptions,
) -> Result<Framework, FrameworkError> {
    rebuild_framework(body, probe, template, dims, options, None).map(|(fw, _)| fw)
}

/// What a build took from the framework before it and what it measured.
#[derive(Clone, Debug, Default)]
pub struct Rebuilt {
    /// The rings taken as the build before made them (the same inputs).
    pub rings_kept: usize,
    /// The patches taken from the framework before (the same sides).
    pub patches_kept: usize,
    /// The body's nearest point to the M0 vertices that are interior samples of the
    /// patches surfaced anew, where they stand (see [`Assembled::measured`]).
    pub measured: Vec<(u32, Nearest)>,
}

/// [`build_framework`], given the framework before a dimension edit: its rings are taken
/// where their inputs are the same (as that framework's build made them, whatever drags
/// moved them since), and its contour spans and patches where their samples are the same
/// (as after a drag). The same framework as a build without `previous`, bit for bit.
pub fn rebuild_framework(
    body: &Body,
    probe: &BodyProbe,
    template: TemplateKind,
    dims: &Dimensions,
    options: &FrameworkOptions,
    previous: Option<&Framework>,
) -> Result<(Framework, Rebuilt), FrameworkError> {
    let height = body.mesh.height();
    let mut ctx = BuildCtx {
        body,
        probe,
        dims,
        options,
        height,
        ease: 0.0,
        mid_x: body.landmarks.mid_x,
        dimensions: Vec::new(),
        previous: previous.map_or(&[], |p| p.built_rings.as_slice()),
        built: Vec::new(),
        rings_kept: 0,
    };
    ctx.ease = ctx.value(
        "ease",
        options.ease_fraction * height,
        (0.0, 0.1 * height),
        "ease must be between 0 and a tenth of the body's height",
    )?;
    if !template.takes_style() && options.style != Style::default() {
        return Err(FrameworkError::Section {
            curve: template.name().to_string(),
            what: "takes no sleeves or collar".into(),
        });
    }
    let spec = template::styled(template, options.style);
    let fit = spec.fit(options.fit);
    let parts = spec.curves(&mut ctx, fit)?;
    let (mut fw, built) = finish(&ctx, (template, options.style), fit, parts, previous)?;
    fw.dimensions = std::mem::take(&mut ctx.dimensions);
    fw.dimensions.sort_by(|a, b| a.name.cmp(&b.name));
    let rebuilt = Rebuilt {
        rings_kept: ctx.rings_kept,
        patches_kept: fw.patches.len() - built.resurfaced.len(),
        measured: built.measured,
    };
    fw.built_rings = Arc::new(std::mem::take(&mut ctx.built));
    Ok((fw, rebuilt))
}

/// Assembles the lines, patches and M0 from the curves (patch interiors cleared off the
/// body, see [`super::surface`]).
fn finish(
    ctx: &BuildCtx<'_>,
    (template, style): (TemplateKind, Style),
    fit: Fit,
    parts: Parts,
    previous: Option<&Framework>,
) -> Result<(Framework, Assembled), FrameworkError> {
    let mut fw = Framework {
        template,
        style,
        fit,
        planes: parts.planes,
        rings: parts.rings,
        open_curves: parts.open_curves,
        lines: Vec::new(),
        contours: parts.contours,
        straightened: parts.straightened,
        patches: Vec::new(),
        m0: M0::default(),
        spans: Default::default(),
        dimensions: Vec::new(),
        layout: parts.layout,
        built_rings: Arc::default(),
    };
    let mut built = assemble(&fw, ctx.probe, previous)?;
    built.place_on(&mut fw);
    Ok((fw, built))
}
