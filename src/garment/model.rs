//! The data model of a garment framework: which template and fit, the dimensions set, and
//! the solved framework itself (planes, rings, open curves, seams and junction lines,
//! contours, patches, the stitched mesh M0, the dimensions reached, and the layout of sample
//! counts fixed for the garment's life). The algorithms that make and edit it live beside
//! it: [`super::build`] solves it, [`super::assemble`] surfaces it, and each template in
//! [`super::template`] says what its curves and patches are.
//!
//! Units: metres, world frame (y up, the body faces +z, its left is +x).

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::DVec3;
use thiserror::Error;

use super::contour::Contour;
use super::m0::{M0, PatchError, PatchGrid};
use super::open_curve::OpenCurve;
use super::ring::{BuiltRing, GarmentRing, RingBuildError};
use crate::geom::{Plane, SplineError};

/// The garments drape can build.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
pub enum TemplateKind {
    /// Jumpsuit (sleeveless unless its [`Style`] says otherwise).
    Jumpsuit,
    /// Skirt or dress from the waist.
    Dress,
    /// Shirt: the jumpsuit's bodice down to the hip, with sleeves and a collar.
    Shirt,
}

impl TemplateKind {
    /// Every template.
    pub const ALL: [Self; 3] = [Self::Jumpsuit, Self::Dress, Self::Shirt];

    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Jumpsuit => "jumpsuit",
            Self::Dress => "dress",
            Self::Shirt => "shirt",
        }
    }

    /// The style a session gets when it names none: the shirt has long sleeves and a stand
    /// collar, the others neither.
    pub fn default_style(self) -> Style {
        match self {
            Self::Shirt => Style {
                sleeves: Sleeves::Long,
                collar: Collar::Stand,
            },
            _ => Style::default(),
        }
    }

    /// Whether the template can take sleeves and a collar (the dress cannot: it starts at
    /// the waist).
    pub fn takes_style(self) -> bool {
        self != Self::Dress
    }

    /// From the session spelling.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }
}

/// A garment's sleeves ([frame] type-I parts on the armholes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub enum Sleeves {
    /// Armholes left open (the straps over the shoulders).
    #[default]
    None,
    /// Down to above the elbow.
    Short,
    /// Down to the wrist.
    Long,
}

impl Sleeves {
    /// Every choice.
    pub const ALL: [Self; 3] = [Self::None, Self::Short, Self::Long];

    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Short => "short",
            Self::Long => "long",
        }
    }

    /// From the session spelling.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }
}

/// A garment's collar ([frame] type-I part on the neckline).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub enum Collar {
    /// The neckline left open.
    #[default]
    None,
    /// A stand collar rising from the neckline.
    Stand,
}

impl Collar {
    /// Every choice.
    pub const ALL: [Self; 2] = [Self::None, Self::Stand];

    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Stand => "stand",
        }
    }

    /// From the session spelling.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }
}

/// The type-I parts a garment carries: its sleeves and its collar (default: neither).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct Style {
    /// Sleeves.
    pub sleeves: Sleeves,
    /// Collar.
    pub collar: Collar,
}

/// How contours run below the top ring of a loose part.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Fit {
    /// Contours follow the rings' anchors (splines through them).
    Tight,
    /// Contours below a fixed ring are straightened (trouser legs, an A-line skirt).
    Loose,
}

impl Fit {
    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Tight => "tight",
            Self::Loose => "loose",
        }
    }

    /// From the session spelling.
    pub fn from_name(name: &str) -> Option<Self> {
        [Self::Tight, Self::Loose].into_iter().find(|f| f.name() == name)
    }
}

/// Dimension values a session has set (the rest come from the body).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Dimensions {
    /// Name to value (m, or a fraction for `strap_position`).
    pub values: BTreeMap<String, f64>,
}

impl Dimensions {
    /// A value if set (m, or a fraction for `strap_position`).
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.get(name).copied()
    }
}

/// Why a framework cannot be solved.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FrameworkError {
    /// A ring or open curve failed.
    #[error(transparent)]
    Ring(#[from] RingBuildError),
    /// A plane cuts no usable section.
    #[error("{curve}: {what}")]
    Section {
        /// Curve.
        curve: String,
        /// What is missing.
        what: String,
    },
    /// A contour could not be fitted.
    #[error("contour '{0}': {1}")]
    Contour(String, SplineError),
    /// A patch failed.
    #[error(transparent)]
    Patch(#[from] PatchError),
    /// A dimension is out of range.
    #[error("dimension {name} = {value}: {reason}")]
    Dimension {
        /// Name.
        name: String,
        /// Value.
        value: f64,
        /// Allowed range.
        reason: String,
    },
    /// The body mesh cannot be queried.
    #[error("the body mesh cannot be prepared for distance queries")]
    Probe,
}

/// A named plane with where to draw it.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedPlane {
    /// Name.
    pub name: String,
    /// The plane.
    pub plane: Plane,
    /// A point of it near the body (the centre of the drawn square).
    pub centre: DVec3,
    /// Half the drawn square's side, m.
    pub extent: f64,
}

/// A short feature line (seam, junction).
#[derive(Clone, Debug, PartialEq)]
pub struct FeatureLine {
    /// Name.
    pub name: String,
    /// Samples, m (world frame), ends exact.
    pub points: Vec<DVec3>,
}

/// A dimension's value after the solve.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DimensionValue {
    /// Name.
    pub name: String,
    /// Value reached (m, or a fraction).
    pub value: f64,
    /// The value set by the session, if any (same unit as `value`).
    pub target: Option<f64>,
}

/// A contour straightened by the loose fit: its control points before and after.
#[derive(Clone, Debug, PartialEq)]
pub struct Straightened {
    /// Contour.
    pub contour: String,
    /// The contour's points before, m (world frame).
    pub before: Vec<DVec3>,
    /// After, m.
    pub after: Vec<DVec3>,
}

/// A solved framework and its mesh.
#[derive(Clone, Debug)]
pub struct Framework {
    /// Template.
    pub template: TemplateKind,
    /// Its sleeves and collar.
    pub style: Style,
    /// Fit.
    pub fit: Fit,
    /// Planes used.
    pub planes: Vec<NamedPlane>,
    /// Rings, top to bottom.
    pub rings: Vec<GarmentRing>,
    /// Open curves.
    pub open_curves: Vec<OpenCurve>,
    /// Seams and junctions.
    pub lines: Vec<FeatureLine>,
    /// Contours.
    pub contours: Vec<Contour>,
    /// Loose-fit straightening.
    pub straightened: Vec<Straightened>,
    /// Patches.
    pub patches: Vec<PatchGrid>,
    /// The stitched mesh.
    pub m0: M0,
    /// The cleared contour spans its patches were surfaced from.
    pub spans: Spans,
    /// Dimensions reached.
    pub dimensions: Vec<DimensionValue>,
    /// Sample counts of the patches and lines (fixed for the garment's life).
    pub layout: Layout,
    /// The rings as its build made them from their inputs, before any edit moved them:
    /// what a build with a changed dimension takes again where the inputs are the same.
    pub built_rings: Arc<Vec<BuiltRing>>,
}

impl Framework {
    /// A copy of its curves, dimensions and layout, without its surface: no patches, no
    /// M0 and no cleared spans (what an edit's solve changes, before the assembly makes
    /// the surface again; copying the surface cost the solve about a millisecond a drag at
    /// resolution 24).
    pub fn without_surface(&self) -> Framework {
        Framework {
            template: self.template,
            style: self.style,
            fit: self.fit,
            planes: self.planes.clone(),
            rings: self.rings.clone(),
            open_curves: self.open_curves.clone(),
            lines: self.lines.clone(),
            contours: self.contours.clone(),
            straightened: self.straightened.clone(),
            patches: Vec::new(),
            m0: M0::default(),
            spans: Spans::new(),
            dimensions: self.dimensions.clone(),
            layout: self.layout.clone(),
            built_rings: self.built_rings.clone(),
        }
    }

    /// Every feature curve as a dense polyline, by name: rings (closed, their last point
    /// the first again) and open curves by their splines, contours by theirs, seams and
    /// junction lines by their samples, and each contour's spans as the patches took them
    /// (cleared off the body) under the contour's name again. In the framework's order:
    /// rings, open curves, contours, spans, lines.
    pub fn curve_polylines(&self) -> Vec<(String, Vec<DVec3>)> {
        let mut out = Vec::new();
        for r in &self.rings {
            let mut points = r.spline.subdivide(16, true);
            if let Some(&first) = points.first() {
                points.push(first);
            }
            out.push((r.name.clone(), points));
        }
        for c in &self.open_curves {
            out.push((c.name.clone(), c.spline.subdivide(16, false)));
        }
        for c in &self.contours {
            out.push((c.name.clone(), c.polyline()));
        }
        // The contours' spans as the patches use them: cleared off the body where the
        // contour dips in, so that they may stand centimetres off the contour itself.
        for ((name, _, _), span) in &self.spans {
            out.push((name.clone(), span.cleared.clone()));
        }
        for l in &self.lines {
            out.push((l.name.clone(), l.points.clone()));
        }
        out
    }

    /// A ring by name.
    pub fn ring(&self, name: &str) -> Option<&GarmentRing> {
        self.rings.iter().find(|r| r.name == name)
    }

    /// Every named control point (`waist.front`, `left_knee.outer`, `crotch.point`,
    /// `left_strap.top`, ...), in a fixed order.
    pub fn control_points(&self) -> Vec<(String, DVec3)> {
        let mut out: Vec<(String, DVec3)> = self
            .rings
            .iter()
            .flat_map(|r| {
                r.anchors
                    .iter()
                    .map(move |a| (format!("{}.{}", r.name, a.name), a.point))
            })
            .collect();
        for c in &self.open_curves {
            out.push((format!("{}.{}", c.name, c.apex_name), c.apex));
        }
        out
    }

    /// The control points of every feature curve by name: rings and open curves (their
    /// spline control points), contours (the points they pass), seams and junction lines
    /// (their samples).
    pub fn curve_controls(&self) -> BTreeMap<String, Vec<DVec3>> {
        let mut out = BTreeMap::new();
        for r in &self.rings {
            out.insert(r.name.clone(), r.stages.control.clone());
        }
        for c in &self.open_curves {
            out.insert(c.name.clone(), c.stages.control.clone());
        }
        for c in &self.contours {
            out.insert(c.name.clone(), c.points.clone());
        }
        for l in &self.lines {
            out.insert(l.name.clone(), l.points.clone());
        }
        out
    }

    /// The ease (the `ease` dimension), m.
    pub fn ease(&self) -> f64 {
        self.dimension("ease").unwrap_or(0.0)
    }

    /// A dimension's value (m, or a fraction for `strap_position`).
    pub fn dimension(&self, name: &str) -> Option<f64> {
        self.dimensions.iter().find(|d| d.name == name).map(|d| d.value)
    }
}

/// Sample counts of a template's patches and lines, fixed when the garment is built.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// Body height, m.
    pub height: f64,
    /// Clearance of contour spans and seams from the body, m.
    pub clearance: f64,
    /// Weld threshold, m.
    pub weld: f64,
    /// Segments per anchor arc of a ring.
    pub k: usize,
    /// Per-template counts.
    pub counts: Counts,
}

/// Segment counts along the contours of each band.
#[derive(Clone, Debug, PartialEq)]
pub enum Counts {
    /// The jumpsuit.
    Jumpsuit {
        /// Shoulder seam.
        seam: usize,
        /// Neckline arcs of the panels.
        neck: usize,
        /// Thigh-to-hip junction.
        junction: usize,
        /// Inner contour part of the junction.
        inner: usize,
        /// Crotch-curve part of the junction.
        crotch: usize,
        /// Strap halves.
        strap: usize,
        /// Torso bands hip-waist, waist-bust, bust-chest.
        torso: [usize; 3],
        /// Leg bands hem-knee, knee-thigh.
        leg: [usize; 2],
        /// Sleeve bands, armhole to cuff (none without sleeves).
        sleeve: Vec<usize>,
        /// With sleeves, the strap's upper parts (the armhole from `A` to the top); the
        /// lower parts have as many as a ring's anchor arc.
        armhole: usize,
        /// The collar's band, neckline to top (0 without a collar).
        collar: usize,
    },
    /// The dress: bands hem-thigh, thigh-hip, hip-waist.
    Dress([usize; 3]),
}

/// Cleared contour spans by (contour, span from its control point `k`, segments): the
/// spans a framework's patches were surfaced from, kept with it so that the next assembly
/// takes those whose samples did not change instead of clearing them again.
pub type Spans = BTreeMap<(String, usize, usize), Span>;

/// A contour span's samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Span {
    /// On the contour, m.
    pub raw: Vec<DVec3>,
    /// Inner samples cleared off the body, m.
    pub cleared: Vec<DVec3>,
}
