//! The shape of `src/`, read from the source text (an independent reading: the compiler
//! accepts import circles, long files and long functions): no import circle between the
//! library's modules, no `super::super`, the steps as leaves (no file of
//! `session/steps/` imports another step or the dispatch), no file over 500 lines and no
//! function over 120.
//!
//! A module is a file (`a/b.rs` is `a::b`, `a/mod.rs` is `a`). Its imports are the paths of
//! its `use` statements (braces expanded), every `crate::`, `super::` and `self::` path in
//! its code, and every path through one of its own child modules (`steps::run`). A path is
//! read as the longest module it names; an item a folder's `mod.rs` re-exports (`pub use`)
//! is followed to the module that defines it, so `crate::session::RunOptions` is an import
//! of `session::options`. A folder's own `pub use` of its children is its front, not an
//! import. Unit tests (after `#[cfg(test)]`) are left out.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

type Module = Vec<String>;

fn src() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("a folder of src/")
        .map(|e| e.expect("an entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The text with comments, strings and character literals blanked (lines kept).
fn code_of(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let blank = |s: &[u8], out: &mut Vec<u8>| out.extend(s.iter().map(|&c| if c == b'\n' { b'\n' } else { b' ' }));
    let mut i = 0;
    while i < b.len() {
        let rest = &b[i..];
        let after_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        let end = if rest.starts_with(b"//") {
            rest.iter().position(|&c| c == b'\n').unwrap_or(rest.len())
        } else if rest.starts_with(b"/*") {
            rest.windows(2).position(|w| w == b"*/").map_or(rest.len(), |p| p + 2)
        } else if rest[0] == b'r' && !after_word && rest.len() > 1 && (rest[1] == b'"' || rest[1] == b'#') {
            let hashes = rest[1..].iter().take_while(|&&c| c == b'#').count();
            if rest.get(1 + hashes) != Some(&b'"') {
                out.push(rest[0]);
                i += 1;
                continue;
            }
            let mut close = vec![b'"'];
            close.extend(std::iter::repeat_n(b'#', hashes));
            let body = 2 + hashes;
            rest[body..]
                .windows(close.len())
                .position(|w| w == close.as_slice())
                .map_or(rest.len(), |p| body + p + close.len())
        } else if rest[0] == b'"' {
            let mut j = 1;
            while j < rest.len() && rest[j] != b'"' {
                j += if rest[j] == b'\\' { 2 } else { 1 };
            }
            j + 1
        } else if rest[0] == b'\'' && rest.len() > 2 && (rest[1] == b'\\' || rest[2] == b'\'') {
            // A character literal ('a', '\n', '\u{..}'); a lifetime has no closing quote.
            let close = rest[1..].iter().position(|&c| c == b'\'').map_or(1, |p| p + 2);
            if rest[1] != b'\\' && close != 3 {
                out.push(rest[0]);
                i += 1;
                continue;
            }
            close
        } else {
            out.push(rest[0]);
            i += 1;
            continue;
        };
        let end = end.min(rest.len());
        blank(&rest[..end], &mut out);
        i += end;
    }
    String::from_utf8(out).expect("blanking keeps UTF-8")
}

/// Each `use` tree expanded into its paths; `true` for a `pub use`.
fn use_paths(code: &str) -> Vec<(bool, Vec<String>)> {
    use_statements(code)
        .into_iter()
        .flat_map(|(public, paths, _)| paths.into_iter().map(move |p| (public, p)))
        .collect()
}

/// The code without its `use` statements and `pub(in path)` visibilities (what is left
/// names items where they are used).
fn uses_blanked(code: &str) -> String {
    let mut bytes = code.as_bytes().to_vec();
    let mut blank = |from: usize, to: usize| {
        for b in &mut bytes[from..to] {
            if *b != b'\n' {
                *b = b' ';
            }
        }
    };
    for (_, _, range) in use_statements(code) {
        blank(range.0, range.1);
    }
    for (at, _) in code.match_indices("pub(in ") {
        let end = code[at..].find(')').map_or(at, |p| at + p + 1);
        blank(at, end);
    }
    String::from_utf8(bytes).expect("blanking keeps UTF-8")
}

/// Each `use` statement: whether it is public, its paths, and its byte range.
#[allow(clippy::type_complexity)]
fn use_statements(code: &str) -> Vec<(bool, Vec<Vec<String>>, (usize, usize))> {
    fn expand(prefix: &[String], tree: &str, out: &mut Vec<Vec<String>>) {
        let (mut depth, mut start) = (0, 0);
        let mut parts = Vec::new();
        for (k, c) in tree.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    parts.push(&tree[start..k]);
                    start = k + 1;
                }
                _ => {}
            }
        }
        parts.push(&tree[start..]);
        for part in parts.into_iter().map(str::trim).filter(|p| !p.is_empty()) {
            let mut path = prefix.to_vec();
            if let Some(open) = part.find('{') {
                let close = part.rfind('}').expect("a closing brace");
                path.extend(segments(&part[..open]));
                expand(&path, &part[open + 1..close], out);
            } else {
                path.extend(segments(part.split(" as ").next().unwrap_or(part)));
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    let mut at = 0;
    for line in code.split_inclusive('\n') {
        let start = at;
        at += line.len();
        let trimmed = line.trim_start();
        let public = trimmed.starts_with("pub");
        let head = if public {
            // `pub use`, `pub(crate) use`, `pub(in crate::x) use`.
            let after = match trimmed[3..].strip_prefix('(') {
                Some(t) => t.find(')').map(|p| &t[p + 1..]),
                None => Some(&trimmed[3..]),
            };
            after.and_then(|t| t.trim_start().strip_prefix("use "))
        } else {
            trimmed.strip_prefix("use ")
        };
        let Some(head) = head else {
            continue;
        };
        let from = start + (line.len() - head.len());
        let Some(end) = code[from..].find(';') else {
            continue;
        };
        let mut paths = Vec::new();
        expand(&[], &code[from..from + end], &mut paths);
        out.push((public, paths, (start, from + end + 1)));
    }
    out
}

fn segments(path: &str) -> impl Iterator<Item = String> + '_ {
    path.split("::")
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(str::to_string)
}

/// Every `ident::ident...` path in the code (outside `use` statements too).
fn code_paths(code: &str) -> Vec<Vec<String>> {
    let bytes = code.as_bytes();
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if word(bytes[i]) && (i == 0 || !(word(bytes[i - 1]) || bytes[i - 1] == b':')) {
            let mut path = Vec::new();
            let mut j = i;
            loop {
                let start = j;
                while j < bytes.len() && word(bytes[j]) {
                    j += 1;
                }
                path.push(code[start..j].to_string());
                if code[j..].starts_with("::") && bytes.get(j + 2).is_some_and(|&c| word(c)) {
                    j += 2;
                } else {
                    break;
                }
            }
            if path.len() > 1 {
                out.push(path);
            }
            i = j.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

struct Tree {
    /// Module to its file's code (unit tests cut off).
    code: BTreeMap<Module, String>,
    /// Folder modules (`mod.rs`, `lib.rs`).
    folders: BTreeSet<Module>,
    /// Per folder module: a re-exported name to the path it re-exports.
    fronts: BTreeMap<Module, BTreeMap<String, Vec<String>>>,
}

impl Tree {
    fn read() -> Self {
        let mut files = Vec::new();
        rust_files(&src(), &mut files);
        let mut code = BTreeMap::new();
        let mut folders = BTreeSet::new();
        for path in files {
            let rel = path
                .strip_prefix(src())
                .expect("under src/")
                .to_string_lossy()
                .replace('\\', "/");
            if rel.starts_with("bin/") {
                continue;
            }
            let mut module: Module = rel.trim_end_matches(".rs").split('/').map(str::to_string).collect();
            if matches!(module.last().map(String::as_str), Some("mod" | "lib")) {
                module.pop();
                folders.insert(module.clone());
            }
            let text = std::fs::read_to_string(&path).expect("a source file");
            let text = code_of(&text);
            let text = match text.find("#[cfg(test)]") {
                Some(k) => text[..k].to_string(),
                None => text,
            };
            code.insert(module, text);
        }
        let mut tree = Tree {
            code,
            folders,
            fronts: BTreeMap::new(),
        };
        let mut fronts = BTreeMap::new();
        for folder in &tree.folders {
            for (public, path) in use_paths(&tree.code[folder]) {
                if let (true, Some(full)) = (public, tree.absolute(folder, &path)) {
                    let name = full.last().cloned().unwrap_or_default();
                    fronts
                        .entry(folder.clone())
                        .or_insert_with(BTreeMap::new)
                        .insert(name, full);
                }
            }
        }
        tree.fronts = fronts;
        tree
    }

    /// `path` from the crate's root, as written in `module`; `None` for another crate's.
    fn absolute(&self, module: &Module, path: &[String]) -> Option<Vec<String>> {
        let first = path.first()?;
        if first == "crate" {
            return Some(path[1..].to_vec());
        }
        let mut at = module.clone();
        let mut k = 0;
        while k < path.len() && (path[k] == "super" || path[k] == "self") {
            if path[k] == "super" {
                at.pop();
            }
            k += 1;
        }
        if k > 0 {
            at.extend_from_slice(&path[k..]);
            return Some(at);
        }
        let mut child = module.clone();
        child.push(first.clone());
        self.code.contains_key(&child).then(|| {
            child.extend_from_slice(&path[1..]);
            child
        })
    }

    /// The module that defines what `path` (from the root) names.
    fn resolve(&self, path: &[String], hops: usize) -> Option<Module> {
        (0..=path.len()).rev().find_map(|k| {
            let module: Module = path[..k].to_vec();
            if !self.code.contains_key(&module) {
                return None;
            }
            let front = path.get(k).and_then(|name| self.fronts.get(&module)?.get(name));
            match front {
                Some(target) if hops < 8 && target.as_slice() != path => self.resolve(target, hops + 1),
                _ => Some(module),
            }
        })
    }

    /// Every module's imports (itself left out).
    fn imports(&self) -> BTreeMap<Module, BTreeSet<Module>> {
        let mut edges = BTreeMap::new();
        for (module, code) in &self.code {
            let folder = self.folders.contains(module);
            let mut paths: Vec<Vec<String>> = use_paths(code)
                .into_iter()
                .filter(|(public, _)| !(folder && *public))
                .map(|(_, p)| p)
                .collect();
            let rest = uses_blanked(code);
            paths.extend(code_paths(&rest));
            // A name a folder re-exports and also uses in its own code is an import of it.
            if let Some(front) = self.fronts.get(module) {
                let words: BTreeSet<&str> = rest
                    .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .filter(|w| !w.is_empty())
                    .collect();
                paths.extend(front.iter().filter(|(n, _)| words.contains(n.as_str())).map(|(_, p)| {
                    let mut full = vec!["crate".to_string()];
                    full.extend(p.iter().cloned());
                    full
                }));
            }
            let mut to = BTreeSet::new();
            for path in paths {
                if let Some(target) = self.absolute(module, &path).and_then(|a| self.resolve(&a, 0))
                    && target != *module
                {
                    to.insert(target);
                }
            }
            edges.insert(module.clone(), to);
        }
        edges
    }
}

fn name(module: &Module) -> String {
    if module.is_empty() {
        "crate".to_string()
    } else {
        module.join("::")
    }
}

/// The strongly connected components of more than one module (Tarjan).
fn circles(edges: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<Vec<Module>> {
    struct Walk<'e> {
        edges: &'e BTreeMap<Module, BTreeSet<Module>>,
        index: BTreeMap<&'e Module, usize>,
        low: BTreeMap<&'e Module, usize>,
        stack: Vec<&'e Module>,
        on_stack: BTreeSet<&'e Module>,
        found: Vec<Vec<Module>>,
    }
    impl<'e> Walk<'e> {
        fn visit(&mut self, v: &'e Module) {
            let n = self.index.len();
            self.index.insert(v, n);
            self.low.insert(v, n);
            self.stack.push(v);
            self.on_stack.insert(v);
            for w in &self.edges[v] {
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut component = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    component.push(w.clone());
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 {
                    component.sort();
                    self.found.push(component);
                }
            }
        }
    }
    let mut walk = Walk {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !walk.index.contains_key(v) {
            walk.visit(v);
        }
    }
    walk.found
}

#[test]
fn the_reader_finds_a_circle_it_is_shown() {
    // Three modules, one through a folder's re-export, one through a child's path: the
    // reading must see the circle a -> b -> c -> a, and none once c's import is gone.
    let mut tree = Tree {
        code: BTreeMap::new(),
        folders: BTreeSet::new(),
        fronts: BTreeMap::new(),
    };
    let m = |s: &str| -> Module { s.split("::").map(str::to_string).collect() };
    tree.folders.insert(m("a"));
    tree.code
        .insert(m("a"), "mod b;\npub use b::Thing;\nfn f() { b::run(); }\n".into());
    tree.code
        .insert(m("a::b"), "use crate::c::{self, Other};\npub struct Thing;\n".into());
    tree.code
        .insert(m("c"), "pub struct Other;\nfn g(_: crate::a::Thing) {}\n".into());
    tree.fronts
        .insert(m("a"), BTreeMap::from([("Thing".to_string(), m("a::b::Thing"))]));
    let edges = tree.imports();
    assert_eq!(edges[&m("c")], BTreeSet::from([m("a::b")]), "the re-export is followed");
    assert!(edges[&m("a")].contains(&m("a::b")), "a child's path is an import");
    assert_eq!(circles(&edges), vec![vec![m("a::b"), m("c")]]);
    tree.code.insert(m("c"), "pub struct Other;\n".into());
    assert!(circles(&tree.imports()).is_empty());
}

#[test]
fn no_module_of_the_library_imports_itself_through_others() {
    let tree = Tree::read();
    let edges = tree.imports();
    let found = circles(&edges);
    let count: usize = edges.values().map(BTreeSet::len).sum();
    println!(
        "{} modules, {count} imports between them, {} circles",
        edges.len(),
        found.len()
    );
    let shown: Vec<String> = found
        .iter()
        .map(|c| {
            let members: BTreeSet<&Module> = c.iter().collect();
            c.iter()
                .map(|v| {
                    let to: Vec<String> = edges[v].iter().filter(|w| members.contains(w)).map(name).collect();
                    format!("{} -> {}", name(v), to.join(", "))
                })
                .collect::<Vec<_>>()
                .join("; ")
        })
        .collect();
    if std::env::var_os("LAYOUT_DEBUG").is_some() {
        for (m, to) in &edges {
            println!("{} -> {}", name(m), to.iter().map(name).collect::<Vec<_>>().join(", "));
        }
    }
    assert!(found.is_empty(), "import circles:\n{}", shown.join("\n"));
    assert!(edges.len() > 100 && count > 300, "the reader found too little to trust");
}

#[test]
fn the_steps_are_leaves() {
    let tree = Tree::read();
    let edges = tree.imports();
    let steps = vec!["session".to_string(), "steps".to_string()];
    let mut kinds = 0;
    for (module, to) in &edges {
        if module.len() == 3 && module.starts_with(&steps) {
            kinds += 1;
            let wrong: Vec<String> = to.iter().filter(|w| w.starts_with(&steps)).map(name).collect();
            assert!(wrong.is_empty(), "{} imports {wrong:?}", name(module));
        }
    }
    // The dispatch reaches every step but the scene, which the runner runs first.
    let dispatched = edges[&steps].iter().filter(|w| w.starts_with(&steps)).count();
    assert_eq!(dispatched + 1, kinds, "the steps run_step sends a step to");
    assert!(kinds >= 10, "{kinds} step files");
}

#[test]
fn no_path_climbs_two_folders() {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let found: Vec<String> = files
        .iter()
        .filter(|f| code_of(&std::fs::read_to_string(f).expect("a source file")).contains("super::super"))
        .map(|f| f.display().to_string())
        .collect();
    assert!(found.is_empty(), "super::super in {found:?}");
}

/// Each function's name and its length in lines, from its `fn` to its closing brace.
fn functions(code: &str) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for (at, _) in code.match_indices("fn ") {
        if at > 0 && code.as_bytes()[at - 1].is_ascii_alphanumeric() {
            continue;
        }
        let name: String = code[at + 3..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let Some(open) = code[at..].find(['{', ';']).map(|p| at + p) else {
            continue;
        };
        if name.is_empty() || code.as_bytes()[open] == b';' {
            continue;
        }
        let mut depth = 0;
        let mut close = open;
        for (k, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        close = open + k;
                        break;
                    }
                }
                _ => {}
            }
        }
        out.push((name, code[at..=close].lines().count()));
    }
    out
}

#[test]
fn no_file_is_over_500_lines_and_no_function_over_120() {
    assert_eq!(
        functions(&code_of("fn a() {\n    if x { y(\"}\") }\n}\nfn b();\nfn c() {}\n")),
        vec![("a".to_string(), 3), ("c".to_string(), 1)],
        "the function reader on a known text"
    );
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut long = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).expect("a source file");
        let lines = text.lines().count();
        if lines > 500 {
            long.push(format!("{}: {lines} lines", f.display()));
        }
        for (name, n) in functions(&code_of(&text)) {
            if n > 120 {
                long.push(format!("{}: fn {name} {n} lines", f.display()));
            }
        }
    }
    assert!(long.is_empty(), "too long:\n{}", long.join("\n"));
}
