//! The `section` step: a body section.

use crate::session::format::args::{Args, number};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};

/// `section y=H name=NAME`.
pub(super) fn section(line: &Line<'_>, rest: &[Token<'_>]) -> Result<Op, ParseError> {
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
