//! The parser: statements into the syntax tree, one method per statement. Scene statements
//! come first; steps are checked against what came before them (a `set` names a dimension
//! of the garment built before it, an `undo` needs something to take back). Each statement
//! has its own file in `parser/` (`move` in `move_part.rs`), and the dispatch here is one
//! arm per entry of the statement table ([`super::statements::Statement`]).

use std::path::Path;

use super::lexer::{Line, Token, tokenize};
use super::statements::{Place, Statement};
use super::suggest::did_you_mean;
use super::syntax::{LogDetail, ParseError, Scene, Session, Step, Units};
use crate::body::{BodySource, LandmarkKind, LandmarkOverride};
use crate::constraint::SolverOptions;
use crate::garment::{Style, TemplateKind};
use crate::m1::M1Options;

mod body;
mod cut;
mod drag;
mod drape;
mod garment;
mod garment_mesh;
mod landmark;
mod layers;
mod log;
mod m1;
mod mannequin;
mod move_part;
mod nurbs;
mod patterns;
mod sculpt;
mod section;
mod set;
mod solver;
mod undo;
mod units;

use mannequin::mannequin;
use section::section;

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
        patterns: None,
        log: None,
        steps: Vec::new(),
        garment: None,
        mesh_garment: None,
        undoable: 0,
        nurbs: Vec::new(),
        worn: Vec::new(),
        step_garment: None,
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
    if let (Some((o, line)), None) = (&p.patterns, &p.m1)
        && o.source == crate::pattern::Source::M1
    {
        return Err(ParseError {
            file: name.into(),
            line: *line,
            column: 1,
            message: "patterns from=m1 needs M1: add an 'm1' statement to the scene".into(),
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
            patterns: p.patterns.map(|m| m.0),
            log: p.log.map(|l| l.0),
        },
        steps: p.steps,
    })
}

/// A garment the session wears, as the parser knows it.
struct Worn {
    /// Its name.
    name: String,
    /// Its template (`None`: a mesh from a file).
    garment: Option<(TemplateKind, Style)>,
    /// The line of its `garment mesh` step, for a mesh from a file.
    mesh_line: Option<usize>,
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
    patterns: Option<(crate::pattern::PatternOptions, usize)>,
    log: Option<(LogDetail, usize)>,
    steps: Vec<Step>,
    /// The template of the last `garment` step (`None` after a `garment mesh`).
    garment: Option<(TemplateKind, Style)>,
    /// The line of the last `garment mesh` step, while it is the current garment.
    mesh_garment: Option<usize>,
    /// Garment steps that `undo` can take back.
    undoable: usize,
    /// NURBS parts added so far, with their lines.
    nurbs: Vec<(String, usize)>,
    /// The garments worn, innermost first (the last is the current one).
    worn: Vec<Worn>,
    /// The garment the statement being parsed names (`drag outer:waist.front`).
    step_garment: Option<String>,
}

impl Parser<'_> {
    /// A garment step (from a template or a file) came before.
    fn has_garment(&self) -> bool {
        self.garment.is_some() || self.mesh_garment.is_some()
    }

    /// The refusal of `verb` (`drag`, `set`) on a garment from a file, when the current
    /// garment is one: it has no control points or dimensions.
    fn refuse_on_mesh(&self, line: &Line<'_>, head: &Token<'_>, what: &str) -> Result<(), ParseError> {
        match self.mesh_garment {
            Some(at) => Err(line.error(
                head.column,
                format!(
                    "'{}' needs a garment built from a template: the garment of line {at} is a mesh from a file, \
                     which has no {what} (sculpt pushes or pulls its surface)",
                    head.text
                ),
            )),
            None => Ok(()),
        }
    }

    /// A step's quoted file (resolved against the session's folder) and the name of what it
    /// holds (`name=`, else the file's stem, else `fallback`), checked to hold letters,
    /// digits, '_' and '-' only; `what` names it in the message (`part`, `garment`).
    fn file_and_name(
        &self,
        line: &Line<'_>,
        (file, name): (&Token<'_>, Option<Token<'_>>),
        column: usize,
        (what, fallback): (&str, &str),
    ) -> Result<(std::path::PathBuf, String), ParseError> {
        let p = std::path::PathBuf::from(file.text);
        let path = if p.is_absolute() { p } else { self.base_dir.join(p) };
        let name = match name {
            Some(t) => t.text.to_string(),
            None => path
                .file_stem()
                .map_or(fallback.into(), |s| s.to_string_lossy().into_owned()),
        };
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
            return Err(line.error(
                column,
                format!("a {what} name may hold letters, digits, '_' and '-' only, found '{name}' (give name=...)"),
            ));
        }
        Ok((path, name))
    }

    fn statement(&mut self, line: &Line<'_>) -> Result<(), ParseError> {
        let Some((head, rest)) = line.tokens.split_first() else {
            return Ok(());
        };
        let keyword = head.text;
        if !self.version_seen {
            return self.version(line, head, rest);
        }
        let Some(statement) = Statement::from_keyword(keyword) else {
            let scene: Vec<&str> = Statement::keywords(Place::Scene).collect();
            let steps: Vec<&str> = Statement::keywords(Place::Step).collect();
            return Err(line.error(
                head.column,
                format!(
                    "unknown statement '{keyword}'{}: expected a scene statement ({}) or a step ({})",
                    did_you_mean(keyword, Statement::ALL.iter().map(|(_, k, _)| *k)),
                    scene.join(", "),
                    steps.join(", ")
                ),
            ));
        };
        if statement.place() == Place::Scene && !self.steps.is_empty() {
            return Err(line.error(
                head.column,
                format!("'{keyword}' belongs to the scene and must come before the first step"),
            ));
        }
        let op = match statement {
            Statement::Drape => {
                return Err(line.error(head.column, "'drape' may appear only once, as the first statement"));
            }
            Statement::Body => return self.body(line, head, rest),
            Statement::Units => return self.units(line, head, rest),
            Statement::Landmark => return self.landmark(line, rest),
            Statement::Solver => return self.solver(line, head, rest),
            Statement::M1 => return self.m1(line, head, rest),
            Statement::Patterns => return self.patterns(line, head, rest),
            Statement::Log => return self.log(line, head, rest),
            Statement::Mannequin => mannequin(line, rest)?,
            Statement::Section => section(line, rest)?,
            Statement::Garment => self.garment(line, rest)?,
            Statement::Set | Statement::Drag | Statement::Cut | Statement::Sculpt => {
                self.on_named_garment(line, rest, |p, rest| match statement {
                    Statement::Set => p.set(line, head, rest),
                    Statement::Drag => p.drag(line, head, rest),
                    Statement::Cut => p.cut(line, head, rest),
                    _ => p.sculpt(line, head, rest),
                })?
            }
            Statement::Undo => self.undo(line, head, rest)?,
            Statement::Nurbs => self.nurbs(line, head, rest)?,
            Statement::Move => self.move_part(line, head, rest)?,
        };
        self.steps.push(Step {
            line: line.number,
            op,
            garment: self.step_garment.take(),
        });
        Ok(())
    }
}
