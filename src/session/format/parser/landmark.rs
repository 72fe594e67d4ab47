//! The `landmark` statement: a landmark's height or point set by hand.

use super::Parser;
use crate::body::{LandmarkKind, LandmarkOverride};
use crate::session::format::args::{Args, number, vector};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::ParseError;

impl Parser<'_> {
    /// `landmark NAME y=H` or `landmark NAME at=x,y,z`.
    pub(super) fn landmark(&mut self, line: &Line<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        let Some((which, args)) = rest.split_first() else {
            return Err(line.error(line.end_column, "expected a landmark name after 'landmark'"));
        };
        let names: Vec<&str> = LandmarkKind::ALL
            .iter()
            .chain(&LandmarkKind::ARMS)
            .map(|k| k.name())
            .collect();
        let kind = LandmarkKind::from_name(which.text).ok_or_else(|| {
            line.error(
                which.column,
                format!(
                    "unknown landmark '{}'{}: expected one of {}",
                    which.text,
                    did_you_mean(which.text, names.iter().copied()),
                    names.join(", ")
                ),
            )
        })?;
        if let Some((_, first)) = self.landmark_lines.iter().find(|(k, _)| *k == kind) {
            return Err(line.error(
                which.column,
                format!("landmark '{}' is already set on line {first}", which.text),
            ));
        }
        let a = Args::parse(line, args, &["y", "at"], "landmark")?;
        let correction = match (a.get("y"), a.get("at")) {
            (Some(y), None) => LandmarkOverride::Height(number(line, y, "y")?),
            (None, Some(at)) => LandmarkOverride::Point(vector(line, at, "at")?),
            (Some(_), Some(at)) => {
                return Err(line.error(at.column, "give either y= or at=, not both"));
            }
            (None, None) => {
                return Err(line.error(line.end_column, "expected y=<height> or at=<x,y,z>"));
            }
        };
        self.landmarks.push((kind, correction));
        self.landmark_lines.push((kind, line.number));
        Ok(())
    }
}
