//! Every statement of the session format, in one table: its keyword and whether it belongs
//! to the scene or is a step. The parser dispatches on [`Statement`] (a new statement does
//! not compile until it has a parser arm), an [`crate::session::Op`] names its statement,
//! and the messages ("unknown statement", "did you mean") list the table.

/// Where a statement stands in a session.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// Before the first step: what the session runs on and how.
    Scene,
    /// A step, run in order.
    Step,
}

/// A statement of the session format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Statement {
    /// `drape 1`, the format's version.
    Drape,
    /// `body builtin | "FILE"`.
    Body,
    /// `units km|m|cm|mm`.
    Units,
    /// `landmark KIND y=... | at=...`.
    Landmark,
    /// `solver chains=... passes=...`.
    Solver,
    /// `m1 ...`, the display mesh's settings.
    M1,
    /// `log all|final|metrics`.
    Log,
    /// `mannequin ...`, the dress-form study.
    Mannequin,
    /// `section y=... name=...`, a body section.
    Section,
    /// `garment TEMPLATE ...`.
    Garment,
    /// `set DIMENSION VALUE`.
    Set,
    /// `drag NAME by=... | to=...`.
    Drag,
    /// `undo`.
    Undo,
    /// `patterns ...`, the pattern pieces' settings.
    Patterns,
    /// `cut NAME ...`, a cut line.
    Cut,
    /// `nurbs "FILE" name=...`.
    Nurbs,
    /// `move NAME by=... turn=...`, a NURBS part moved.
    Move,
    /// `sculpt at=... radius=... peak=...`.
    Sculpt,
}

impl Statement {
    /// The table: every statement with its keyword and place, scene statements first, in
    /// the order the messages list them.
    pub const ALL: &'static [(Statement, &'static str, Place)] = &[
        (Self::Drape, "drape", Place::Scene),
        (Self::Body, "body", Place::Scene),
        (Self::Units, "units", Place::Scene),
        (Self::Landmark, "landmark", Place::Scene),
        (Self::Solver, "solver", Place::Scene),
        (Self::M1, "m1", Place::Scene),
        (Self::Patterns, "patterns", Place::Scene),
        (Self::Log, "log", Place::Scene),
        (Self::Mannequin, "mannequin", Place::Step),
        (Self::Section, "section", Place::Step),
        (Self::Garment, "garment", Place::Step),
        (Self::Set, "set", Place::Step),
        (Self::Drag, "drag", Place::Step),
        (Self::Undo, "undo", Place::Step),
        (Self::Cut, "cut", Place::Step),
        (Self::Nurbs, "nurbs", Place::Step),
        (Self::Move, "move", Place::Step),
        (Self::Sculpt, "sculpt", Place::Step),
    ];

    /// The statement a keyword starts.
    pub fn from_keyword(word: &str) -> Option<Self> {
        Self::ALL.iter().find(|(_, k, _)| *k == word).map(|(s, _, _)| *s)
    }

    /// Its keyword.
    pub fn keyword(self) -> &'static str {
        Self::ALL.iter().find(|(s, _, _)| *s == self).map_or("", |(_, k, _)| k)
    }

    /// Where it stands.
    pub fn place(self) -> Place {
        Self::ALL
            .iter()
            .find(|(s, _, _)| *s == self)
            .map_or(Place::Step, |(_, _, p)| *p)
    }

    /// The keywords of one place, in the table's order.
    pub fn keywords(place: Place) -> impl Iterator<Item = &'static str> {
        Self::ALL
            .iter()
            .filter(move |(_, _, p)| *p == place)
            .map(|(_, k, _)| *k)
    }
}
