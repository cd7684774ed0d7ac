//! Names for files in REPORT/ made from names nobody checked: a student's
//! folder name may hold spaces, quotes, `<script>`, bytes that are not
//! UTF-8 or hundreds of characters. A slug holds only `[a-z0-9_-]`, is
//! never empty, never `.` or `..`, and is unique among the names slugged
//! together, so no name can make raystep write outside REPORT/ or onto
//! another student's files.

use std::collections::{HashMap, HashSet};

/// The longest slug, before a `-2` that keeps it unique.
const MAX_CHARS: usize = 48;

/// One slug per name, in order: unique among them. Equal slugs are told
/// apart by `-2`, `-3`, ... in the names' order: each name takes the
/// first of its slug, `-2`, `-3`, ... not taken by a name before it.
pub(crate) fn slugs<'a>(names: impl IntoIterator<Item = &'a str>, fallback: &str) -> Vec<String> {
    let mut taken = HashSet::new();
    // The number each slug last took (1 for the slug itself): every one
    // below it was taken then, and what is taken stays so, so the search
    // goes on from there instead of from 1 (20,000 names alike took 24 s,
    // 200 million tries).
    let mut last = HashMap::new();
    names
        .into_iter()
        .map(|name| {
            let base = slug(name, fallback);
            let n = last.entry(base.clone()).or_insert(1);
            let mut candidate = suffixed(&base, *n);
            while !taken.insert(candidate.clone()) {
                *n += 1;
                candidate = suffixed(&base, *n);
            }
            candidate
        })
        .collect()
}

/// `base` for 1, else `base-n`.
fn suffixed(base: &str, n: usize) -> String {
    if n == 1 {
        base.to_string()
    } else {
        format!("{base}-{n}")
    }
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

    #[test]
    fn a_name_whose_slug_another_took_by_number_goes_on_counting() {
        // By hand, each name taking the first of its slug, -2, -3, ... not
        // taken before it: "a-2" is taken by the second name itself, so
        // the third "a" goes past it to a-3; "a-3" (its own slug) is then
        // taken and becomes a-3-2; the fourth "a" skips a-2 and a-3 to
        // a-4; "a-2" again becomes a-2-2.
        let names = ["a", "a-2", "a", "a-3", "a", "a-2", "a-2-2"];
        assert_eq!(
            slugs(names, "student"),
            ["a", "a-2", "a-3", "a-3-2", "a-4", "a-2-2", "a-2-2-2"]
        );
    }

    #[test]
    fn two_hundred_thousand_names_alike_are_slugged_well_within_a_minute() {
        // main counted up from 2 for each name: 2 x 10^10 tries for these
        // (20,000 alike took 24 s in grade), hours; now 200,000 tries, a
        // fraction of a second. Run on a thread, so that a hang fails the
        // test instead of stalling it.
        let (done, finished) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let names = vec!["Ada Lovelace"; 200_000];
            let _ = done.send(slugs(names, "student"));
        });
        let slugs = finished
            .recv_timeout(std::time::Duration::from_secs(60))
            .expect("slugged within a minute");
        assert_eq!(slugs[0], "ada-lovelace");
        assert_eq!(slugs[1], "ada-lovelace-2");
        assert_eq!(slugs[199_999], "ada-lovelace-200000");
        assert_eq!(slugs.iter().collect::<HashSet<_>>().len(), 200_000);
    }
}
