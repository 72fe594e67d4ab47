//! The `body` statement: the body the session runs on.

use super::Parser;
use crate::body::BodySource;
use crate::session::format::args::one_argument;
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::ParseError;
use std::path::PathBuf;

impl Parser<'_> {
    /// `body builtin` or `body "path.obj"`.
    pub(super) fn body(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.body {
            return Err(line.error(head.column, format!("the body is already set on line {first}")));
        }
        let t = one_argument(line, rest, ("body", "body"), "'builtin' or a quoted OBJ path")?;
        let source = match t {
            t if !t.quoted && t.text == "builtin" => BodySource::Builtin,
            t if t.quoted => {
                let p = PathBuf::from(t.text);
                BodySource::File(if p.is_absolute() { p } else { self.base_dir.join(p) })
            }
            t => {
                return Err(line.error(
                    t.column,
                    format!("expected 'builtin' or a quoted OBJ path, found '{}'", t.text),
                ));
            }
        };
        self.body = Some((source, line.number));
        Ok(())
    }
}
