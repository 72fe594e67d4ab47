//! The `garment` step: a garment built from its template.

use super::Parser;
use crate::garment::{ContourKind, Fit, TemplateKind};
use crate::session::format::args::{Args, integer_in};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::{Op, ParseError};

impl Parser<'_> {
    /// `garment jumpsuit|dress fit=tight|loose contours=local|natural resolution=N`.
    pub(super) fn garment(&mut self, line: &Line<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        let Some((which, args)) = rest.split_first() else {
            return Err(line.error(
                line.end_column,
                "expected a template after 'garment' (jumpsuit or dress)",
            ));
        };
        let names: Vec<&str> = TemplateKind::ALL.iter().map(|t| t.name()).collect();
        let template = TemplateKind::from_name(which.text).ok_or_else(|| {
            line.error(
                which.column,
                format!(
                    "unknown template '{}'{}: expected one of {}",
                    which.text,
                    did_you_mean(which.text, names.iter().copied()),
                    names.join(", ")
                ),
            )
        })?;
        let a = Args::parse(line, args, &["fit", "contours", "resolution"], "garment")?;
        let fit = match a.get("fit") {
            None => Fit::Tight,
            Some(t) => Fit::from_name(t.text)
                .ok_or_else(|| line.error(t.column, format!("unknown fit '{}': expected tight or loose", t.text)))?,
        };
        let contours = match a.get("contours") {
            None => ContourKind::default(),
            Some(t) => ContourKind::from_name(t.text).ok_or_else(|| {
                line.error(
                    t.column,
                    format!("unknown contours '{}': expected local or natural", t.text),
                )
            })?,
        };
        let resolution = match a.get("resolution") {
            None => 6,
            Some(t) => integer_in(line, t, "resolution", 2..=24)?,
        };
        self.garment = Some(template);
        self.undoable = 0;
        Ok(Op::Garment {
            template,
            fit,
            contours,
            resolution,
        })
    }
}
