//! Puts a benchmark's table into a docs page, between `<!-- figures:NAME -->` and
//! `<!-- /figures:NAME -->` (shared by the benchmarks that write their figures).

/// Replaces the text between the markers of `name` in `path` with `body`.
pub fn write_block(path: &str, name: &str, body: &str) {
    let text = std::fs::read_to_string(path).expect("the docs page");
    let (open, close) = (
        format!("<!-- figures:{name} -->\n"),
        format!("<!-- /figures:{name} -->"),
    );
    let start = text.find(&open).expect("the opening marker") + open.len();
    let end = text.find(&close).expect("the closing marker");
    let updated = format!("{}{body}{}", &text[..start], &text[end..]);
    std::fs::write(path, updated).expect("the docs page written");
    println!("{path}: figures:{name} rewritten");
}
