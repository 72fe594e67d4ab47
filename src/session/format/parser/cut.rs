//! The `cut` step: a cut line on the garment.

use crate::m1::CutPlane;
use crate::session::format::args::{Args, vector};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};

use super::Parser;

impl Parser<'_> {
    /// `cut NAME at=x,y,z normal=nx,ny,nz`: a style line, the section of M1 by the plane
    /// through `at` with that normal.
    pub(super) fn cut(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        if self.garment.is_none() {
            return Err(line.error(head.column, "'cut' needs a garment: put a 'garment' step before it"));
        }
        if self.m1.is_none() {
            return Err(line.error(
                head.column,
                "'cut' draws on M1: put an 'm1' statement in the scene (before the first step)",
            ));
        }
        let Some((which, args)) = rest.split_first() else {
            return Err(line.error(line.end_column, "expected a name for the cut line after 'cut'"));
        };
        if which.text.contains('=') || which.text.is_empty() {
            return Err(line.error(
                which.column,
                format!("expected a name for the cut line, found '{}'", which.text),
            ));
        }
        let a = Args::parse(line, args, &["at", "normal"], "cut")?;
        let at = a
            .get("at")
            .ok_or_else(|| line.error(line.end_column, "expected at=x,y,z (a point of the cut's plane)"))?;
        let normal = a
            .get("normal")
            .ok_or_else(|| line.error(line.end_column, "expected normal=nx,ny,nz (the cut plane's normal)"))?;
        let point = vector(line, at, "at")?;
        let n = vector(line, normal, "normal")?;
        if n.length() == 0.0 {
            return Err(line.error(normal.column, "the cut plane's normal must not be zero"));
        }
        self.undoable += 1;
        Ok(Op::Cut {
            name: which.text.to_string(),
            plane: CutPlane { point, normal: n },
        })
    }
}
