//! Layers in the session text: a garment's `name=` and `over=`, and a step naming the
//! garment it edits (`drag outer:waist.front`, `set inner:waist_girth +0.02`, `cut
//! outer:hem ...`, `sculpt at=outer:waist.front ...`).

use super::{Parser, Worn};
use crate::garment::{Style, TemplateKind};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::suggest::did_you_mean;
use crate::session::format::syntax::{Op, ParseError};

impl Parser<'_> {
    /// Puts on a garment named `name` (written at `column`), over the garment `over` names,
    /// which must be the outermost so far; without `over`, it replaces every garment worn.
    /// It becomes the current garment.
    pub(super) fn wear(
        &mut self,
        line: &Line<'_>,
        (name, column): (&str, usize),
        over: Option<&Token<'_>>,
        worn: (Option<(TemplateKind, Style)>, Option<usize>),
    ) -> Result<Option<String>, ParseError> {
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
            return Err(line.error(
                column,
                format!("a garment name may hold letters, digits, '_' and '-' only, found '{name}'"),
            ));
        }
        match over {
            None => self.worn.clear(),
            Some(t) => {
                let Some(top) = self.worn.last() else {
                    return Err(line.error(
                        t.column,
                        format!(
                            "over={} needs a garment to be worn over: put a 'garment' step before this one",
                            t.text
                        ),
                    ));
                };
                if top.name != t.text {
                    let message = if self.worn.iter().any(|w| w.name == t.text) {
                        format!(
                            "'{}' is under '{}' already: a garment goes over the outermost one (over={})",
                            t.text, top.name, top.name
                        )
                    } else {
                        format!(
                            "no garment '{}' to wear this over{}: the garments worn are {}",
                            t.text,
                            did_you_mean(t.text, self.worn.iter().map(|w| w.name.as_str())),
                            self.names()
                        )
                    };
                    return Err(line.error(t.column, message));
                }
            }
        }
        if self.worn.iter().any(|w| w.name == name) {
            return Err(line.error(
                column,
                format!("a garment named '{name}' is worn already: give this one another name (name=...)"),
            ));
        }
        let (garment, mesh_line) = worn;
        self.worn.push(Worn {
            name: name.to_string(),
            garment,
            mesh_line,
        });
        self.garment = garment;
        self.mesh_garment = mesh_line;
        self.undoable = 0;
        Ok(over.map(|t| t.text.to_string()))
    }

    /// The garments worn, innermost first, as a list for messages.
    fn names(&self) -> String {
        self.worn.iter().map(|w| w.name.as_str()).collect::<Vec<_>>().join(", ")
    }

    /// Parses an edit (`parse`) with its first token's garment name (`outer:waist.front`)
    /// taken off and that garment current while it is parsed; the current garment is the
    /// outermost again afterwards.
    pub(super) fn on_named_garment(
        &mut self,
        line: &Line<'_>,
        rest: &[Token<'_>],
        parse: impl FnOnce(&mut Self, &[Token<'_>]) -> Result<Op, ParseError>,
    ) -> Result<Op, ParseError> {
        let current = (self.garment, self.mesh_garment);
        let mut tokens = rest.to_vec();
        if let Some(first) = tokens.first_mut().filter(|t| !t.text.contains('=')) {
            *first = self.named(line, *first)?;
        }
        let op = parse(self, &tokens);
        (self.garment, self.mesh_garment) = current;
        op
    }

    /// `token` without the garment it names (`outer:` of `outer:waist.front`), that garment
    /// made the statement's; `token` itself when it names none.
    pub(super) fn named<'t>(&mut self, line: &Line<'_>, token: Token<'t>) -> Result<Token<'t>, ParseError> {
        let Some((name, rest)) = token.text.split_once(':').filter(|_| !token.quoted) else {
            return Ok(token);
        };
        let Some(worn) = self.worn.iter().find(|w| w.name == name) else {
            return Err(line.error(
                token.column,
                format!(
                    "no garment '{name}'{}: the garments worn are {}",
                    did_you_mean(name, self.worn.iter().map(|w| w.name.as_str())),
                    if self.worn.is_empty() {
                        "none".into()
                    } else {
                        self.names()
                    }
                ),
            ));
        };
        self.garment = worn.garment;
        self.mesh_garment = worn.mesh_line;
        self.step_garment = Some(name.to_string());
        Ok(Token {
            text: rest,
            column: token.column + name.len() + 1,
            quoted: false,
        })
    }
}
