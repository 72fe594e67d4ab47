//! The garment steps: `garment` (a new garment) and `set` (a dimension changed).

use crate::garment::{ContourKind, Fit, TemplateKind};
use crate::session::format::args::{Args, integer_in, number};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::{Change, Op, ParseError};

use super::Parser;

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

    /// `set NAME +d | -d | value`.
    pub(super) fn set(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        let Some(template) = self.garment else {
            return Err(line.error(head.column, "'set' needs a garment: put a 'garment' step before it"));
        };
        let (which, value) = match rest {
            [w, v] => (*w, *v),
            [] | [_] => {
                return Err(line.error(
                    line.end_column,
                    "expected a dimension and a value: set NAME +0.04 (or -0.04, or 0.74)",
                ));
            }
            [_, _, extra, ..] => {
                return Err(line.error(extra.column, format!("unexpected '{}' after the value", extra.text)));
            }
        };
        let known = crate::garment::template::of(template).dimension_names();
        if !known.iter().any(|k| k == which.text) {
            return Err(line.error(
                which.column,
                format!(
                    "unknown dimension '{}' for the {}{}: expected one of {}",
                    which.text,
                    template.name(),
                    did_you_mean(which.text, known.iter().map(String::as_str)),
                    known.join(", ")
                ),
            ));
        }
        let v = number(line, value, "the value")?;
        let change = if value.text.starts_with(['+', '-']) {
            Change::By(v)
        } else {
            Change::To(v)
        };
        self.undoable += 1;
        Ok(Op::Set {
            name: which.text.to_string(),
            change,
        })
    }
}
