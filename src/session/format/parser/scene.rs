//! The scene statements: `drape` (the version), `body`, `units`, `landmark`, `log`, `solver`.

use crate::body::{BodySource, LandmarkKind, LandmarkOverride};
use crate::constraint::{Chains, SolverOptions};
use crate::session::format::args::{Args, integer_in, number, one_argument, vector};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::{LogDetail, ParseError, Units};
use std::path::PathBuf;

use super::Parser;

impl Parser<'_> {
    /// `drape 1`, the required first statement.
    pub(super) fn version(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if head.text != "drape" || head.quoted {
            return Err(line.error(
                head.column,
                format!("expected 'drape 1' as the first statement, found '{}'", head.text),
            ));
        }
        let v = one_argument(line, rest, ("drape", "version"), "a format version (drape 1)")?;
        if v.text != "1" {
            return Err(line.error(
                v.column,
                format!("unsupported format version '{}': this drape reads version 1", v.text),
            ));
        }
        self.version_seen = true;
        Ok(())
    }

    /// `body builtin` or `body "path.obj"`.
    pub(super) fn body(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.body {
            return Err(line.error(head.column, format!("the body is already set on line {first}")));
        }
        let t = one_argument(line, rest, ("body", "body"), "'builtin' or a quoted OBJ path")?;
        let source = match t {
            t if !t.quoted && t.text == "builtin" => BodySource::Builtin,
            t if t.quoted => {
                let p = PathBuf::from(t.text);
                BodySource::File(if p.is_absolute() { p } else { self.base_dir.join(p) })
            }
            t => {
                return Err(line.error(
                    t.column,
                    format!("expected 'builtin' or a quoted OBJ path, found '{}'", t.text),
                ));
            }
        };
        self.body = Some((source, line.number));
        Ok(())
    }

    /// `units m|cm|mm`.
    pub(super) fn units(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.units {
            return Err(line.error(head.column, format!("units are already set on line {first}")));
        }
        let t = one_argument(line, rest, ("units", "units"), "km, m, cm or mm")?;
        let u = match t.text {
            "km" => Units::Kilometres,
            "m" => Units::Metres,
            "cm" => Units::Centimetres,
            "mm" => Units::Millimetres,
            other => return Err(line.error(t.column, format!("unknown units '{other}': expected km, m, cm or mm"))),
        };
        self.units = Some((u, line.number));
        Ok(())
    }

    /// `landmark NAME y=H` or `landmark NAME at=x,y,z`.
    pub(super) fn landmark(&mut self, line: &Line<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        let Some((which, args)) = rest.split_first() else {
            return Err(line.error(line.end_column, "expected a landmark name after 'landmark'"));
        };
        let names: Vec<&str> = LandmarkKind::ALL.iter().map(|k| k.name()).collect();
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

    /// `log detail=all|final|metrics`.
    pub(super) fn log(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.log {
            return Err(line.error(head.column, format!("log is already set on line {first}")));
        }
        let a = Args::parse(line, rest, &["detail"], "log")?;
        let t = a
            .get("detail")
            .ok_or_else(|| line.error(line.end_column, "expected detail=all|final|metrics after 'log'"))?;
        let detail = LogDetail::from_name(t.text).ok_or_else(|| {
            line.error(
                t.column,
                format!("unknown detail '{}': expected all, final or metrics", t.text),
            )
        })?;
        self.log = Some((detail, line.number));
        Ok(())
    }

    /// `solver chains=iterate|split passes=N`.
    pub(super) fn solver(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
        if let Some((_, first)) = self.solver {
            return Err(line.error(head.column, format!("the solver is already set on line {first}")));
        }
        let a = Args::parse(line, rest, &["chains", "passes"], "solver")?;
        let mut options = SolverOptions::default();
        if let Some(t) = a.get("chains") {
            options.chains = Chains::from_name(t.text).ok_or_else(|| {
                line.error(
                    t.column,
                    format!("unknown chains '{}': expected iterate or split", t.text),
                )
            })?;
        }
        if let Some(t) = a.get("passes") {
            options.passes = integer_in(line, t, "passes", 1..=100)?;
        }
        self.solver = Some((options, line.number));
        Ok(())
    }
}
