//! The `units` statement: the units of the body file's coordinates.

use super::Parser;
use crate::session::format::args::one_argument;
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{ParseError, Units};

impl Parser<'_> {
    /// `units m|cm|mm`.
    pub(super) fn units(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.units {
            return Err(line.error(head.column, format!("units are already set on line {first}")));
        }
        let t = one_argument(line, rest, ("units", "units"), "km, m, cm or mm")?;
        let u = match t.text {
            "km" => Units::Kilometres,
            "m" => Units::Metres,
            "cm" => Units::Centimetres,
            "mm" => Units::Millimetres,
            other => return Err(line.error(t.column, format!("unknown units '{other}': expected km, m, cm or mm"))),
        };
        self.units = Some((u, line.number));
        Ok(())
    }
}
