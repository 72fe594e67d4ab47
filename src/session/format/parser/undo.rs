//! The `undo` step: back to the state before the last garment step.

use super::Parser;
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};

impl Parser<'_> {
    /// `undo`.
    pub(super) fn undo(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        if let Some(extra) = rest.first() {
            return Err(line.error(extra.column, format!("unexpected '{}' after 'undo'", extra.text)));
        }
        if self.undoable == 0 {
            return Err(line.error(
                head.column,
                "nothing to undo: 'undo' takes back a drag, set, cut or sculpt step of the garment",
            ));
        }
        self.undoable -= 1;
        Ok(Op::Undo)
    }
}
