//! Garment templates: which rings, curves, contours and patches make a garment, and the
//! named dimensions a session can set.
//!
//! * **Jumpsuit** (sleeveless): a torso tube (hip, waist, bust and chest rings; centre
//!   front and back, side and princess contours), two leg tubes (thigh, knee and hem rings;
//!   front, outer, back and inner contours), the crotch junction (the crotch curve in the
//!   vertical crotch plane, and the junction from the crotch point to each thigh), and
//!   front and back panels up to the neckline, held by straps over the shoulders. The
//!   armholes and the neckline are boundary curves.
//! * **Dress** (a skirt from the waist): one tube, waist, hip, thigh and hem rings; the
//!   rings below the hip wrap both legs, and the contours below the hip are straight.
//!
//! Every size comes from the body's landmarks: heights, and the default ease as a fraction
//! of the body's height.

use std::collections::BTreeMap;

/// The garments drape can build.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
pub enum TemplateKind {
    /// Sleeveless jumpsuit.
    Jumpsuit,
    /// Skirt or dress from the waist.
    Dress,
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

/// Rings of the jumpsuit, top to bottom.
pub const JUMPSUIT_RINGS: [&str; 11] = [
    "neckline",
    "chest",
    "bust",
    "waist",
    "hip",
    "left_thigh",
    "right_thigh",
    "left_knee",
    "right_knee",
    "left_hem",
    "right_hem",
];

/// Rings of the dress, top to bottom.
pub const DRESS_RINGS: [&str; 4] = ["waist", "hip", "thigh", "hem"];

impl TemplateKind {
    /// Every template.
    pub const ALL: [Self; 2] = [Self::Jumpsuit, Self::Dress];

    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Jumpsuit => "jumpsuit",
            Self::Dress => "dress",
        }
    }

    /// From the session spelling.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }

    /// The template's rings.
    pub fn rings(self) -> &'static [&'static str] {
        match self {
            Self::Jumpsuit => &JUMPSUIT_RINGS,
            Self::Dress => &DRESS_RINGS,
        }
    }

    /// Its length dimensions with what they measure.
    pub fn lengths(self) -> &'static [(&'static str, &'static str)] {
        match self {
            Self::Jumpsuit => &[
                (
                    "inseam",
                    "crotch height minus hem height, m (default: down to the ankles)",
                ),
                ("neck_rise", "neckline above the neck-base plane, m (default 0)"),
                (
                    "strap_position",
                    "where the straps cross the shoulder, 0 at the side neck to 1 at the shoulder point (default 0.5)",
                ),
            ],
            Self::Dress => &[(
                "length",
                "waist height minus hem height, m (default: down to the knees)",
            )],
        }
    }

    /// Every dimension name a session may set, sorted.
    pub fn dimension_names(self) -> Vec<String> {
        let mut names = vec!["ease".to_string()];
        for r in self.rings() {
            names.push(format!("{r}_girth"));
            names.push(format!("{r}_ease"));
        }
        names.extend(self.lengths().iter().map(|(n, _)| n.to_string()));
        names.sort();
        names
    }
}

/// Dimension values a session has set (the rest come from the body).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Dimensions {
    /// Name to value (m, or a fraction for `strap_position`).
    pub values: BTreeMap<String, f64>,
}

impl Dimensions {
    /// A value if set.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.get(name).copied()
    }
}
