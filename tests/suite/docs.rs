//! The documentation against the tree it documents: every module of `src/` is on the module
//! map of `docs/architecture.md` and every path on it exists; every relative link of the
//! README and the pages under `docs/` leads to a file, and every `#anchor` to a heading of
//! its page.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The code block under "### Code layout" in docs/architecture.md.
fn module_map() -> String {
    let text = std::fs::read_to_string(root().join("docs/architecture.md")).expect("docs/architecture.md");
    let from = text.find("### Code layout").expect("a Code layout section");
    let block = &text[from..];
    let start = block.find("```\n").expect("a code block") + 4;
    let end = block[start..].find("```").expect("its end") + start;
    block[start..end].to_string()
}

#[test]
fn the_module_map_names_every_module_and_only_paths_that_exist() {
    let map = module_map();
    // Every entry at the top of src/ (a folder or a file) is named on the map.
    let mut entries: Vec<String> = std::fs::read_dir(root().join("src"))
        .expect("src/")
        .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
        .collect();
    entries.sort();
    let missing: Vec<&String> = entries.iter().filter(|e| !map.contains(&format!("src/{e}"))).collect();
    assert!(
        missing.is_empty(),
        "not on the module map of docs/architecture.md: {missing:?}"
    );
    // Every src/ path on the map exists.
    let mut named = 0;
    for word in map.split(|c: char| c.is_whitespace() || c == ',') {
        if let Some(path) = word.strip_prefix("src/") {
            let path = path.trim_end_matches([':', ';', ')']);
            assert!(
                root().join("src").join(path).exists(),
                "docs/architecture.md names src/{path}, which does not exist"
            );
            named += 1;
        }
    }
    assert!(named >= entries.len(), "{named} paths named");
}

/// GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens.
fn anchor(heading: &str) -> String {
    heading
        .trim_start_matches('#')
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == '-' || *c == ' ' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The text outside fenced code blocks.
fn prose(text: &str) -> String {
    text.split("```").step_by(2).collect::<Vec<_>>().join("\n")
}

fn pages() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).expect("a folder") {
            let p = e.expect("an entry").path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p);
            }
        }
    }
    let mut out = vec![root().join("README.md"), root().join("CHANGELOG.md")];
    walk(&root().join("docs"), &mut out);
    out.sort();
    out
}

#[test]
fn every_link_of_the_readme_and_the_docs_leads_somewhere() {
    let headings = |p: &Path| -> Vec<String> {
        prose(&std::fs::read_to_string(p).expect("a page"))
            .lines()
            .filter(|l| l.starts_with('#'))
            .map(anchor)
            .collect()
    };
    let mut links = 0;
    for page in pages() {
        let text = prose(&std::fs::read_to_string(&page).expect("a page"));
        for (k, _) in text.match_indices("](") {
            let rest = &text[k + 2..];
            let Some(end) = rest.find(')') else { continue };
            let target = &rest[..end];
            if target.contains("://") || target.starts_with("mailto:") || target.contains(' ') {
                continue;
            }
            let (path, hash) = target.split_once('#').unwrap_or((target, ""));
            let file = if path.is_empty() {
                page.clone()
            } else {
                page.parent().expect("a folder").join(path)
            };
            assert!(file.exists(), "{}: the link {target} leads nowhere", page.display());
            if !hash.is_empty() && file.extension().is_some_and(|x| x == "md") {
                assert!(
                    headings(&file).iter().any(|h| h == hash),
                    "{}: no heading #{hash} in {}",
                    page.display(),
                    file.display()
                );
            }
            links += 1;
        }
    }
    assert!(links > 30, "{links} links");
}
