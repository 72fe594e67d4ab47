//! The `nurbs` step: a NURBS part added from its file.

use super::Parser;
use crate::session::format::args::Args;
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};
use std::path::PathBuf;

impl Parser<'_> {
    /// `nurbs "part.nurbs" name=NAME`: a NURBS part (the name defaults to the file's stem).
    pub(super) fn nurbs(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        let Some((file, args)) = rest.split_first().filter(|(t, _)| t.quoted) else {
            let column = rest.first().map_or(line.end_column, |t| t.column);
            return Err(line.error(column, "expected a quoted .nurbs path after 'nurbs'"));
        };
        let a = Args::parse(line, args, &["name"], "nurbs")?;
        let p = PathBuf::from(file.text);
        let path = if p.is_absolute() { p } else { self.base_dir.join(p) };
        let name = match a.get("name") {
            Some(t) => t.text.to_string(),
            None => path
                .file_stem()
                .map_or("part".into(), |s| s.to_string_lossy().into_owned()),
        };
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
            return Err(line.error(
                head.column,
                format!("a part name may hold letters, digits, '_' and '-' only, found '{name}' (give name=...)"),
            ));
        }
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
