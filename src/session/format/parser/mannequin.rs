//! The `mannequin` step: the dress-form study.

use crate::mannequin::MannequinOptions;
use crate::session::format::args::{Args, integer_in};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};

/// `mannequin layers=L points=P subdivisions=K`.
pub(super) fn mannequin(line: &Line<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
    let a = Args::parse(line, rest, &["layers", "points", "subdivisions"], "mannequin")?;
    let mut options = MannequinOptions::default();
    if let Some(t) = a.get("layers") {
        options.layers = integer_in(line, t, "layers", 4..=200)?;
    }
    if let Some(t) = a.get("points") {
        options.points = integer_in(line, t, "points", 6..=360)?;
    }
    if let Some(t) = a.get("subdivisions") {
        options.subdivisions = integer_in(line, t, "subdivisions", 1..=20)?;
    }
    Ok(Op::Mannequin(options))
}
