//! The `solver` statement: how the constraint solver treats closed chains.

use super::Parser;
use crate::constraint::{Chains, SolverOptions};
use crate::session::format::args::{Args, integer_in};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::ParseError;

impl Parser<'_> {
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
