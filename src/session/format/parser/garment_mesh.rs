//! The `garment mesh` step: a garment mesh from a file as the garment.

use super::Parser;
use crate::session::format::args::{Args, number};
use crate::session::format::lexer::{Line, Token};
use crate::session::format::syntax::{Op, ParseError};

/// The file units `garment mesh` takes, with their factor to metres.
const UNITS: [(&str, f64); 4] = [("m", 1.0), ("cm", 0.01), ("mm", 0.001), ("in", 0.0254)];

/// The largest ease, m (as `drape check-garment --ease`).
const MAX_EASE: f64 = 0.1;

impl Parser<'_> {
    /// `garment mesh "FILE" [name=N] [ease=E] [units=m|cm|mm|in] [over=NAME]`: the file resolved
    /// against the session's folder, the name defaulting to the file's stem, the ease to
    /// 0.002 m.
    pub(super) fn garment_mesh(
        &mut self,
        line: &Line<'_>,
        mesh: &Token<'_>,
        rest: &[Token<'_>],
    ) -> Result<Op, ParseError> {
        let Some((file, args)) = rest.split_first().filter(|(t, _)| t.quoted) else {
            let column = rest.first().map_or(line.end_column, |t| t.column);
            return Err(line.error(
                column,
                "expected a quoted mesh path (OBJ, PLY, glTF or GLB) after 'garment mesh'",
            ));
        };
        let a = Args::parse(line, args, &["name", "ease", "units", "over"], "garment mesh")?;
        let column = a.get("name").map_or(mesh.column, |t| t.column);
        let (path, name) = self.file_and_name(line, (file, a.get("name")), column, ("garment", "garment"))?;
        let ease = match a.get("ease") {
            None => crate::import::CheckOptions::default().ease,
            Some(t) => {
                let e = number(line, t, "ease")?;
                if !(0.0..=MAX_EASE).contains(&e) {
                    return Err(line.error(
                        t.column,
                        format!("ease must be between 0 and {MAX_EASE} m, found '{}'", t.text),
                    ));
                }
                e
            }
        };
        let scale = match a.get("units") {
            None => 1.0,
            Some(t) => UNITS
                .iter()
                .find(|(u, _)| *u == t.text)
                .map(|(_, s)| *s)
                .ok_or_else(|| {
                    line.error(
                        t.column,
                        format!("unknown units '{}': expected m, cm, mm or in", t.text),
                    )
                })?,
        };
        let over = self.wear(line, (&name, column), a.get("over").as_ref(), (None, Some(line.number)))?;
        Ok(Op::GarmentMesh {
            path,
            name,
            ease,
            scale,
            over,
        })
    }
}
