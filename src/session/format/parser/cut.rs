//! The `cut` step: a cut line on the garment.

use crate::m1::CutPlane;
use crate::session::format::args::{Args, vector};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};

use super::Parser;

impl Parser<'_> {
    /// `cut NAME at=x,y,z normal=nx,ny,nz`: a style line, the section of M1 by the plane
    /// through `at` with that normal; `cut NAME through=x,y,z;x,y,z;...`: a cut line through
    /// picked points of the garment (at least two), a seam of its pattern.
    pub(super) fn cut(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        if !self.has_garment() {
            return Err(line.error(head.column, "'cut' needs a garment: put a 'garment' step before it"));
        }
        if let Some((which, args)) = rest.split_first()
            && let Some(through) = args.iter().find(|t| t.text.starts_with("through="))
        {
            if let Some(at) = self.mesh_garment {
                return Err(line.error(
                    through.column,
                    format!(
                        "a cut through points is a seam of the pattern, and the garment of line {at} (a mesh from a \
                         file) has no seam curves to cut a pattern along: cut it with a plane (at=x,y,z normal=x,y,z)"
                    ),
                ));
            }
            if self.patterns.is_none() {
                return Err(line.error(
                    through.column,
                    "a cut through points is a seam of the pattern: put a 'patterns' statement in the scene",
                ));
            }
            let a = Args::parse(line, args, &["through"], "cut")?;
            let t = a
                .get("through")
                .ok_or_else(|| line.error(line.end_column, "expected through=x,y,z;x,y,z"))?;
            let mut points = Vec::new();
            let mut column = t.column;
            for part in t.text.split(';') {
                points.push(vector(
                    line,
                    Token {
                        text: part,
                        column,
                        quoted: false,
                    },
                    "through",
                )?);
                column += part.len() + 1;
            }
            if points.len() < 2 {
                return Err(line.error(t.column, "a cut through points needs at least two: through=x,y,z;x,y,z"));
            }
            if which.text.contains('=') || which.text.is_empty() {
                return Err(line.error(
                    which.column,
                    format!("expected a name for the cut line, found '{}'", which.text),
                ));
            }
            self.undoable += 1;
            return Ok(Op::CutThrough {
                name: which.text.to_string(),
                points,
            });
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
