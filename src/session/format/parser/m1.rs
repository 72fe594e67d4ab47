//! The `m1` statement: the display mesh's settings.

use crate::m1::{M1Options, Rule, Smoothing};
use crate::session::format::args::{Args, integer_in, number};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::ParseError;

use super::Parser;

impl Parser<'_> {
    /// `m1 [steps=1|2] [patches=selected|all] [rules=stretch,angle,edges,body]
    /// [smooth=none|kobbelt] [stretch=R] [angle=DEG] [long=K1] [short=K2] [body=K]`.
    pub(super) fn m1(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.m1 {
            return Err(line.error(head.column, format!("m1 is already set on line {first}")));
        }
        let keys = [
            "steps", "patches", "rules", "smooth", "stretch", "angle", "long", "short", "body",
        ];
        let a = Args::parse(line, rest, &keys, "m1")?;
        let mut o = M1Options::default();
        if let Some(t) = a.get("steps") {
            o.steps = integer_in(line, t, "steps", 1..=2)?;
        }
        if let Some(t) = a.get("patches") {
            o.all_patches = match t.text {
                "selected" => false,
                "all" => true,
                other => {
                    return Err(line.error(t.column, format!("unknown patches '{other}': expected selected or all")));
                }
            };
        }
        if let Some(t) = a.get("rules") {
            let mut rules = Vec::new();
            let mut column = t.column;
            for name in t.text.split(',') {
                let rule = Rule::from_name(name).ok_or_else(|| {
                    line.error(
                        column,
                        format!(
                            "unknown rule '{name}'{}: expected some of stretch, angle, edges, body",
                            did_you_mean(name, Rule::ALL.map(Rule::name))
                        ),
                    )
                })?;
                if !rules.contains(&rule) {
                    rules.push(rule);
                }
                column += name.len() + 1;
            }
            o.select.rules = rules;
        }
        if let Some(t) = a.get("smooth") {
            o.smoothing = Smoothing::from_name(t.text).ok_or_else(|| {
                line.error(
                    t.column,
                    format!("unknown smooth '{}': expected none or kobbelt", t.text),
                )
            })?;
        }
        let positive = |key: &str, least: f64, most: f64| -> Result<Option<f64>, ParseError> {
            let Some(t) = a.get(key) else { return Ok(None) };
            let v = number(line, t, key)?;
            if !(least..=most).contains(&v) {
                return Err(line.error(t.column, format!("{key} must be from {least} to {most}, found {v}")));
            }
            Ok(Some(v))
        };
        if let Some(v) = positive("stretch", 1.0, 100.0)? {
            o.select.stretch = v;
        }
        if let Some(v) = positive("angle", 0.0, 180.0)? {
            o.select.angle_deg = v;
        }
        if let Some(v) = positive("long", 1.0, 100.0)? {
            o.select.long_edge = v;
        }
        if let Some(v) = positive("short", 0.0, 1.0)? {
            o.select.short_edge = v;
        }
        if let Some(v) = positive("body", 0.0, 1000.0)? {
            o.select.body_edge = v;
        }
        self.m1 = Some((o, line.number));
        Ok(())
    }
}
