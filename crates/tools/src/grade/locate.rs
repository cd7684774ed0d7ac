//! Which file in a student's folder is taken for each name the assignment
//! asks for, the folder read as a download leaves it:
//!
//! - what an operating system or an archiver leaves (`__MACOSX`, `.DS_Store`
//!   and every other name starting with a dot, `Thumbs.db`, `desktop.ini`)
//!   is never a student's file (`is_junk`);
//! - a folder that holds exactly one folder and none of the files asked for
//!   (`STUDENT/lab4-submission/*.png`, what zipping a folder gives) is read
//!   one level down, with a note;
//! - a name that differs from the one asked for only in case, spaces or a
//!   doubled extension (`Shadows.PNG`, `mirrors.png.png`, `prism .png`) is
//!   taken for it, with a note the student sees, unless the assignment says
//!   `strict_names = true`; two such names for one file are refused, never
//!   guessed between;
//! - a missing file's refusal names the closest names the folder holds.

use std::ffi::{OsStr, OsString};
use std::fs;
use std::path::{Path, PathBuf};

/// Names no student hands in: what macOS, Windows and archivers leave
/// beside the files (every name starting with a dot is one too).
const JUNK: [&str; 3] = ["__MACOSX", "Thumbs.db", "desktop.ini"];

/// How many of the names a folder holds a missing file's refusal names.
const CLOSEST: usize = 3;

/// Whether `name` is left by a system or an archiver, not by a student: a
/// dot name (`.DS_Store`, `._shadows.png`, `.git`), `__MACOSX`,
/// `Thumbs.db`, `desktop.ini` (these three in any case).
pub(crate) fn is_junk(name: &OsStr) -> bool {
    let bytes = name.as_encoded_bytes();
    bytes.first() == Some(&b'.')
        || JUNK
            .iter()
            .any(|j| j.as_bytes().eq_ignore_ascii_case(bytes))
}

/// What was found in one student's folder.
pub(crate) struct Found {
    /// The folder the files are read from (canonical): the student's, or
    /// the one folder in it.
    pub folder: PathBuf,
    /// What the student should know about where the files were read from.
    pub notes: Vec<String>,
    /// Per name asked for, in the assignment's order: the file taken for
    /// it, or why none was.
    pub files: Vec<Result<Taken, String>>,
}

/// The file taken for a name asked for.
#[derive(Debug, PartialEq)]
pub(crate) struct Taken {
    /// Its name in `Found::folder`.
    pub name: String,
    /// "took Shadows.PNG for shadows.png" when it is not the name asked for.
    pub note: Option<String>,
}

/// One entry of a folder, junk left out.
struct Entry {
    name: OsString,
    /// Its name; `None` when it is not UTF-8 (never taken for a name asked
    /// for, which always is).
    text: Option<String>,
    /// Its name as shown (invalid UTF-8 as U+FFFD, a folder with `/`).
    shown: String,
    /// A real folder, not a link to one (a link is never gone down).
    folder: bool,
}

/// Finds the files `submits` in the student's `root` folder (canonical);
/// `strict` takes only exact names. `Err` when the folder cannot be read.
pub(crate) fn locate(root: &Path, submits: &[&str], strict: bool) -> Result<Found, String> {
    let unreadable = |e: std::io::Error| format!("cannot read the student's folder: {e}");
    let mut folder = root.to_path_buf();
    let mut entries = read_entries(&folder).map_err(unreadable)?;
    let mut notes = Vec::new();
    let asked_for = |entries: &[Entry], folder: &Path| {
        submits.iter().any(|submit| {
            fs::symlink_metadata(folder.join(submit)).is_ok()
                || entries
                    .iter()
                    .any(|e| e.text.as_deref().is_some_and(|t| near(t, submit)))
        })
    };
    let folders: Vec<&Entry> = entries.iter().filter(|e| e.folder).collect();
    if let [only] = folders[..]
        && !asked_for(&entries, &folder)
        // A real folder inside (never a link): what lies in it lies in the
        // student's.
        && let Ok(real) = fs::canonicalize(root.join(&only.name))
        && real.starts_with(root)
        && let Ok(inside) = read_entries(&real)
    {
        notes.push(format!(
            "your files were read from the folder {}, the one folder in yours",
            only.shown
        ));
        folder = real;
        entries = inside;
    }
    let files = take(&folder, &entries, submits, strict);
    Ok(Found {
        folder,
        notes,
        files,
    })
}

/// The entries of `folder`, junk left out, sorted by their names as shown.
fn read_entries(folder: &Path) -> std::io::Result<Vec<Entry>> {
    let mut found = Vec::new();
    for entry in fs::read_dir(folder)? {
        let entry = entry?;
        let name: OsString = entry.file_name();
        if is_junk(&name) {
            continue;
        }
        let folder = entry.file_type().is_ok_and(|t| t.is_dir());
        let text = name.to_str().map(str::to_string);
        let mut shown = quoted(&name.to_string_lossy());
        if folder {
            shown.push('/');
        }
        found.push(Entry {
            name,
            text,
            shown,
            folder,
        });
    }
    // The folder's order is the file system's: sort, so every message is
    // the same whatever it is.
    found.sort_by(|a, b| a.shown.cmp(&b.shown));
    Ok(found)
}

/// The file taken for each of `submits` among `entries` of `folder`.
fn take(
    folder: &Path,
    entries: &[Entry],
    submits: &[&str],
    strict: bool,
) -> Vec<Result<Taken, String>> {
    let exact: Vec<bool> = submits
        .iter()
        .map(|s| fs::symlink_metadata(folder.join(s)).is_ok())
        .collect();
    // A file named exactly as one scene asks is never another's near miss.
    let claimed = |text: &str| submits.iter().zip(&exact).any(|(s, e)| *e && *s == text);
    let candidates: Vec<Vec<&str>> = submits
        .iter()
        .zip(&exact)
        .map(|(submit, exact)| {
            if *exact {
                return Vec::new();
            }
            entries
                .iter()
                .filter_map(|e| e.text.as_deref())
                .filter(|t| near(t, submit) && !claimed(t))
                .collect()
        })
        .collect();
    let taken: Vec<Option<&str>> = candidates
        .iter()
        .map(|c| match c[..] {
            [one] if !strict => Some(one),
            _ => None,
        })
        .collect();
    submits
        .iter()
        .enumerate()
        .map(|(i, submit)| {
            if exact[i] {
                return Ok(Taken {
                    name: submit.to_string(),
                    note: None,
                });
            }
            let shown: Vec<String> = candidates[i].iter().map(|c| quoted(c)).collect();
            if strict && !shown.is_empty() {
                return Err(format!(
                    "missing: the folder holds no {submit}, only {} (the assignment asks for \
                     exact names: strict_names = true)",
                    list(&shown)
                ));
            }
            if shown.len() > 1 {
                return Err(format!(
                    "{} files could be {submit}: {}; rename the one you mean to {submit}",
                    shown.len(),
                    list(&shown)
                ));
            }
            let Some(one) = taken[i] else {
                // What another name took or could take is accounted for there.
                return Err(missing(entries, submit, |t| {
                    claimed(t) || candidates.iter().any(|c| c.contains(&t))
                }));
            };
            // One file, the near miss of two names: which it is, is a guess.
            let others: Vec<&str> = (0..submits.len())
                .filter(|&j| j != i && taken[j] == Some(one))
                .map(|j| submits[j])
                .collect();
            if !others.is_empty() {
                let mut names = vec![submit.to_string()];
                names.extend(others.iter().map(|o| o.to_string()));
                return Err(format!(
                    "{} could be {}: rename it to the one you mean",
                    quoted(one),
                    list_or(&names)
                ));
            }
            Ok(Taken {
                name: one.to_string(),
                note: Some(format!("took {} for {submit}", quoted(one))),
            })
        })
        .collect()
}

/// A missing file's refusal: the closest names the folder holds, those
/// another name took or could take (`taken`) left out.
fn missing(entries: &[Entry], submit: &str, taken: impl Fn(&str) -> bool) -> String {
    let mut rest: Vec<(usize, &str)> = entries
        .iter()
        .filter(|e| !e.text.as_deref().is_some_and(&taken))
        .map(|e| {
            let name = e.text.as_deref().unwrap_or(&e.shown);
            (
                distance(&name.to_lowercase(), &submit.to_lowercase()),
                e.shown.as_str(),
            )
        })
        .collect();
    let mut message = format!("missing: the folder holds no {submit}");
    if rest.is_empty() {
        return message;
    }
    rest.sort();
    let mut named: Vec<String> = rest
        .iter()
        .take(CLOSEST)
        .map(|(_, s)| s.to_string())
        .collect();
    if rest.len() > CLOSEST {
        named.push(format!("{} more", rest.len() - CLOSEST));
    }
    message.push_str("; the folder holds ");
    message.push_str(&list(&named));
    message
}

/// Whether `name` differs from `submit` only in case, white space or a
/// doubled extension.
pub(crate) fn near(name: &str, submit: &str) -> bool {
    name != submit && key(name, submit) == key(submit, submit)
}

/// `name` lower-cased, its white space removed, and the extension of
/// `submit` (`.png`) that ends it twice or more kept once.
fn key(name: &str, submit: &str) -> String {
    let mut key: String = name
        .chars()
        .filter(|c| !c.is_whitespace())
        .flat_map(char::to_lowercase)
        .collect();
    let extension = Path::new(submit)
        .extension()
        .and_then(OsStr::to_str)
        .map(|e| format!(".{}", e.to_lowercase()));
    if let Some(extension) = extension.filter(|e| e.len() > 1) {
        let twice = extension.repeat(2);
        while key.ends_with(&twice) {
            key.truncate(key.len() - extension.len());
        }
    }
    key
}

/// Levenshtein's distance between `a` and `b`, in characters: the fewest
/// insertions, deletions and substitutions that make one the other.
pub(crate) fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substituted = diagonal + usize::from(ca != *cb);
            diagonal = row[j + 1];
            row[j + 1] = substituted.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

/// A name as messages write it: in quotes when white space could hide in
/// it (`"prism .png"`).
pub(crate) fn quoted(name: &str) -> String {
    if name.chars().any(char::is_whitespace) {
        format!("\"{name}\"")
    } else {
        name.to_string()
    }
}

/// `a`, `a and b`, `a, b and c`.
fn list(items: &[String]) -> String {
    join(items, "and")
}

/// `a or b`, `a, b or c`.
fn list_or(items: &[String]) -> String {
    join(items, "or")
}

fn join(items: &[String], word: &str) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [head @ .., last] => format!("{} {word} {last}", head.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A folder holding `files` (empty files; a name ending in `/` a folder).
    fn folder(files: &[&str]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        for file in files {
            let path = dir.path().join(file);
            if file.ends_with('/') {
                fs::create_dir_all(path).unwrap();
            } else {
                fs::create_dir_all(path.parent().unwrap()).unwrap();
                fs::write(path, b"").unwrap();
            }
        }
        dir
    }

    fn found(files: &[&str], submits: &[&str], strict: bool) -> Found {
        let dir = folder(files);
        let root = fs::canonicalize(dir.path()).unwrap();
        locate(&root, submits, strict).unwrap()
    }

    fn took(name: &str, submit: &str) -> Result<Taken, String> {
        Ok(Taken {
            name: name.into(),
            note: Some(format!("took {name} for {submit}")),
        })
    }

    #[test]
    fn near_names_differ_only_in_case_spaces_or_a_doubled_extension() {
        for name in [
            "Shadows.PNG",
            "shadows.png.png",
            "shadows .png",
            " shadows.png ",
            "SHADOWS.PNG.png.PNG",
        ] {
            assert!(near(name, "shadows.png"), "{name}");
        }
        // Not near: another name, extension or a single letter more.
        for name in [
            "shadows.png",
            "shadow.png",
            "shadows.jpg",
            "shadows.png.txt",
            "shadows2.png",
            "shadows.pngpng",
        ] {
            assert!(!near(name, "shadows.png"), "{name}");
        }
    }

    #[test]
    fn distances_by_hand() {
        // kitten -> sitten -> sittin -> sitting: two substitutions, one insertion.
        assert_eq!(distance("kitten", "sitting"), 3);
        assert_eq!(distance("shadow.png", "shadows.png"), 1);
        // png -> jpg: p for j, n for p.
        assert_eq!(distance("shadows.jpg", "shadows.png"), 2);
        assert_eq!(distance("", "abc"), 3);
        assert_eq!(distance("é", "e"), 1);
    }

    #[test]
    fn junk_is_dot_names_macosx_thumbs_and_desktop_ini() {
        for name in [
            ".DS_Store",
            ".git",
            "._shadows.png",
            "__MACOSX",
            "Thumbs.db",
            "thumbs.db",
            "Desktop.ini",
        ] {
            assert!(is_junk(OsStr::new(name)), "{name}");
        }
        for name in ["ada", "MACOSX", "Thumbs.db.png", "shadows.png"] {
            assert!(!is_junk(OsStr::new(name)), "{name}");
        }
    }

    #[test]
    fn exact_names_first_then_one_near_miss_with_a_note() {
        let found = found(
            &["a.png", "B.PNG", "c .png", ".DS_Store"],
            &["a.png", "b.png", "c.png"],
            false,
        );
        assert!(found.notes.is_empty());
        assert_eq!(
            found.files,
            [
                Ok(Taken {
                    name: "a.png".into(),
                    note: None
                }),
                took("B.PNG", "b.png"),
                Ok(Taken {
                    name: "c .png".into(),
                    note: Some("took \"c .png\" for c.png".into())
                }),
            ]
        );
    }

    #[test]
    fn two_candidates_or_one_file_for_two_names_are_refused() {
        let found = found(
            &["B.png", "b.PNG", "x.png", "A.png"],
            &["b.png", "a.png", "A.PNG"],
            false,
        );
        assert_eq!(
            found.files[0],
            Err("2 files could be b.png: B.png and b.PNG; rename the one you mean to b.png".into())
        );
        // a.png and A.PNG are asked for, neither is there; A.png is the
        // near miss of both: one file, two names.
        assert_eq!(
            found.files[1],
            Err("A.png could be a.png or A.PNG: rename it to the one you mean".into())
        );
        // An exact name is never another's near miss.
        let found = self::found(&["a.png", "A.png"], &["a.png", "A.PNG"], false);
        assert_eq!(
            found.files[0],
            Ok(Taken {
                name: "a.png".into(),
                note: None
            })
        );
        assert_eq!(found.files[1], took("A.png", "A.PNG"));
    }

    #[test]
    fn strict_names_refuse_a_near_miss_naming_it() {
        let found = found(&["Shadows.PNG"], &["shadows.png"], true);
        assert_eq!(
            found.files[0],
            Err(
                "missing: the folder holds no shadows.png, only Shadows.PNG (the assignment \
                 asks for exact names: strict_names = true)"
                    .into()
            )
        );
    }

    #[test]
    fn a_missing_file_names_the_closest_names_held() {
        // Distances to shadows.png: shadow.png 1, shadows.jpg 2,
        // shadows.png.txt 4 (".txt" added), zz.bin at least 5 (5 characters
        // shorter); highlights.png is taken for the other scene, not named.
        let found = found(
            &[
                "zz.bin",
                "shadows.png.txt",
                "shadow.png",
                "shadows.jpg",
                "highlights.png",
            ],
            &["shadows.png", "highlights.png"],
            false,
        );
        assert_eq!(
            found.files[0],
            Err(
                "missing: the folder holds no shadows.png; the folder holds shadow.png, \
                 shadows.jpg, shadows.png.txt and 1 more"
                    .into()
            )
        );
        // Nothing else held: the message as it always was.
        let found = self::found(
            &["highlights.png"],
            &["shadows.png", "highlights.png"],
            false,
        );
        assert_eq!(
            found.files[0],
            Err("missing: the folder holds no shadows.png".into())
        );
        // Near misses of another name are that name's business, even when
        // refused as two.
        let found = self::found(&["A.png", "a.PNG", "b.txt"], &["a.png", "b.png"], false);
        assert_eq!(
            found.files[1],
            Err("missing: the folder holds no b.png; the folder holds b.txt".into())
        );
    }

    #[test]
    fn one_folder_and_no_file_asked_for_is_read_one_level_down() {
        let found = found(
            &[
                "lab 4/Shadows.png",
                "lab 4/glass.png",
                "__MACOSX/lab 4/._glass.png",
                "README.txt",
            ],
            &["shadows.png", "glass.png"],
            false,
        );
        assert_eq!(
            found.notes,
            ["your files were read from the folder \"lab 4\"/, the one folder in yours"]
        );
        assert!(found.folder.ends_with("lab 4"));
        assert_eq!(found.files[0], took("Shadows.png", "shadows.png"));
        assert_eq!(
            found.files[1],
            Ok(Taken {
                name: "glass.png".into(),
                note: None
            })
        );
        // A file asked for beside the folder, or two folders: not gone down.
        for files in [&["a/glass.png", "Glass.PNG"][..], &["a/glass.png", "b/"]] {
            let found = self::found(files, &["glass.png"], false);
            assert!(found.notes.is_empty(), "{files:?}");
        }
    }
}
