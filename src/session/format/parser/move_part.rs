//! The `move` step: a NURBS part moved.

use super::Parser;
use crate::session::format::args::{Args, number, vector};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};
use glam::DVec3;

impl Parser<'_> {
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
