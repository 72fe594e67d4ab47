//! The `set` step: a dimension changed.

use super::Parser;
use crate::session::format::args::number;
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::{Change, Op, ParseError};

impl Parser<'_> {
    /// `set NAME +d | -d | value`.
    pub(super) fn set(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        self.refuse_on_mesh(line, head, "dimensions to set")?;
        let Some((template, style)) = self.garment else {
            return Err(line.error(head.column, "'set' needs a garment: put a 'garment' step before it"));
        };
        let (which, value) = match rest {
            [w, v] => (*w, *v),
            [] | [_] => {
                return Err(line.error(
                    line.end_column,
                    "expected a dimension and a value: set NAME +0.04 (or -0.04, or 0.74)",
                ));
            }
            [_, _, extra, ..] => {
                return Err(line.error(extra.column, format!("unexpected '{}' after the value", extra.text)));
            }
        };
        let known = crate::garment::template::styled(template, style).dimension_names();
        if !known.iter().any(|k| k == which.text) {
            return Err(line.error(
                which.column,
                format!(
                    "unknown dimension '{}' for the {}{}: expected one of {}",
                    which.text,
                    template.name(),
                    did_you_mean(which.text, known.iter().map(String::as_str)),
                    known.join(", ")
                ),
            ));
        }
        let v = number(line, value, "the value")?;
        let change = if value.text.starts_with(['+', '-']) {
            Change::By(v)
        } else {
            Change::To(v)
        };
        self.undoable += 1;
        Ok(Op::Set {
            name: which.text.to_string(),
            change,
        })
    }
}
