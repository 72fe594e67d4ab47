//! Arguments of a statement: `key=value` pairs checked against the allowed keys, and the
//! readers of values (finite numbers, whole numbers in a range, `x,y,z` vectors), each error
//! at the column of the offending text.

use glam::DVec3;

use super::lexer::{Line, Token};
use super::syntax::ParseError;

/// `key=value` arguments of a statement, each checked against the allowed keys once.
pub(super) struct Args<'a> {
    pairs: Vec<(&'a str, Token<'a>, usize)>,
}

impl<'a> Args<'a> {
    /// Reads `tokens` as `key=value` pairs, each key one of `allowed`, none twice.
    pub(super) fn parse(
        line: &Line<'a>,
        tokens: &[Token<'a>],
        allowed: &[&str],
        statement: &str,
    ) -> Result<Self, ParseError> {
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

    /// The value of `key`, if given.
    pub(super) fn get(&self, key: &str) -> Option<Token<'a>> {
        self.pairs.iter().find(|(k, _, _)| *k == key).map(|(_, v, _)| *v)
    }
}

/// The single argument of a statement: an error at the line's end if it is missing, or at
/// the first extra token. `(keyword, noun)` name the statement in the messages.
pub(super) fn one_argument<'a>(
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

/// A finite number; `what` names it in the message.
pub(super) fn number(line: &Line<'_>, t: Token<'_>, what: &str) -> Result<f64, ParseError> {
    let v: f64 = t
        .text
        .parse()
        .map_err(|_| line.error(t.column, format!("expected a number for {what}, found '{}'", t.text)))?;
    if !v.is_finite() {
        return Err(line.error(t.column, format!("{what} must be finite, found '{}'", t.text)));
    }
    Ok(v)
}

/// A whole number within `range`; `what` names it in the message.
pub(super) fn integer_in(
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
pub(super) fn vector(line: &Line<'_>, t: Token<'_>, key: &str) -> Result<DVec3, ParseError> {
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
