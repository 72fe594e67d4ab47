//! The `patterns` statement: the pattern pieces' settings.

use crate::garment::template;
use crate::garment::{Collar, Sleeves, Style, TemplateKind};
use crate::pattern::{DEFAULT_SEAMS, Method, PatternOptions, Source};
use crate::session::format::args::{Args, number};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::ParseError;

use super::Parser;

impl Parser<'_> {
    /// `patterns [seams=default|NAME,...] [from=m0|m1] [method=arap|lscm] [notches=M]
    /// [boundary=W]`.
    pub(super) fn patterns(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.patterns {
            return Err(line.error(head.column, format!("patterns is already set on line {first}")));
        }
        let a = Args::parse(
            line,
            rest,
            &["seams", "from", "method", "notches", "boundary"],
            "patterns",
        )?;
        let mut o = PatternOptions::default();
        if let Some(t) = a.get("seams")
            && t.text != "default"
        {
            let known = known_seams();
            let mut list = Vec::new();
            let mut column = t.column;
            for name in t.text.split(',') {
                if !known.iter().any(|k| k == name) {
                    return Err(line.error(
                        column,
                        format!(
                            "unknown seam '{name}'{}: expected default or curves such as {}",
                            did_you_mean(name, known.iter().map(String::as_str)),
                            DEFAULT_SEAMS.join(", ")
                        ),
                    ));
                }
                if !list.iter().any(|s: &String| s == name) {
                    list.push(name.to_string());
                }
                column += name.len() + 1;
            }
            o.seams = Some(list);
        }
        if let Some(t) = a.get("from") {
            o.source = match t.text {
                "m0" => Source::M0,
                "m1" => Source::M1,
                other => return Err(line.error(t.column, format!("unknown from '{other}': expected m0 or m1"))),
            };
        }
        if let Some(t) = a.get("method") {
            o.flatten.method = Method::from_name(t.text)
                .ok_or_else(|| line.error(t.column, format!("unknown method '{}': expected arap or lscm", t.text)))?;
        }
        if let Some(t) = a.get("notches") {
            let v = number(line, t, "notches")?;
            if !(0.01..=10.0).contains(&v) {
                return Err(line.error(t.column, format!("notches must be from 0.01 to 10 m apart, found {v}")));
            }
            o.notch_spacing = v;
        }
        if let Some(t) = a.get("boundary") {
            let v = number(line, t, "boundary")?;
            if !(0.0..=1000.0).contains(&v) {
                return Err(line.error(t.column, format!("boundary must be from 0 to 1000, found {v}")));
            }
            o.flatten.boundary_weight = v;
        }
        self.patterns = Some((o, line.number));
        Ok(())
    }
}

/// Every curve name a garment can have: each template's curves in each style, and the
/// default seams.
fn known_seams() -> Vec<String> {
    let mut out: Vec<String> = DEFAULT_SEAMS.iter().map(|s| s.to_string()).collect();
    for kind in TemplateKind::ALL {
        for sleeves in Sleeves::ALL {
            for collar in Collar::ALL {
                let t = template::styled(kind, Style { sleeves, collar });
                out.extend(t.curve_names().into_iter().map(str::to_string));
            }
        }
    }
    out.extend(["seam_left", "seam_right", "junction_left", "junction_right"].map(String::from));
    out.sort();
    out.dedup();
    out
}
