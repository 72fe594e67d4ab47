//! The `nurbs` step: a NURBS part added from its file.

use super::Parser;
use crate::session::format::args::Args;
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};

impl Parser<'_> {
    /// `nurbs "part.nurbs" name=NAME`: a NURBS part (the name defaults to the file's stem).
    pub(super) fn nurbs(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        let Some((file, args)) = rest.split_first().filter(|(t, _)| t.quoted) else {
            let column = rest.first().map_or(line.end_column, |t| t.column);
            return Err(line.error(column, "expected a quoted .nurbs path after 'nurbs'"));
        };
        let a = Args::parse(line, args, &["name"], "nurbs")?;
        let (path, name) = self.file_and_name(line, (file, a.get("name")), head.column, ("part", "part"))?;
        if let Some((_, first)) = self.nurbs.iter().find(|(n, _)| *n == name) {
            return Err(line.error(
                head.column,
                format!("a part named '{name}' is already added on line {first}"),
            ));
        }
        self.nurbs.push((name.clone(), line.number));
        Ok(Op::Nurbs { name, path })
    }
}
