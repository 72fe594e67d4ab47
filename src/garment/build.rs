//! Solving a garment's framework on a body (\[frame\] sections 2-4): the template solves its
//! curves in a [`BuildCtx`] (see [`super::solve`]), then the framework is surfaced into its
//! patches and M0.

use super::assemble::assemble;
use super::m0::M0;
use super::model::{Dimensions, Fit, Framework, FrameworkError, Style, TemplateKind};
use super::probe::BodyProbe;
use super::solve::{BuildCtx, FrameworkOptions, Parts};
use super::template;
use crate::body::Body;

/// Solves the framework of `template` on `body` with the session's dimensions.
pub fn build_framework(
    body: &Body,
    probe: &BodyProbe,
    template: TemplateKind,
    dims: &Dimensions,
    options: &FrameworkOptions,
) -> Result<Framework, FrameworkError> {
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
    let mut fw = finish(&ctx, (template, options.style), fit, parts)?;
    fw.dimensions = std::mem::take(&mut ctx.dimensions);
    fw.dimensions.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(fw)
}

/// Assembles the lines, patches and M0 from the curves (patch interiors cleared off the
/// body, see [`super::surface`]).
fn finish(
    ctx: &BuildCtx<'_>,
    (template, style): (TemplateKind, Style),
    fit: Fit,
    parts: Parts,
) -> Result<Framework, FrameworkError> {
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
    };
    let built = assemble(&fw, ctx.probe, None)?;
    fw.lines = built.lines;
    fw.patches = built.patches;
    fw.m0 = built.m0;
    fw.spans = built.spans;
    Ok(fw)
}
