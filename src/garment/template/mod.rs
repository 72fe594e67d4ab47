//! Garment templates: one module per template, each owning its curves, patches, anchor
//! names, dimensions and the roles its curves play in the constraint network, behind one
//! [`Template`] trait.
//!
//! * [`Jumpsuit`] (sleeveless): a torso tube (hip, waist, bust and chest rings; centre
//!   front and back, side and princess contours), two leg tubes (thigh, knee and hem rings;
//!   front, outer, back and inner contours), the crotch junction (the crotch curve in the
//!   vertical crotch plane, and the junction from the crotch point to each thigh), and
//!   front and back panels up to the neckline, held by straps over the shoulders. The
//!   armholes and the neckline are boundary curves.
//! * [`Dress`] (a skirt from the waist): one tube, waist, hip, thigh and hem rings; the
//!   rings below the hip wrap both legs, and the contours below the hip are straight.
//!
//! Every size comes from the body's landmarks: heights, and the default ease as a fraction
//! of the body's height. A new template is a new module here implementing [`Template`], a
//! [`TemplateKind`] variant and one arm in [`of`].

mod dress;
mod jumpsuit;
mod spec;

pub use dress::Dress;
pub use jumpsuit::Jumpsuit;
pub use spec::{BRIDGE_REACH, CurveRoles, EndJoint, THIGH_DROP, TangentJoint, Template};

use super::model::TemplateKind;

/// The template of a kind.
pub fn of(kind: TemplateKind) -> &'static dyn Template {
    match kind {
        TemplateKind::Jumpsuit => &Jumpsuit,
        TemplateKind::Dress => &Dress,
    }
}
