//! The lexer: one line of session text into tokens (bare words or "quoted strings"),
//! each with its column, stopping at a `#` comment.

use super::syntax::ParseError;

/// A word of a line.
#[derive(Clone, Copy, Debug)]
pub(super) struct Token<'a> {
    /// The text (without the quotes of a quoted string).
    pub(super) text: &'a str,
    /// 1-based column of its first character.
    pub(super) column: usize,
    /// Written as a "quoted string".
    pub(super) quoted: bool,
}

/// A tokenized line.
pub(super) struct Line<'a> {
    /// Session file name.
    pub(super) file: &'a str,
    /// 1-based line number.
    pub(super) number: usize,
    /// Its tokens.
    pub(super) tokens: Vec<Token<'a>>,
    /// The column just past its last character (where a missing argument is reported).
    pub(super) end_column: usize,
}

impl Line<'_> {
    /// An error at `column` of this line.
    pub(super) fn error(&self, column: usize, message: impl Into<String>) -> ParseError {
        ParseError {
            file: self.file.to_string(),
            line: self.number,
            column,
            message: message.into(),
        }
    }
}

/// Splits a line into tokens (bare words or "quoted strings"), stopping at `#`.
pub(super) fn tokenize<'a>(file: &'a str, number: usize, text: &'a str) -> Result<Line<'a>, ParseError> {
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
