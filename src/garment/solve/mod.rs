//! What a template's solve works in: the settings ([`FrameworkOptions`]), the context
//! ([`BuildCtx`]) with the lookups the templates share, the contour fits, and what a solve
//! returns ([`Parts`]). Below the templates; [`super::build`] drives them.

mod context;
mod contours;

pub use context::{BuildCtx, find, landmark, point, section_error};
pub use contours::{ContourSpec, fit_contours, loosen};

use super::contour::{Contour, ContourKind};
use super::model::{Fit, Layout, NamedPlane, Straightened, Style};
use super::open_curve::OpenCurve;
use super::ring::{GarmentRing, RingOptions};

/// Settings of a framework solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameworkOptions {
    /// Segments per anchor arc of a ring in M0 (default 6: 48 around the torso, 24 around a leg).
    pub resolution: usize,
    /// Contour fit (default tight for the jumpsuit; the dress is always loose below the hip).
    pub fit: Fit,
    /// How contours pass through their points (default [`ContourKind::Local`]).
    pub contours: ContourKind,
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
    /// Sleeves and collar (default neither; the session gives the shirt long sleeves and
    /// a stand collar).
    pub style: Style,
}

impl Default for FrameworkOptions {
    fn default() -> Self {
        Self {
            resolution: 6,
            fit: Fit::Tight,
            contours: ContourKind::Local,
            ring: RingOptions::default(),
            weld_threshold: 1e-5,
            ease_fraction: 0.012,
            style: Style::default(),
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

    /// With this style.
    pub fn with_style(mut self, style: Style) -> Self {
        self.style = style;
        self
    }

    /// With these contours.
    pub fn with_contours(mut self, contours: ContourKind) -> Self {
        self.contours = contours;
        self
    }
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
