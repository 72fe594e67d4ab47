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

pub mod collar;
mod dress;
mod jumpsuit;
pub mod sleeve;
mod spec;

pub use dress::Dress;
pub use jumpsuit::Jumpsuit;
pub use spec::{BRIDGE_REACH, CurveRoles, EndJoint, THIGH_DROP, TangentJoint, Template};

use super::model::{Collar, Sleeves, Style, TemplateKind};

/// Every jumpsuit (legs) and shirt (no legs), by legs, sleeves and collar.
static BODICES: [[[Jumpsuit; 2]; 3]; 2] = {
    const fn row(legs: bool, sleeves: Sleeves) -> [Jumpsuit; 2] {
        [
            Jumpsuit::new(legs, sleeves, Collar::None),
            Jumpsuit::new(legs, sleeves, Collar::Stand),
        ]
    }
    const fn set(legs: bool) -> [[Jumpsuit; 2]; 3] {
        [
            row(legs, Sleeves::None),
            row(legs, Sleeves::Short),
            row(legs, Sleeves::Long),
        ]
    }
    [set(false), set(true)]
};

/// The template of a kind, without sleeves or a collar.
pub fn of(kind: TemplateKind) -> &'static dyn Template {
    styled(kind, Style::default())
}

/// The template of a kind with `style` (the dress takes none: its style is ignored).
pub fn styled(kind: TemplateKind, style: Style) -> &'static dyn Template {
    let sleeves = match style.sleeves {
        Sleeves::None => 0,
        Sleeves::Short => 1,
        Sleeves::Long => 2,
    };
    let collar = usize::from(style.collar == Collar::Stand);
    match kind {
        TemplateKind::Jumpsuit => &BODICES[1][sleeves][collar],
        TemplateKind::Shirt => &BODICES[0][sleeves][collar],
        TemplateKind::Dress => &Dress,
    }
}
