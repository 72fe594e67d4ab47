//! The `sculpt` step.

use crate::session::format::args::{Args, integer_in, number, vector};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::{Op, ParseError, SculptAt};
use glam::DVec3;

use super::Parser;

impl Parser<'_> {
    /// `sculpt at=x,y,z radius=R peak=H [dir=x,y,z] [falloff=NAME] [eps=E] [levels=N]
    /// [weight=W]`: lengths in m.
    pub(super) fn sculpt(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        use crate::sculpt::{AdaptiveOptions, Drag, Falloff, SculptOptions};
        if !self.has_garment() {
            return Err(line.error(head.column, "'sculpt' needs a garment: put a 'garment' step before it"));
        }
        let a = Args::parse(
            line,
            rest,
            &["at", "radius", "peak", "dir", "falloff", "eps", "levels", "weight"],
            "sculpt",
        )?;
        let required = |key: &str, what: &str| {
            a.get(key)
                .ok_or_else(|| line.error(head.column, format!("'sculpt' needs {key}= ({what})")))
        };
        let at_token = required(
            "at",
            "a control point such as waist.front, or the pick point x,y,z in m",
        )?;
        // `at=outer:waist.front`: the sculpt is the named garment's.
        let at_token = self.named(line, at_token)?;
        let at = if at_token.text.chars().any(|c| c.is_ascii_alphabetic()) {
            if let Some(at) = self.mesh_garment {
                return Err(line.error(
                    at_token.column,
                    format!(
                        "the garment of line {at} is a mesh from a file and has no control point '{}': give the \
                         pick point, at=x,y,z in m",
                        at_token.text
                    ),
                ));
            }
            let names = self
                .garment
                .map(|(t, style)| crate::garment::template::styled(t, style).point_names())
                .unwrap_or_default();
            if !names.iter().any(|n| n == at_token.text) {
                return Err(line.error(
                    at_token.column,
                    format!(
                        "unknown control point '{}'{}: expected x,y,z or one of {}",
                        at_token.text,
                        did_you_mean(at_token.text, names.iter().map(String::as_str)),
                        names.join(", ")
                    ),
                ));
            }
            SculptAt::Control(at_token.text.to_string())
        } else {
            SculptAt::Point(vector(line, at_token, "at")?)
        };
        let positive = |t: Token<'_>, what: &str| {
            let v = number(line, t, what)?;
            if v > 0.0 {
                Ok(v)
            } else {
                Err(line.error(
                    t.column,
                    format!("{what} must be a positive length in m, found '{}'", t.text),
                ))
            }
        };
        let radius = positive(required("radius", "the radius in m")?, "the radius")?;
        let peak = number(line, required("peak", "the peak offset in m")?, "the peak")?;
        let direction = match a.get("dir") {
            Some(t) => {
                let d = vector(line, t, "dir")?;
                if d.length() == 0.0 {
                    return Err(line.error(t.column, "dir must not be zero"));
                }
                Some(d)
            }
            None => None,
        };
        let falloff = match a.get("falloff") {
            Some(t) => Falloff::from_name(t.text).ok_or_else(|| {
                let names: Vec<&str> = Falloff::ALL.iter().map(|f| f.name()).collect();
                line.error(
                    t.column,
                    format!("unknown falloff '{}': expected one of {}", t.text, names.join(", ")),
                )
            })?,
            None => Falloff::default(),
        };
        let epsilon = a.get("eps").map(|t| positive(t, "eps")).transpose()?;
        let max_levels = a
            .get("levels")
            .map(|t| integer_in(line, t, "levels", 0..=8))
            .transpose()?
            .unwrap_or(AdaptiveOptions::MAX_LEVELS);
        let weight = match a.get("weight") {
            Some(t) => {
                let w = number(line, t, "the weight")?;
                if !(0.0..=1.0).contains(&w) {
                    return Err(line.error(t.column, format!("the weight must be from 0 to 1, found '{}'", t.text)));
                }
                w
            }
            None => 1.0,
        };
        self.undoable += 1;
        Ok(Op::Sculpt {
            at,
            drag: Drag {
                at: DVec3::ZERO,
                radius,
                peak,
                direction,
                falloff,
            },
            options: SculptOptions {
                epsilon,
                max_levels,
                weight,
            },
        })
    }
}
