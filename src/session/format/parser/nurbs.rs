//! The NURBS steps: `nurbs` (a part) and `move` (a part moved).

use crate::session::format::args::{Args, number, vector};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};
use glam::DVec3;
use std::path::PathBuf;

use super::Parser;

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

    /// `move NAME by=x,y,z turn=DEG`: moves a NURBS part (m) and turns it about the vertical
    /// through its centre (degrees).
    pub(super) fn move_part(
        &mut self,
        line: &Line<'_>,
        head: &Token<'_>,
        rest: &[Token<'_>],
    ) -> Result<Op, ParseError> {
        let Some((which, args)) = rest.split_first() else {
            return Err(line.error(line.end_column, "expected the name of a NURBS part after 'move'"));
        };
        if !self.nurbs.iter().any(|(n, _)| n == which.text) {
            let known: Vec<&str> = self.nurbs.iter().map(|(n, _)| n.as_str()).collect();
            return Err(line.error(
                which.column,
                if known.is_empty() {
                    format!(
                        "no NURBS part '{}': add one first with nurbs \"FILE\" name=...",
                        which.text
                    )
                } else {
                    format!("no NURBS part '{}': the parts are {}", which.text, known.join(", "))
                },
            ));
        }
        let a = Args::parse(line, args, &["by", "turn"], "move")?;
        let by = a.get("by").map(|t| vector(line, t, "by")).transpose()?;
        let turn = a.get("turn").map(|t| number(line, t, "turn")).transpose()?;
        if by.is_none() && turn.is_none() {
            return Err(line.error(head.column, "expected by=x,y,z (m) or turn=DEG for 'move'"));
        }
        Ok(Op::Move {
            name: which.text.to_string(),
            by: by.unwrap_or(DVec3::ZERO),
            turn_deg: turn.unwrap_or(0.0),
        })
    }
}
