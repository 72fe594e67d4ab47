//! The `log` statement: what the recording gets.

use super::Parser;
use crate::session::format::args::Args;
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{LogDetail, ParseError};

impl Parser<'_> {
    /// `log detail=all|final|metrics`.
    pub(super) fn log(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.log {
            return Err(line.error(head.column, format!("log is already set on line {first}")));
        }
        let a = Args::parse(line, rest, &["detail"], "log")?;
        let t = a
            .get("detail")
            .ok_or_else(|| line.error(line.end_column, "expected detail=all|final|metrics after 'log'"))?;
        let detail = LogDetail::from_name(t.text).ok_or_else(|| {
            line.error(
                t.column,
                format!("unknown detail '{}': expected all, final or metrics", t.text),
            )
        })?;
        self.log = Some((detail, line.number));
        Ok(())
    }
}
