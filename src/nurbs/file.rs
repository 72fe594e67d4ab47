//! The `.nurbs` text format (documented in `assets/nurbs/README.md`): one keyword per line,
//! `#` comments, control points row-major with their weights.
//!
//! ```text
//! nurbs 1
//! name butterfly
//! degree 3 3
//! count 9 9
//! knots u 0 0 0 0 0.1 ... 1 1 1 1
//! knots v 0 0 0 0 0.15 ... 1 1 1 1
//! point x y z w        (count_u x count_v lines, i along u slowest)
//! ```

use glam::DVec3;
use thiserror::Error;

use super::surface::{NurbsError, NurbsSurface};

/// Why a `.nurbs` text could not be read.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum NurbsFileError {
    /// A line that does not parse.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A required line is missing.
    #[error("no `{0}` line")]
    Missing(&'static str),
    /// The parts parse but do not make a valid surface.
    #[error(transparent)]
    Surface(#[from] NurbsError),
}

/// A surface read from a `.nurbs` text, with its name.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedSurface {
    /// The `name` line (empty when absent).
    pub name: String,
    /// The surface.
    pub surface: NurbsSurface,
}

fn numbers<T: std::str::FromStr>(words: &[&str], line: usize, what: &str) -> Result<Vec<T>, NurbsFileError> {
    words
        .iter()
        .map(|w| {
            w.parse().map_err(|_| NurbsFileError::Line {
                line,
                message: format!("{what}: `{w}` is not a number"),
            })
        })
        .collect()
}

fn exactly<T: Copy, const N: usize>(v: Vec<T>, line: usize, what: &str) -> Result<[T; N], NurbsFileError> {
    v.try_into().map_err(|v: Vec<T>| NurbsFileError::Line {
        line,
        message: format!("{what} takes {N} numbers, got {}", v.len()),
    })
}

/// Reads a surface from `.nurbs` text.
pub fn parse(text: &str) -> Result<NamedSurface, NurbsFileError> {
    let (mut name, mut version) = (String::new(), None);
    let (mut degree, mut count) = (None, None);
    let mut knots: [Option<Vec<f64>>; 2] = [None, None];
    let (mut points, mut weights) = (Vec::new(), Vec::new());
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        let words: Vec<&str> = content.split_whitespace().collect();
        let Some((&key, rest)) = words.split_first() else {
            continue;
        };
        match key {
            "nurbs" => {
                let [v] = exactly(numbers::<u32>(rest, line, "nurbs")?, line, "nurbs")?;
                if v != 1 {
                    return Err(NurbsFileError::Line {
                        line,
                        message: format!("format version {v} is not known (this reads version 1)"),
                    });
                }
                version = Some(v);
            }
            "name" => name = rest.join(" "),
            "degree" => degree = Some(exactly(numbers::<usize>(rest, line, "degree")?, line, "degree")?),
            "count" => count = Some(exactly(numbers::<usize>(rest, line, "count")?, line, "count")?),
            "knots" => {
                let slot = match rest.first() {
                    Some(&"u") => 0,
                    Some(&"v") => 1,
                    _ => {
                        return Err(NurbsFileError::Line {
                            line,
                            message: "knots must name their direction: `knots u ...` or `knots v ...`".into(),
                        });
                    }
                };
                knots[slot] = Some(numbers(&rest[1..], line, "knot")?);
            }
            "point" => {
                let [x, y, z, w] = exactly(numbers::<f64>(rest, line, "point")?, line, "point (x y z w)")?;
                points.push(DVec3::new(x, y, z));
                weights.push(w);
            }
            other => {
                return Err(NurbsFileError::Line {
                    line,
                    message: format!("unknown keyword `{other}` (nurbs, name, degree, count, knots, point)"),
                });
            }
        }
    }
    version.ok_or(NurbsFileError::Missing("nurbs 1"))?;
    let degree = degree.ok_or(NurbsFileError::Missing("degree"))?;
    let count = count.ok_or(NurbsFileError::Missing("count"))?;
    let [ku, kv] = knots;
    let knots = [
        ku.ok_or(NurbsFileError::Missing("knots u"))?,
        kv.ok_or(NurbsFileError::Missing("knots v"))?,
    ];
    let surface = NurbsSurface::new(degree, knots, count, &points, &weights)?;
    Ok(NamedSurface { name, surface })
}

/// Writes `surface` as `.nurbs` text (shortest round-trip floats, so reading it back gives
/// the same surface bit for bit).
pub fn write(name: &str, surface: &NurbsSurface) -> String {
    let mut out = format!("nurbs 1\nname {name}\n");
    let [pu, pv] = surface.degree();
    let [nu, nv] = surface.count();
    out += &format!("degree {pu} {pv}\ncount {nu} {nv}\n");
    for (dir, knots) in ["u", "v"].iter().zip(surface.knots()) {
        let list: Vec<String> = knots.iter().map(f64::to_string).collect();
        out += &format!("knots {dir} {}\n", list.join(" "));
    }
    for h in surface.net() {
        let p = h.truncate() / h.w;
        out += &format!("point {} {} {} {}\n", p.x, p.y, p.z, h.w);
    }
    out
}
