//! The `drape 1` statement: the format's version, required first.

use super::Parser;
use crate::session::format::args::one_argument;
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::ParseError;

impl Parser<'_> {
    /// `drape 1`, the required first statement.
    pub(super) fn version(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if head.text != "drape" || head.quoted {
            return Err(line.error(
                head.column,
                format!("expected 'drape 1' as the first statement, found '{}'", head.text),
            ));
        }
        let v = one_argument(line, rest, ("drape", "version"), "a format version (drape 1)")?;
        if v.text != "1" {
            return Err(line.error(
                v.column,
                format!("unsupported format version '{}': this drape reads version 1", v.text),
            ));
        }
        self.version_seen = true;
        Ok(())
    }
}
