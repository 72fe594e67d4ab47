//! The `garment` step: a garment built from its template.

use super::Parser;
use crate::garment::{Collar, ContourKind, Fit, Sleeves, TemplateKind};
use crate::session::format::args::{Args, integer_in};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::{Op, ParseError};

impl Parser<'_> {
    /// `garment jumpsuit|dress|shirt sleeves=none|short|long collar=none|stand
    /// fit=tight|loose contours=local|natural resolution=N name=NAME over=NAME`.
    pub(super) fn garment(&mut self, line: &Line<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        let Some((which, args)) = rest.split_first() else {
            return Err(line.error(
                line.end_column,
                "expected a template after 'garment' (jumpsuit, dress or shirt)",
            ));
        };
        if which.text == "mesh" && !which.quoted {
            return self.garment_mesh(line, which, args);
        }
        let names: Vec<&str> = TemplateKind::ALL.iter().map(|t| t.name()).collect();
        let template = TemplateKind::from_name(which.text).ok_or_else(|| {
            line.error(
                which.column,
                format!(
                    "unknown template '{}'{}: expected one of {}, or mesh \"FILE\" for a garment from a file",
                    which.text,
                    did_you_mean(which.text, names.iter().copied().chain(["mesh"])),
                    names.join(", ")
                ),
            )
        })?;
        let a = Args::parse(
            line,
            args,
            &["sleeves", "collar", "fit", "contours", "resolution", "name", "over"],
            "garment",
        )?;
        let mut style = template.default_style();
        for (key, t) in [("sleeves", a.get("sleeves")), ("collar", a.get("collar"))] {
            let Some(t) = t else { continue };
            if !template.takes_style() {
                return Err(line.error(
                    t.column,
                    format!("the {} takes no {key}: it starts at the waist", template.name()),
                ));
            }
            if key == "sleeves" {
                style.sleeves = Sleeves::from_name(t.text).ok_or_else(|| {
                    line.error(
                        t.column,
                        format!("unknown sleeves '{}': expected none, short or long", t.text),
                    )
                })?;
            } else {
                style.collar = Collar::from_name(t.text).ok_or_else(|| {
                    line.error(t.column, format!("unknown collar '{}': expected none or stand", t.text))
                })?;
            }
        }
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
        let (name, column) = a
            .get("name")
            .map_or((template.name(), which.column), |t| (t.text, t.column));
        let over = self.wear(
            line,
            (name, column),
            a.get("over").as_ref(),
            (Some((template, style)), None),
        )?;
        Ok(Op::Garment {
            template,
            style,
            fit,
            contours,
            resolution,
            layer: crate::session::format::syntax::Layer {
                name: name.to_string(),
                over,
            },
        })
    }
}
