//! Names for files in REPORT/ made from names nobody checked: a student's
//! folder name may hold spaces, quotes, `<script>`, bytes that are not
//! UTF-8 or hundreds of characters. A slug holds only `[a-z0-9_-]`, is
//! never empty, never `.` or `..`, and is unique among the names slugged
//! together, so no name can make raystep write outside REPORT/ or onto
//! another student's files.

use std::collections::HashSet;

/// The longest slug, before a `-2` that keeps it unique.
const MAX_CHARS: usize = 48;

/// One slug per name, in order: unique among them. Equal slugs are told
/// apart by `-2`, `-3`, ... in the names' order.
pub(crate) fn slugs<'a>(names: impl IntoIterator<Item = &'a str>, fallback: &str) -> Vec<String> {
    let mut taken = HashSet::new();
    names
        .into_iter()
        .map(|name| {
            let base = slug(name, fallback);
            let mut candidate = base.clone();
            let mut n = 1;
            while !taken.insert(candidate.clone()) {
                n += 1;
                candidate = format!("{base}-{n}");
            }
            candidate
        })
        .collect()
}

/// `name` in lower-case ASCII letters, digits, `_` and `-`: every other
/// character (and run of them) becomes one `-`, none at either end, at
/// most `MAX_CHARS`; `fallback` when nothing is left.
fn slug(name: &str, fallback: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        let c = c.to_ascii_lowercase();
        if c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_' {
            out.push(c);
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    let cut: String = out.trim_matches('-').chars().take(MAX_CHARS).collect();
    let cut = cut.trim_end_matches('-');
    if cut.is_empty() {
        fallback.to_string()
    } else {
        cut.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn any_name_becomes_a_safe_unique_slug() {
        let long = "é".repeat(150) + &"a".repeat(300);
        let names = [
            "Ada Lovelace",
            "ada-lovelace",
            "ada_lovelace",
            "<script>alert(1)</script>",
            "../../etc",
            "..",
            "\u{fffd}\u{fffd}",
            "O'Brien \"quoted\"",
            long.as_str(),
            "",
        ];
        let slugs = slugs(names, "student");
        assert_eq!(
            slugs[..8],
            [
                "ada-lovelace",
                "ada-lovelace-2",
                "ada_lovelace",
                "script-alert-1-script",
                "etc",
                "student",
                "student-2",
                "o-brien-quoted",
            ]
        );
        // 150 'é' become one '-', dropped at the start: 48 'a'.
        assert_eq!(slugs[8], "a".repeat(48));
        assert_eq!(slugs[9], "student-3");
        for s in &slugs {
            assert!(
                s.chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || "_-".contains(c))
            );
        }
    }
}
