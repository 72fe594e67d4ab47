//! "Did you mean": the known name nearest a misspelt one, by edit distance.

/// The Levenshtein distance between `a` and `b` (insertions, deletions and substitutions of
/// characters).
pub(super) fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1).min(row[j] + 1).min(diagonal + usize::from(ca != *cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

/// The known name nearest `asked`, if it is near enough to be a slip (at most a third of the
/// name's characters, and at least 2, differ). Ties go to the first in `known`.
pub(super) fn nearest<'k>(asked: &str, known: impl IntoIterator<Item = &'k str>) -> Option<&'k str> {
    let limit = (asked.chars().count() / 3).max(2);
    known
        .into_iter()
        .map(|k| (edit_distance(asked, k), k))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// `" (did you mean 'x'?)"` for the nearest known name, or nothing.
pub(super) fn did_you_mean<'k>(asked: &str, known: impl IntoIterator<Item = &'k str>) -> String {
    nearest(asked, known).map_or_else(String::new, |k| format!(" (did you mean '{k}'?)"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_and_suggestions() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("waist.frnt", "waist.front"), 1);
        assert_eq!(
            nearest("waist.frnt", ["waist.front", "waist.back"]),
            Some("waist.front")
        );
        assert_eq!(nearest("xyz", ["waist.front"]), None);
    }
}
