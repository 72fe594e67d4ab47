//! Fuzzed parsers: the session parser and the OBJ reader on mutated and generated inputs
//! return (no panic), and every error names its place: the file, and a line that exists
//! (1 past the last at most). Bounded here (512 cases each, a second or two); a long run:
//! `PROPTEST_CASES=200000 cargo test --release fuzz`.

use std::path::Path;

use drape::mesh::MeshFileError;
use drape::mesh::obj::parse_obj;
use drape::session::{DEMO_SESSION, parse_session};
use proptest::prelude::*;

/// Pieces that make parsers stumble: separators, signs, exponents, non-numbers, huge and
/// tiny numbers, unicode, control characters, names that nearly exist.
const PIECES: &[&str] = &[
    " ",
    "\t",
    "\n",
    "\r\n",
    "=",
    ",",
    "/",
    "#",
    "-",
    "+",
    ".",
    "e",
    "E",
    "0",
    "1",
    "9",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1e309",
    "-1e-320",
    "0x10",
    "1_000",
    "é",
    "∞",
    "\u{0}",
    "\u{feff}",
    "by=",
    "at=",
    "normal=",
    "name=",
    "y=",
    "garment",
    "jumpsuit",
    "dress",
    "set",
    "drag",
    "undo",
    "cut",
    "waist",
    "waist.front",
    "ease",
    "m1",
    "body",
    "builtin",
    "units",
    "mm",
    "section",
    "mannequin",
    "resolution=",
    "fit=",
    "tight",
    "v",
    "f",
    "vn",
    "vt",
    "o",
    "g",
    "s",
    "//",
    "1/2/3",
    "-1",
    "0.5",
    "999999999999999999999",
];

/// A mutation of a text: delete a range, insert pieces, duplicate a range, or cut it short.
#[derive(Clone, Debug)]
enum Mutation {
    Delete(usize, usize),
    Insert(usize, Vec<usize>),
    Duplicate(usize, usize),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 0usize..40).prop_map(|(a, n)| Mutation::Delete(a, n)),
        (any::<usize>(), prop::collection::vec(0..PIECES.len(), 1..6)).prop_map(|(a, p)| Mutation::Insert(a, p)),
        (any::<usize>(), 0usize..80).prop_map(|(a, n)| Mutation::Duplicate(a, n)),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

/// `text` with `mutations` applied, positions taken modulo the length and moved back to
/// a character boundary.
fn mutate(text: &str, mutations: &[Mutation]) -> String {
    let mut s = text.to_string();
    let at = |s: &str, a: usize| {
        let mut a = a % (s.len() + 1);
        while !s.is_char_boundary(a) {
            a -= 1;
        }
        a
    };
    for m in mutations {
        match m {
            Mutation::Delete(a, n) => {
                let a = at(&s, *a);
                let b = at(&s, (a + n).min(s.len()));
                if b > a {
                    s.replace_range(a..b, "");
                }
            }
            Mutation::Insert(a, pieces) => {
                let a = at(&s, *a);
                let insert: String = pieces.iter().map(|&k| PIECES[k]).collect();
                s.insert_str(a, &insert);
            }
            Mutation::Duplicate(a, n) => {
                let a = at(&s, *a);
                let b = at(&s, (a + n).min(s.len()));
                let copy = s[a..b].to_string();
                s.insert_str(b, &copy);
            }
            Mutation::Truncate(a) => {
                let a = at(&s, *a);
                s.truncate(a);
            }
        }
    }
    s
}

/// Lines built from the pieces alone (after the header, or without it).
fn generated() -> impl Strategy<Value = String> {
    (
        any::<bool>(),
        prop::collection::vec(prop::collection::vec(0..PIECES.len(), 0..10), 0..12),
    )
        .prop_map(|(header, lines)| {
            let mut s = if header { "drape 1\n".to_string() } else { String::new() };
            for line in lines {
                s.extend(line.iter().map(|&k| PIECES[k]));
                s.push('\n');
            }
            s
        })
}

const OBJ: &str = "# a tetrahedron\no tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0 0\n\
f 1 3 2\nf 1//1 2//1 4//1\nf 1/1 4/1 3/1\nf 2 3 4\n";

fn lines_of(text: &str) -> usize {
    text.split('\n').count()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(super::common::proptest_cases(512)))]

    #[test]
    fn the_session_parser_survives_mutations_and_names_the_place(
        mutations in prop::collection::vec(mutation(), 1..6)
    ) {
        let text = mutate(DEMO_SESSION, &mutations);
        if let Err(e) = parse_session(&text, "fuzz.drape", Path::new(".")) {
            let shown = e.to_string();
            prop_assert!(shown.starts_with("fuzz.drape:"), "{shown}");
            prop_assert!(e.line >= 1 && e.line <= lines_of(&text) + 1, "line {} of {}: {shown}", e.line, lines_of(&text));
            prop_assert!(!e.message.is_empty());
        }
    }

    #[test]
    fn the_session_parser_survives_generated_lines_and_names_the_place(text in generated()) {
        if let Err(e) = parse_session(&text, "fuzz.drape", Path::new(".")) {
            let shown = e.to_string();
            prop_assert!(shown.starts_with("fuzz.drape:"), "{shown}");
            prop_assert!(e.line >= 1 && e.line <= lines_of(&text) + 1, "line {}: {shown}", e.line);
        }
    }

    #[test]
    fn the_obj_reader_survives_mutations_and_names_the_place(
        mutations in prop::collection::vec(mutation(), 1..6)
    ) {
        let text = mutate(OBJ, &mutations);
        match parse_obj(&text, "fuzz.obj", 1.0) {
            Ok(m) => {
                // What it read is a mesh: every corner names a vertex it read.
                let n = m.mesh.positions.len() as u32;
                prop_assert!(m.mesh.triangles.iter().flatten().all(|&v| v < n));
                prop_assert!(m.mesh.positions.iter().all(|p| p.is_finite()));
            }
            Err(MeshFileError::Syntax { path, line, message, .. }) => {
                prop_assert_eq!(path, "fuzz.obj");
                prop_assert!(line >= 1 && line <= lines_of(&text) + 1, "line {line}: {message}");
            }
            Err(e) => prop_assert!(e.to_string().starts_with("fuzz.obj"), "{e}"),
        }
    }
}
