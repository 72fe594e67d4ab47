//! The `drag` step: a control point or a whole curve moved.

use super::Parser;
use crate::constraint::{Edit, Target};
use crate::session::format::args::{Args, vector};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::{Op, ParseError};

impl Parser<'_> {
    /// `drag POINT by=dx,dy,dz | to=x,y,z` or `drag CURVE by=dx,dy,dz`.
    pub(super) fn drag(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        self.refuse_on_mesh(line, head, "control points to drag")?;
        if self.garment.is_none() {
            return Err(line.error(head.column, "'drag' needs a garment: put a 'garment' step before it"));
        }
        let Some((which, args)) = rest.split_first() else {
            return Err(line.error(
                line.end_column,
                "expected a control point (waist.front) or a curve (left_knee) after 'drag'",
            ));
        };
        if which.quoted
            || !which
                .text
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.')
        {
            return Err(line.error(
                which.column,
                format!("expected a point or curve name, found '{}'", which.text),
            ));
        }
        let a = Args::parse(line, args, &["by", "to"], "drag")?;
        let point = which.text.contains('.');
        if let Some((template, style)) = self.garment {
            let spec = crate::garment::template::styled(template, style);
            let (what, known): (&str, Vec<String>) = if point {
                ("control point", spec.point_names())
            } else {
                ("curve", spec.curve_names().iter().map(|c| c.to_string()).collect())
            };
            if !known.iter().any(|k| k == which.text) {
                return Err(line.error(
                    which.column,
                    format!(
                        "unknown {what} '{}' for the {}{}: expected one of {}",
                        which.text,
                        template.name(),
                        did_you_mean(which.text, known.iter().map(String::as_str)),
                        known.join(", ")
                    ),
                ));
            }
        }
        let name = which.text.to_string();
        let edit = match (a.get("by"), a.get("to")) {
            (Some(by), None) => {
                let v = vector(line, by, "by")?;
                if point {
                    Edit::Point {
                        name,
                        target: Target::By(v),
                    }
                } else {
                    Edit::Curve { name, by: v }
                }
            }
            (None, Some(to)) if point => Edit::Point {
                name,
                target: Target::To(vector(line, to, "to")?),
            },
            (None, Some(to)) => {
                return Err(line.error(
                    to.column,
                    "a whole curve is dragged by a vector (by=dx,dy,dz), not to a point",
                ));
            }
            (Some(_), Some(to)) => return Err(line.error(to.column, "give either by= or to=, not both")),
            (None, None) => {
                return Err(line.error(line.end_column, "expected by=dx,dy,dz or to=x,y,z (metres)"));
            }
        };
        self.undoable += 1;
        Ok(Op::Drag(edit))
    }
}
