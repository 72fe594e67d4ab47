//! The parser: statements into the syntax tree, one method per statement. Scene statements
//! come first; steps are checked against what came before them (a `set` names a dimension
//! of the garment built before it, an `undo` needs something to take back).

use std::path::{Path, PathBuf};

use glam::DVec3;

use super::args::{Args, integer_in, number, one_argument, vector};
use super::lexer::{Line, Token, tokenize};
use super::suggest::did_you_mean;
use super::syntax::{Change, LogDetail, Op, ParseError, Scene, SculptAt, Session, Step, Units};
use crate::body::{BodySource, LandmarkKind, LandmarkOverride};
use crate::constraint::{Chains, Edit, SolverOptions, Target};
use crate::garment::{Contours, Fit, TemplateKind};
use crate::m1::M1Options;
use crate::mannequin::MannequinOptions;

mod m1;

const SCENE_KEYWORDS: [&str; 7] = ["drape", "body", "units", "landmark", "solver", "m1", "log"];
const STEP_KEYWORDS: [&str; 10] = [
    "mannequin",
    "section",
    "garment",
    "set",
    "drag",
    "undo",
    "cut",
    "nurbs",
    "move",
    "sculpt",
];

/// Parses and validates a session. `name` is used in messages; `base_dir` resolves
/// relative body paths.
///
/// # Failures
/// The first problem found, as a [`ParseError`] at its line and column.
pub fn parse_session(text: &str, name: &str, base_dir: &Path) -> Result<Session, ParseError> {
    let mut p = Parser {
        base_dir,
        version_seen: false,
        body: None,
        units: None,
        landmarks: Vec::new(),
        landmark_lines: Vec::new(),
        solver: None,
        m1: None,
        log: None,
        steps: Vec::new(),
        garment: None,
        undoable: 0,
        nurbs: Vec::new(),
    };
    for (index, raw) in text.lines().enumerate() {
        let line = tokenize(name, index + 1, raw)?;
        p.statement(&line)?;
    }
    if !p.version_seen {
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
            body_line: p.body.as_ref().map_or(1, |b| b.1),
            body: p.body.map_or(BodySource::Builtin, |b| b.0),
            units: p.units.map_or(Units::Metres, |u| u.0),
            landmarks: p.landmarks,
            solver: p.solver.map_or_else(SolverOptions::default, |s| s.0),
            m1: p.m1.map(|m| m.0),
            log: p.log.map(|l| l.0),
        },
        steps: p.steps,
    })
}

/// What the statements so far have set, each with the line that set it.
struct Parser<'p> {
    base_dir: &'p Path,
    version_seen: bool,
    body: Option<(BodySource, usize)>,
    units: Option<(Units, usize)>,
    landmarks: Vec<(LandmarkKind, LandmarkOverride)>,
    landmark_lines: Vec<(LandmarkKind, usize)>,
    solver: Option<(SolverOptions, usize)>,
    m1: Option<(M1Options, usize)>,
    log: Option<(LogDetail, usize)>,
    steps: Vec<Step>,
    /// The template of the last `garment` step.
    garment: Option<TemplateKind>,
    /// Garment steps that `undo` can take back.
    undoable: usize,
    /// NURBS parts added so far, with their lines.
    nurbs: Vec<(String, usize)>,
}

impl Parser<'_> {
    fn statement(&mut self, line: &Line<'_>) -> Result<(), ParseError> {
        let Some((head, rest)) = line.tokens.split_first() else {
            return Ok(());
        };
        let keyword = head.text;
        if !self.version_seen {
            return self.version(line, head, rest);
        }
        if SCENE_KEYWORDS.contains(&keyword) && !self.steps.is_empty() {
            return Err(line.error(
                head.column,
                format!("'{keyword}' belongs to the scene and must come before the first step"),
            ));
        }
        let op = match keyword {
            "drape" => {
                return Err(line.error(head.column, "'drape' may appear only once, as the first statement"));
            }
            "body" => return self.body(line, head, rest),
            "units" => return self.units(line, head, rest),
            "landmark" => return self.landmark(line, rest),
            "solver" => return self.solver(line, head, rest),
            "m1" => return self.m1(line, head, rest),
            "log" => return self.log(line, head, rest),
            "cut" => self.cut(line, head, rest)?,
            "drag" => self.drag(line, head, rest)?,
            "undo" => self.undo(line, head, rest)?,
            "mannequin" => mannequin(line, rest)?,
            "section" => section(line, rest)?,
            "garment" => self.garment(line, rest)?,
            "set" => self.set(line, head, rest)?,
            "nurbs" => self.nurbs(line, head, rest)?,
            "move" => self.move_part(line, head, rest)?,
            "sculpt" => self.sculpt(line, head, rest)?,
            other => {
                return Err(line.error(
                    head.column,
                    format!(
                        "unknown statement '{other}'{}: expected a scene statement ({}) or a step ({})",
                        did_you_mean(other, SCENE_KEYWORDS.into_iter().chain(STEP_KEYWORDS)),
                        SCENE_KEYWORDS.join(", "),
                        STEP_KEYWORDS.join(", ")
                    ),
                ));
            }
        };
        self.steps.push(Step { line: line.number, op });
        Ok(())
    }

    /// `drape 1`, the required first statement.
    fn version(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
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
    fn body(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
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
    fn units(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
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
    fn landmark(&mut self, line: &Line<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
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
    fn log(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
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
    fn solver(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<(), ParseError> {
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

    /// `drag POINT by=dx,dy,dz | to=x,y,z` or `drag CURVE by=dx,dy,dz`.
    fn drag(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
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
        if let Some(template) = self.garment {
            let spec = crate::garment::template::of(template);
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

    /// `undo`.
    fn undo(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        if let Some(extra) = rest.first() {
            return Err(line.error(extra.column, format!("unexpected '{}' after 'undo'", extra.text)));
        }
        if self.undoable == 0 {
            return Err(line.error(
                head.column,
                "nothing to undo: 'undo' takes back a drag, set, cut or sculpt step of the garment",
            ));
        }
        self.undoable -= 1;
        Ok(Op::Undo)
    }

    /// `nurbs "part.nurbs" name=NAME`: a NURBS part (the name defaults to the file's stem).
    fn nurbs(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        let Some((file, args)) = rest.split_first().filter(|(t, _)| t.quoted) else {
            let column = rest.first().map_or(line.end_column, |t| t.column);
            return Err(line.error(column, "expected a quoted .nurbs path after 'nurbs'"));
        };
        let a = Args::parse(line, args, &["name"], "nurbs")?;
        let p = PathBuf::from(file.text);
        let path = if p.is_absolute() { p } else { self.base_dir.join(p) };
        let name = match a.get("name") {
            Some(t) => t.text.to_string(),
            None => path
                .file_stem()
                .map_or("part".into(), |s| s.to_string_lossy().into_owned()),
        };
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
            return Err(line.error(
                head.column,
                format!("a part name may hold letters, digits, '_' and '-' only, found '{name}' (give name=...)"),
            ));
        }
        if let Some((_, first)) = self.nurbs.iter().find(|(n, _)| *n == name) {
            return Err(line.error(
                head.column,
                format!("a part named '{name}' is already added on line {first}"),
            ));
        }
        self.nurbs.push((name.clone(), line.number));
        Ok(Op::Nurbs { name, path })
    }

    /// `move NAME by=x,y,z turn=DEG`: moves a NURBS part (m) and turns it about the vertical
    /// through its centre (degrees).
    fn move_part(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        let Some((which, args)) = rest.split_first() else {
            return Err(line.error(line.end_column, "expected the name of a NURBS part after 'move'"));
        };
        if !self.nurbs.iter().any(|(n, _)| n == which.text) {
            let known: Vec<&str> = self.nurbs.iter().map(|(n, _)| n.as_str()).collect();
            return Err(line.error(
                which.column,
                if known.is_empty() {
                    format!(
                        "no NURBS part '{}': add one first with nurbs \"FILE\" name=...",
                        which.text
                    )
                } else {
                    format!("no NURBS part '{}': the parts are {}", which.text, known.join(", "))
                },
            ));
        }
        let a = Args::parse(line, args, &["by", "turn"], "move")?;
        let by = a.get("by").map(|t| vector(line, t, "by")).transpose()?;
        let turn = a.get("turn").map(|t| number(line, t, "turn")).transpose()?;
        if by.is_none() && turn.is_none() {
            return Err(line.error(head.column, "expected by=x,y,z (m) or turn=DEG for 'move'"));
        }
        Ok(Op::Move {
            name: which.text.to_string(),
            by: by.unwrap_or(DVec3::ZERO),
            turn_deg: turn.unwrap_or(0.0),
        })
    }

    /// `sculpt at=x,y,z radius=R peak=H [dir=x,y,z] [falloff=NAME] [eps=E] [levels=N]
    /// [weight=W]`: lengths in m.
    fn sculpt(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
        use crate::sculpt::{AdaptiveOptions, Drag, Falloff, SculptOptions};
        if self.garment.is_none() {
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
        let at = if at_token.text.chars().any(|c| c.is_ascii_alphabetic()) {
            let names = self
                .garment
                .map(|t| crate::garment::template::of(t).point_names())
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

    /// `garment jumpsuit|dress fit=tight|loose contours=local|natural resolution=N`.
    fn garment(&mut self, line: &Line<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
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
            None => Contours::default(),
            Some(t) => Contours::from_name(t.text).ok_or_else(|| {
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
    fn set(&mut self, line: &Line<'_>, head: &Token<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
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

/// `mannequin layers=L points=P subdivisions=K`.
fn mannequin(line: &Line<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
    let a = Args::parse(line, rest, &["layers", "points", "subdivisions"], "mannequin")?;
    let mut options = MannequinOptions::default();
    if let Some(t) = a.get("layers") {
        options.layers = integer_in(line, t, "layers", 4..=200)?;
    }
    if let Some(t) = a.get("points") {
        options.points = integer_in(line, t, "points", 6..=360)?;
    }
    if let Some(t) = a.get("subdivisions") {
        options.subdivisions = integer_in(line, t, "subdivisions", 1..=20)?;
    }
    Ok(Op::Mannequin(options))
}

/// `section y=H name=NAME`.
fn section(line: &Line<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
    let a = Args::parse(line, rest, &["y", "name"], "section")?;
    let y = match a.get("y") {
        Some(t) => number(line, t, "y")?,
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
    Ok(Op::Section { name, y })
}
