//! The session text format (version 1).
//!
//! ```text
//! # comment (to the end of the line)
//! drape 1                            # required first statement: format version
//! body builtin                       # or: body "path/to/body.obj" (relative to the session file)
//! units m                            # m | cm | mm: the units of the body file's coordinates
//! landmark waist y=0.98              # override a landmark's height (metres)
//! landmark front_neck at=0,1.31,0.08 # or its point
//!
//! mannequin layers=18 points=12 subdivisions=6   # steps, run in order
//! section y=0.60 name=mid_thigh
//! garment jumpsuit fit=tight resolution=6        # build a garment: jumpsuit | dress
//! set waist_girth +0.04                          # change a dimension: +d / -d relative, or a value
//! drag waist.front by=0,0,-0.03                  # drag a control point by a vector (m) ...
//! drag crotch.point to=0,0.70,0.07               # ... or to a position
//! drag left_knee by=0,0.02,0                     # drag a whole curve by a vector
//! undo                                           # back to the state before the last step
//! ```
//!
//! The scene may also say how the constraint solver treats closed chains:
//! `solver chains=iterate passes=8` (the default) or `solver chains=split`.
//!
//! Scene statements (`drape`, `body`, `units`, `landmark`) come before the first step.
//! Arguments are `key=value`; unknown statements, keys or values are errors that name the
//! file, line and column. Everything is checked before anything runs.

use std::path::{Path, PathBuf};

use glam::DVec3;
use thiserror::Error;

use crate::body::{BodySource, LandmarkKind, LandmarkOverride};
use crate::constraint::{Chains, Edit, SolverOptions, Target};
use crate::garment::{Fit, TemplateKind};
use crate::mannequin::MannequinOptions;

/// A parse or validation error at a place in the session text.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{file}:{line}:{column}: {message}")]
pub struct ParseError {
    /// Session file name.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// What was expected.
    pub message: String,
}

/// Units of the body file's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Metres.
    Metres,
    /// Centimetres.
    Centimetres,
    /// Millimetres.
    Millimetres,
}

impl Units {
    /// Factor to metres.
    pub fn scale(self) -> f64 {
        match self {
            Self::Metres => 1.0,
            Self::Centimetres => 0.01,
            Self::Millimetres => 0.001,
        }
    }

    /// Session spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Metres => "m",
            Self::Centimetres => "cm",
            Self::Millimetres => "mm",
        }
    }
}

/// The scene header.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The body.
    pub body: BodySource,
    /// Units of the body file.
    pub units: Units,
    /// Landmark corrections, in file order.
    pub landmarks: Vec<(LandmarkKind, LandmarkOverride)>,
    /// Constraint solver settings (`solver chains=iterate|split passes=N`).
    pub solver: SolverOptions,
}

/// One operation.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// Refine the analytic dress form both ways and measure against its true surface.
    Mannequin(MannequinOptions),
    /// Cut the body with a horizontal plane.
    Section {
        /// Name for the viewer.
        name: String,
        /// Height, m.
        y: f64,
    },
    /// Build a garment from a template: framework and M0.
    Garment {
        /// Template.
        template: TemplateKind,
        /// Contour fit.
        fit: Fit,
        /// Segments per anchor arc in M0.
        resolution: usize,
    },
    /// Change a dimension of the current garment and solve again.
    Set {
        /// Dimension name.
        name: String,
        /// The change.
        change: Change,
    },
    /// Drag a control point or a whole curve of the current garment.
    Drag(Edit),
    /// Go back to the state before the last garment step.
    Undo,
}

/// A dimension change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Change {
    /// Add to the current value (`+0.04`, `-0.02`).
    By(f64),
    /// Set the value (`0.74`).
    To(f64),
}

impl Change {
    /// The new value from the current one.
    pub fn apply(self, current: f64) -> f64 {
        match self {
            Self::By(d) => current + d,
            Self::To(v) => v,
        }
    }
}

impl Op {
    /// The operation's keyword.
    pub fn keyword(&self) -> &'static str {
        match self {
            Self::Mannequin(_) => "mannequin",
            Self::Section { .. } => "section",
            Self::Garment { .. } => "garment",
            Self::Set { .. } => "set",
            Self::Drag(_) => "drag",
            Self::Undo => "undo",
        }
    }
}

/// A step and where it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// 1-based line in the session file.
    pub line: usize,
    /// What to do.
    pub op: Op,
}

/// A parsed, validated session.
#[derive(Clone, Debug, PartialEq)]
pub struct Session {
    /// File name (for messages and the recording's name).
    pub name: String,
    /// Scene header.
    pub scene: Scene,
    /// Steps in order.
    pub steps: Vec<Step>,
}

const SCENE_KEYWORDS: [&str; 5] = ["drape", "body", "units", "landmark", "solver"];
const STEP_KEYWORDS: [&str; 6] = ["mannequin", "section", "garment", "set", "drag", "undo"];

#[derive(Clone, Copy, Debug)]
struct Token<'a> {
    text: &'a str,
    column: usize,
    quoted: bool,
}

struct Line<'a> {
    file: &'a str,
    number: usize,
    tokens: Vec<Token<'a>>,
    end_column: usize,
}

impl Line<'_> {
    fn error(&self, column: usize, message: impl Into<String>) -> ParseError {
        ParseError {
            file: self.file.to_string(),
            line: self.number,
            column,
            message: message.into(),
        }
    }
}

/// Splits a line into tokens (bare words or "quoted strings"), stopping at `#`.
fn tokenize<'a>(file: &'a str, number: usize, text: &'a str) -> Result<Line<'a>, ParseError> {
    let mut tokens = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    let err = |column: usize, message: &str| ParseError {
        file: file.to_string(),
        line: number,
        column,
        message: message.to_string(),
    };
    while i < bytes.len() {
        match bytes[i] {
            b' ' | b'\t' | b'\r' => i += 1,
            b'#' => break,
            b'"' => {
                let start = i + 1;
                let Some(len) = text[start..].find('"') else {
                    return Err(err(i + 1, "unterminated string: expected a closing '\"'"));
                };
                tokens.push(Token {
                    text: &text[start..start + len],
                    column: i + 1,
                    quoted: true,
                });
                i = start + len + 1;
            }
            _ => {
                let start = i;
                while i < bytes.len() && !matches!(bytes[i], b' ' | b'\t' | b'\r' | b'#') {
                    i += 1;
                }
                tokens.push(Token {
                    text: &text[start..i],
                    column: start + 1,
                    quoted: false,
                });
            }
        }
    }
    Ok(Line {
        file,
        number,
        tokens,
        end_column: text.trim_end().len() + 1,
    })
}

/// `key=value` arguments of a statement, each checked against the allowed keys once.
struct Args<'a> {
    pairs: Vec<(&'a str, Token<'a>, usize)>,
}

impl<'a> Args<'a> {
    fn parse(line: &Line<'a>, tokens: &[Token<'a>], allowed: &[&str], statement: &str) -> Result<Self, ParseError> {
        let mut pairs: Vec<(&'a str, Token<'a>, usize)> = Vec::new();
        for t in tokens {
            let Some((key, value)) = t.text.split_once('=').filter(|_| !t.quoted) else {
                return Err(line.error(
                    t.column,
                    format!("expected key=value after '{statement}', found '{}'", t.text),
                ));
            };
            if !allowed.contains(&key) {
                return Err(line.error(
                    t.column,
                    format!(
                        "unknown key '{key}' for '{statement}': expected one of {}",
                        allowed.join(", ")
                    ),
                ));
            }
            if pairs.iter().any(|(k, _, _)| *k == key) {
                return Err(line.error(t.column, format!("'{key}' is given twice")));
            }
            let value_column = t.column + key.len() + 1;
            if value.is_empty() {
                return Err(line.error(value_column, format!("expected a value after '{key}='")));
            }
            pairs.push((
                key,
                Token {
                    text: value,
                    column: value_column,
                    quoted: false,
                },
                t.column,
            ));
        }
        Ok(Self { pairs })
    }

    fn get(&self, key: &str) -> Option<Token<'a>> {
        self.pairs.iter().find(|(k, _, _)| *k == key).map(|(_, v, _)| *v)
    }
}

/// The single argument of a statement: an error at the line's end if it is missing, or at
/// the first extra token. `(keyword, noun)` name the statement in the messages.
fn one_argument<'a>(
    line: &Line<'a>,
    rest: &[Token<'a>],
    (keyword, noun): (&str, &str),
    expected: &str,
) -> Result<Token<'a>, ParseError> {
    match rest {
        [t] => Ok(*t),
        [] => Err(line.error(line.end_column, format!("expected {expected} after '{keyword}'"))),
        [_, extra, ..] => Err(line.error(extra.column, format!("unexpected '{}' after the {noun}", extra.text))),
    }
}

fn number(line: &Line<'_>, t: Token<'_>, what: &str) -> Result<f64, ParseError> {
    let v: f64 = t
        .text
        .parse()
        .map_err(|_| line.error(t.column, format!("expected a number for {what}, found '{}'", t.text)))?;
    if !v.is_finite() {
        return Err(line.error(t.column, format!("{what} must be finite, found '{}'", t.text)));
    }
    Ok(v)
}

fn integer_in(
    line: &Line<'_>,
    t: Token<'_>,
    what: &str,
    range: std::ops::RangeInclusive<usize>,
) -> Result<usize, ParseError> {
    let v: usize = t.text.parse().map_err(|_| {
        line.error(
            t.column,
            format!("expected a whole number for {what}, found '{}'", t.text),
        )
    })?;
    if !range.contains(&v) {
        return Err(line.error(
            t.column,
            format!("{what} must be from {} to {}, found {v}", range.start(), range.end()),
        ));
    }
    Ok(v)
}

/// `x,y,z`: three finite numbers, errors at the offending part.
fn vector(line: &Line<'_>, t: Token<'_>, key: &str) -> Result<DVec3, ParseError> {
    let parts: Vec<&str> = t.text.split(',').collect();
    if parts.len() != 3 {
        return Err(line.error(
            t.column,
            format!("expected {key}=x,y,z (3 numbers), found '{}'", t.text),
        ));
    }
    let mut xyz = [0.0; 3];
    let mut column = t.column;
    for (slot, part) in xyz.iter_mut().zip(&parts) {
        *slot = number(
            line,
            Token {
                text: part,
                column,
                quoted: false,
            },
            "a coordinate",
        )?;
        column += part.len() + 1;
    }
    Ok(DVec3::from_array(xyz))
}

/// Parses and validates a session. `name` is used in messages; `base_dir` resolves
/// relative body paths.
///
/// # Failures
/// The first problem found, as a [`ParseError`] at its line and column.
pub fn parse_session(text: &str, name: &str, base_dir: &Path) -> Result<Session, ParseError> {
    let mut version_seen = false;
    let mut body: Option<(BodySource, usize)> = None;
    let mut units: Option<(Units, usize)> = None;
    let mut landmarks: Vec<(LandmarkKind, LandmarkOverride)> = Vec::new();
    let mut landmark_lines: Vec<(LandmarkKind, usize)> = Vec::new();
    let mut steps = Vec::new();
    let mut garment: Option<TemplateKind> = None;
    let mut solver: Option<(SolverOptions, usize)> = None;
    // Garment steps that `undo` can take back.
    let mut undoable = 0usize;
    for (index, raw) in text.lines().enumerate() {
        let line = tokenize(name, index + 1, raw)?;
        let Some((head, rest)) = line.tokens.split_first() else {
            continue;
        };
        let keyword = head.text;
        if !version_seen {
            if keyword != "drape" || head.quoted {
                return Err(line.error(
                    head.column,
                    format!("expected 'drape 1' as the first statement, found '{keyword}'"),
                ));
            }
            let v = one_argument(&line, rest, ("drape", "version"), "a format version (drape 1)")?;
            if v.text != "1" {
                return Err(line.error(
                    v.column,
                    format!("unsupported format version '{}': this drape reads version 1", v.text),
                ));
            }
            version_seen = true;
            continue;
        }
        if SCENE_KEYWORDS.contains(&keyword) && !steps.is_empty() {
            return Err(line.error(
                head.column,
                format!("'{keyword}' belongs to the scene and must come before the first step"),
            ));
        }
        match keyword {
            "drape" => {
                return Err(line.error(head.column, "'drape' may appear only once, as the first statement"));
            }
            "body" => {
                if let Some((_, first)) = body {
                    return Err(line.error(head.column, format!("the body is already set on line {first}")));
                }
                let t = one_argument(&line, rest, ("body", "body"), "'builtin' or a quoted OBJ path")?;
                let source = match t {
                    t if !t.quoted && t.text == "builtin" => BodySource::Builtin,
                    t if t.quoted => {
                        let p = PathBuf::from(t.text);
                        BodySource::File(if p.is_absolute() { p } else { base_dir.join(p) })
                    }
                    t => {
                        return Err(line.error(
                            t.column,
                            format!("expected 'builtin' or a quoted OBJ path, found '{}'", t.text),
                        ));
                    }
                };
                body = Some((source, line.number));
            }
            "units" => {
                if let Some((_, first)) = units {
                    return Err(line.error(head.column, format!("units are already set on line {first}")));
                }
                let t = one_argument(&line, rest, ("units", "units"), "m, cm or mm")?;
                let u = match t.text {
                    "m" => Units::Metres,
                    "cm" => Units::Centimetres,
                    "mm" => Units::Millimetres,
                    other => return Err(line.error(t.column, format!("unknown units '{other}': expected m, cm or mm"))),
                };
                units = Some((u, line.number));
            }
            "landmark" => {
                let Some((which, args)) = rest.split_first() else {
                    return Err(line.error(line.end_column, "expected a landmark name after 'landmark'"));
                };
                let names: Vec<&str> = LandmarkKind::ALL.iter().map(|k| k.name()).collect();
                let kind = LandmarkKind::from_name(which.text).ok_or_else(|| {
                    line.error(
                        which.column,
                        format!(
                            "unknown landmark '{}': expected one of {}",
                            which.text,
                            names.join(", ")
                        ),
                    )
                })?;
                if let Some((_, first)) = landmark_lines.iter().find(|(k, _)| *k == kind) {
                    return Err(line.error(
                        which.column,
                        format!("landmark '{}' is already set on line {first}", which.text),
                    ));
                }
                let a = Args::parse(&line, args, &["y", "at"], "landmark")?;
                let correction = match (a.get("y"), a.get("at")) {
                    (Some(y), None) => LandmarkOverride::Height(number(&line, y, "y")?),
                    (None, Some(at)) => {
                        let xyz = vector(&line, at, "at")?;
                        LandmarkOverride::Point(xyz)
                    }
                    (Some(_), Some(at)) => {
                        return Err(line.error(at.column, "give either y= or at=, not both"));
                    }
                    (None, None) => {
                        return Err(line.error(line.end_column, "expected y=<height> or at=<x,y,z>"));
                    }
                };
                landmarks.push((kind, correction));
                landmark_lines.push((kind, line.number));
            }
            "solver" => {
                if let Some((_, first)) = solver {
                    return Err(line.error(head.column, format!("the solver is already set on line {first}")));
                }
                let a = Args::parse(&line, rest, &["chains", "passes"], "solver")?;
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
                    options.passes = integer_in(&line, t, "passes", 1..=100)?;
                }
                solver = Some((options, line.number));
            }
            "drag" => {
                if garment.is_none() {
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
                let a = Args::parse(&line, args, &["by", "to"], "drag")?;
                let point = which.text.contains('.');
                let edit = match (a.get("by"), a.get("to")) {
                    (Some(by), None) => {
                        let v = vector(&line, by, "by")?;
                        if point {
                            Edit::Point {
                                name: which.text.to_string(),
                                target: Target::By(v),
                            }
                        } else {
                            Edit::Curve {
                                name: which.text.to_string(),
                                by: v,
                            }
                        }
                    }
                    (None, Some(to)) if point => Edit::Point {
                        name: which.text.to_string(),
                        target: Target::To(vector(&line, to, "to")?),
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
                undoable += 1;
                steps.push(Step {
                    line: line.number,
                    op: Op::Drag(edit),
                });
            }
            "undo" => {
                if let Some(extra) = rest.first() {
                    return Err(line.error(extra.column, format!("unexpected '{}' after 'undo'", extra.text)));
                }
                if undoable == 0 {
                    return Err(line.error(
                        head.column,
                        "nothing to undo: 'undo' takes back a drag or set step of the garment",
                    ));
                }
                undoable -= 1;
                steps.push(Step {
                    line: line.number,
                    op: Op::Undo,
                });
            }
            "mannequin" => {
                let a = Args::parse(&line, rest, &["layers", "points", "subdivisions"], "mannequin")?;
                let mut options = MannequinOptions::default();
                if let Some(t) = a.get("layers") {
                    options.layers = integer_in(&line, t, "layers", 4..=200)?;
                }
                if let Some(t) = a.get("points") {
                    options.points = integer_in(&line, t, "points", 6..=360)?;
                }
                if let Some(t) = a.get("subdivisions") {
                    options.subdivisions = integer_in(&line, t, "subdivisions", 1..=20)?;
                }
                steps.push(Step {
                    line: line.number,
                    op: Op::Mannequin(options),
                });
            }
            "section" => {
                let a = Args::parse(&line, rest, &["y", "name"], "section")?;
                let y = match a.get("y") {
                    Some(t) => number(&line, t, "y")?,
                    None => {
                        return Err(line.error(line.end_column, "expected y=<height> for 'section'"));
                    }
                };
                let name = match a.get("name") {
                    Some(t) if t.text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') => t.text.to_string(),
                    Some(t) => {
                        return Err(line.error(
                            t.column,
                            format!("a name may hold letters, digits and '_' only, found '{}'", t.text),
                        ));
                    }
                    None => format!("y{:.0}mm", y * 1000.0),
                };
                steps.push(Step {
                    line: line.number,
                    op: Op::Section { name, y },
                });
            }
            "garment" => {
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
                            "unknown template '{}': expected one of {}",
                            which.text,
                            names.join(", ")
                        ),
                    )
                })?;
                let a = Args::parse(&line, args, &["fit", "resolution"], "garment")?;
                let fit = match a.get("fit") {
                    None => Fit::Tight,
                    Some(t) => Fit::from_name(t.text).ok_or_else(|| {
                        line.error(t.column, format!("unknown fit '{}': expected tight or loose", t.text))
                    })?,
                };
                let resolution = match a.get("resolution") {
                    None => 6,
                    Some(t) => integer_in(&line, t, "resolution", 2..=24)?,
                };
                garment = Some(template);
                undoable = 0;
                steps.push(Step {
                    line: line.number,
                    op: Op::Garment {
                        template,
                        fit,
                        resolution,
                    },
                });
            }
            "set" => {
                let Some(template) = garment else {
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
                let known = template.dimension_names();
                if !known.iter().any(|k| k == which.text) {
                    return Err(line.error(
                        which.column,
                        format!(
                            "unknown dimension '{}' for the {}: expected one of {}",
                            which.text,
                            template.name(),
                            known.join(", ")
                        ),
                    ));
                }
                let v = number(&line, value, "the value")?;
                let change = if value.text.starts_with(['+', '-']) {
                    Change::By(v)
                } else {
                    Change::To(v)
                };
                undoable += 1;
                steps.push(Step {
                    line: line.number,
                    op: Op::Set {
                        name: which.text.to_string(),
                        change,
                    },
                });
            }
            other => {
                return Err(line.error(
                    head.column,
                    format!(
                        "unknown statement '{other}': expected a scene statement ({}) or a step ({})",
                        SCENE_KEYWORDS.join(", "),
                        STEP_KEYWORDS.join(", ")
                    ),
                ));
            }
        }
    }
    if !version_seen {
        return Err(ParseError {
            file: name.into(),
            line: 1,
            column: 1,
            message: "empty session: expected 'drape 1' as the first statement".into(),
        });
    }
    Ok(Session {
        name: name.to_string(),
        scene: Scene {
            body: body.map_or(BodySource::Builtin, |b| b.0),
            units: units.map_or(Units::Metres, |u| u.0),
            landmarks,
            solver: solver.map_or_else(SolverOptions::default, |s| s.0),
        },
        steps,
    })
}
