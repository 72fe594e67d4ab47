//! What a template is ([`Template`]) and what its curves are to the constraint network
//! ([`CurveRoles`]), with the lengths the templates share.

use crate::garment::model::{FeatureLine, Fit, Framework, FrameworkError, Style, TemplateKind};
use crate::garment::probe::BodyProbe;
use crate::garment::solve::{BuildCtx, Parts};
use crate::garment::surface::Surfacer;

/// The thigh ring's drop below the crotch, as a fraction of the body's height (both
/// templates cut their thigh ring there).
pub const THIGH_DROP: f64 = 0.025;

/// Farthest a curve point goes to bridge a gap of the body, as a fraction of the body's
/// height (a gap deeper than this is left, and the collision answers for it).
pub const BRIDGE_REACH: f64 = 0.1;

/// A garment template: what its framework is made of, how it is solved on a body and
/// surfaced, and what its curves are to the constraint layer.
pub trait Template: Sync {
    /// Which template this is.
    fn kind(&self) -> TemplateKind;

    /// Its sleeves and collar.
    fn style(&self) -> Style {
        Style::default()
    }

    /// Its rings, top to bottom.
    fn rings(&self) -> Vec<&'static str>;

    /// Its length dimensions, each with what it measures.
    fn lengths(&self) -> Vec<(&'static str, &'static str)>;

    /// Every dimension a session may set, sorted: `ease`, `<ring>_girth` and `<ring>_ease`
    /// for every ring, and the lengths.
    fn dimension_names(&self) -> Vec<String> {
        let mut names = vec!["ease".to_string()];
        for r in self.rings() {
            names.push(format!("{r}_girth"));
            names.push(format!("{r}_ease"));
        }
        names.extend(self.lengths().iter().map(|(n, _)| n.to_string()));
        names.sort();
        names
    }

    /// Every ring with its anchors, in ring order: the named control points `ring.anchor`.
    fn ring_anchors(&self) -> Vec<(&'static str, &'static [&'static str])>;

    /// The open curves with the name of their apex (`crotch` and `point`).
    fn open_curves(&self) -> Vec<(&'static str, &'static str)> {
        Vec::new()
    }

    /// The contours, by name.
    fn contours(&self) -> Vec<&'static str>;

    /// Every control point a drag may name (`waist.front`, `crotch.point`, ...), in the
    /// order of the curves.
    fn point_names(&self) -> Vec<String> {
        let mut out: Vec<String> = self
            .ring_anchors()
            .iter()
            .flat_map(|(ring, anchors)| anchors.iter().map(move |a| format!("{ring}.{a}")))
            .collect();
        out.extend(self.open_curves().iter().map(|(c, apex)| format!("{c}.{apex}")));
        out
    }

    /// Every curve a drag may move whole: rings, open curves, contours.
    fn curve_names(&self) -> Vec<&'static str> {
        let mut out: Vec<&'static str> = self.ring_anchors().iter().map(|(r, _)| *r).collect();
        out.extend(self.open_curves().iter().map(|(c, _)| *c));
        out.extend(self.contours());
        out
    }

    /// The fit the template is built with when `asked` is asked for (a dress is always
    /// loose below the hip).
    fn fit(&self, asked: Fit) -> Fit {
        asked
    }

    /// Solves the template's curves on the body: planes, rings, open curves, contours, the
    /// loose-fit straightening, and the layout of sample counts.
    ///
    /// # Failures
    /// A dimension out of its range, a section that cannot be cut, a curve that cannot be
    /// fitted.
    fn curves(&self, ctx: &mut BuildCtx<'_>, fit: Fit) -> Result<Parts, FrameworkError>;

    /// The seams and junction lines between the curves (none by default).
    fn lines(&self, _fw: &Framework, _probe: &BodyProbe) -> Result<Vec<FeatureLine>, FrameworkError> {
        Ok(Vec::new())
    }

    /// Surfaces every patch of the framework in `s` (with its `lines`).
    fn patches(&self, s: &mut Surfacer<'_>, lines: &[FeatureLine]) -> Result<(), FrameworkError>;

    /// What the curves are to the constraint layer.
    fn roles(&self) -> CurveRoles;
}

/// What a template's curves are to the constraint network: which curves mirror each
/// other, which rings are centred on the mirror plane, where open curves end, which curve
/// drives another's tangent, and which curve's plane is the mirror plane. The network asks
/// these instead of reading curve names.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CurveRoles {
    /// Curves mirrored left-right, the left one first.
    pub mirrored: Vec<(&'static str, &'static str)>,
    /// Rings centred on the mirror plane, each with its anchors' mirror pairs (the left
    /// member, or a centre anchor paired with itself, first).
    pub centred: Vec<(&'static str, Vec<(&'static str, &'static str)>)>,
    /// Open curves whose ends lie on a ring's anchors.
    pub ends: Vec<EndJoint>,
    /// Directed tangents: an open curve's end drives a contour's top.
    pub tangents: Vec<TangentJoint>,
    /// The open curve whose plane is the body's mirror plane (else the mean `x` of the
    /// rings' `front` anchors is used).
    pub mirror_plane: Option<&'static str>,
    /// Rings of type-I parts (sleeves), positioned along their own axis: their band runs
    /// along their plane's normal, not up the body.
    pub axial: Vec<&'static str>,
}

/// An open curve whose front and back ends lie on a ring's anchors.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EndJoint {
    /// The open curve.
    pub curve: &'static str,
    /// The ring.
    pub ring: &'static str,
    /// The anchors its front and back ends meet.
    pub anchors: [&'static str; 2],
}

/// A contour whose top leaves in the direction of an open curve's end.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TangentJoint {
    /// The open curve (drives).
    pub curve: &'static str,
    /// The contour (driven).
    pub contour: &'static str,
    /// The open curve's front end (or its back end).
    pub front: bool,
}

impl CurveRoles {
    /// The ends of open curve `name`, if they lie on a ring.
    pub fn ends_of(&self, name: &str) -> Option<&EndJoint> {
        self.ends.iter().find(|e| e.curve == name)
    }

    /// The mirror pairs of ring `name`'s anchors, if it is centred.
    pub fn centred_pairs(&self, name: &str) -> Option<&[(&'static str, &'static str)]> {
        self.centred.iter().find(|(r, _)| *r == name).map(|(_, p)| p.as_slice())
    }

    /// The right-hand partner of curve `name`, if it is the left member of a mirrored pair.
    pub fn right_of(&self, name: &str) -> Option<&'static str> {
        self.mirrored.iter().find(|(l, _)| *l == name).map(|(_, r)| *r)
    }
}
