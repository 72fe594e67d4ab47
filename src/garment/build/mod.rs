//! Solving a garment's framework on a body (\[frame\] sections 2-4): the template solves its
//! curves in a [`BuildCtx`], then the framework is surfaced into its patches and M0.

mod context;
mod contours;

pub use context::{BuildCtx, find, landmark, point, section_error};
pub use contours::{ContourSpec, fit_contours, loosen};

use super::assemble::assemble;
use super::contour::Contour;
use super::m0::M0;
use super::model::{
    Contours, Dimensions, Fit, Framework, FrameworkError, Layout, NamedPlane, Straightened, TemplateKind,
};
use super::open_curve::OpenCurve;
use super::probe::BodyProbe;
use super::ring::{GarmentRing, RingOptions};
use super::template;
use crate::body::Body;

/// Settings of a framework solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameworkOptions {
    /// Segments per anchor arc of a ring in M0 (default 6: 48 around the torso, 24 around a leg).
    pub resolution: usize,
    /// Contour fit (default tight for the jumpsuit; the dress is always loose below the hip).
    pub fit: Fit,
    /// How contours pass through their points (default [`Contours::Local`]).
    pub contours: Contours,
    /// Ring processing.
    pub ring: RingOptions,
    /// Weld threshold as a fraction of the body's height (default 1e-5: 17 um on a 1.7 m
    /// body). The ends of a patch's sides must meet within it at the patch's corners, and
    /// the weld merges the patches' samples within it: one tolerance, so that no corner a
    /// patch accepts is left as a crack in M0. A solve leaves coincident points of two
    /// curves up to its tolerance apart (6e-7 of the height,
    /// [`crate::constraint::SolverOptions::tolerance`]); a garment's samples stand
    /// millimetres apart.
    pub weld_threshold: f64,
    /// Default ease as a fraction of the body's height (default 0.012: 1.9 cm on 1.59 m).
    pub ease_fraction: f64,
}

impl Default for FrameworkOptions {
    fn default() -> Self {
        Self {
            resolution: 6,
            fit: Fit::Tight,
            contours: Contours::Local,
            ring: RingOptions::default(),
            weld_threshold: 1e-5,
            ease_fraction: 0.012,
        }
    }
}

impl FrameworkOptions {
    /// With this resolution.
    pub fn with_resolution(mut self, resolution: usize) -> Self {
        self.resolution = resolution;
        self
    }

    /// With this fit.
    pub fn with_fit(mut self, fit: Fit) -> Self {
        self.fit = fit;
        self
    }

    /// With these contours.
    pub fn with_contours(mut self, contours: Contours) -> Self {
        self.contours = contours;
        self
    }
}

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
    let spec = template::of(template);
    let fit = spec.fit(options.fit);
    let parts = spec.curves(&mut ctx, fit)?;
    let mut fw = finish(&ctx, template, fit, parts)?;
    fw.dimensions = std::mem::take(&mut ctx.dimensions);
    fw.dimensions.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(fw)
}

/// The curves of a framework as a template solves them, before surfacing.
#[derive(Clone, Debug)]
pub struct Parts {
    /// Planes used (drawn in the viewer).
    pub planes: Vec<NamedPlane>,
    /// Rings, top to bottom.
    pub rings: Vec<GarmentRing>,
    /// Open curves.
    pub open_curves: Vec<OpenCurve>,
    /// Contours.
    pub contours: Vec<Contour>,
    /// Loose-fit straightening.
    pub straightened: Vec<Straightened>,
    /// Sample counts, fixed for the garment's life.
    pub layout: Layout,
}

/// Assembles the lines, patches and M0 from the curves (patch interiors cleared off the
/// body, see [`super::surface`]).
fn finish(ctx: &BuildCtx<'_>, template: TemplateKind, fit: Fit, parts: Parts) -> Result<Framework, FrameworkError> {
    let mut fw = Framework {
        template,
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
