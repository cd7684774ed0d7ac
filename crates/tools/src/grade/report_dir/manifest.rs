//! Which files of a report raystep wrote. Each report holds
//! `.raystep-manifest.json`: the path of every file raystep wrote into it,
//! with its length and checksum. A file listed there and still as written
//! is raystep's, to replace; any other entry (a teacher's notes.txt, a
//! folder of comments, a link) is the teacher's, kept; a listed file that
//! was changed since (grades.csv edited in a spreadsheet) is the teacher's
//! work too, and is never replaced. A report written before the manifest
//! existed is read by raystep's layout instead (`grades.csv`,
//! `grades.json`, `index.html`, `reference/S.png`,
//! `images/S/S.yours.png` and `.flip.png`, `students/S.html`, S a slug).
//!
//! ```json
//! {"written_by": "raystep grade", "files": [
//!   {"path": "grades.csv", "bytes": 812, "fnv1a64": "9e2f0c6a41d57b13"}]}
//! ```

use std::collections::BTreeMap;
use std::fs::{self, File, FileType};
use std::io::{self, Read};
use std::path::{Path, PathBuf};

use serde_json::json;

/// The manifest's name in REPORT/.
pub(crate) const MANIFEST: &str = ".raystep-manifest.json";
/// A manifest longer than this is not read (a class of 10,000 students
/// lists some 50,000 files: about 5 MB).
const MAX_MANIFEST: u64 = 256 << 20;

/// 64-bit FNV-1a: a checksum that tells a changed file, not a defence
/// against a forged one (a teacher's edit is not an attack).
pub(crate) fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The manifest of `files`, the report's other files: its bytes.
pub(crate) fn write(files: &[(String, Vec<u8>)]) -> Vec<u8> {
    let mut sorted: Vec<&(String, Vec<u8>)> = files.iter().collect();
    sorted.sort_by(|a, b| a.0.cmp(&b.0));
    let listed: Vec<_> = sorted
        .iter()
        .map(|(path, bytes)| {
            json!({
                "path": path,
                "bytes": bytes.len(),
                "fnv1a64": format!("{:016x}", fnv1a64(bytes)),
            })
        })
        .collect();
    let value = json!({"written_by": "raystep grade", "files": listed});
    let mut text = serde_json::to_string_pretty(&value).expect("a JSON value prints");
    text.push('\n');
    text.into_bytes()
}

/// Whose an entry of a report is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Owner {
    /// Written by raystep, and as written.
    Raystep,
    /// Listed in the manifest, but not as raystep wrote it.
    Changed,
    /// Not raystep's: the teacher's.
    Teacher,
}

/// What raystep wrote into one report folder.
pub(crate) struct Written {
    dir: PathBuf,
    /// Path -> (length, checksum); None: read by the layout.
    listed: Option<BTreeMap<String, (u64, u64)>>,
}

impl Written {
    /// Reads `dir`'s manifest; without one (or one unreadable), its layout.
    pub(crate) fn read(dir: &Path) -> Written {
        Written {
            dir: dir.to_owned(),
            listed: read_manifest(&dir.join(MANIFEST)),
        }
    }

    /// Whether `dir` holds a manifest raystep wrote.
    pub(crate) fn has_manifest(&self) -> bool {
        self.listed.is_some()
    }

    /// Whose the entry at `relative`, of type `kind`, is.
    pub(crate) fn owner(&self, relative: &Path, kind: FileType) -> Owner {
        // raystep writes regular files only, under ASCII names.
        let Some(name) = relative.to_str().filter(|_| kind.is_file()) else {
            return Owner::Teacher;
        };
        let Some(listed) = &self.listed else {
            return if in_layout(name) {
                Owner::Raystep
            } else {
                Owner::Teacher
            };
        };
        if name == MANIFEST {
            return Owner::Raystep;
        }
        match listed.get(name) {
            None => Owner::Teacher,
            Some(&(bytes, hash)) if unchanged(&self.dir.join(relative), bytes, hash) => {
                Owner::Raystep
            }
            Some(_) => Owner::Changed,
        }
    }
}

/// Every entry of a report that is not a folder, and every empty folder,
/// each with its path relative to the report, and whose it is.
pub(crate) struct Survey {
    pub(crate) entries: Vec<(PathBuf, Owner)>,
}

impl Survey {
    /// The entries that are not raystep's as written, to keep.
    pub(crate) fn kept(&self) -> impl Iterator<Item = &Path> {
        (self.entries.iter())
            .filter(|(_, owner)| *owner != Owner::Raystep)
            .map(|(path, _)| path.as_path())
    }

    /// The files raystep wrote that were changed since.
    pub(crate) fn changed(&self) -> impl Iterator<Item = &Path> {
        (self.entries.iter())
            .filter(|(_, owner)| *owner == Owner::Changed)
            .map(|(path, _)| path.as_path())
    }
}

/// Surveys the report `dir`, links never followed.
pub(crate) fn survey(dir: &Path) -> io::Result<Survey> {
    let written = Written::read(dir);
    let mut entries = Vec::new();
    walk(dir, |relative, kind, empty_dir| {
        if !kind.is_dir() {
            entries.push((relative.to_owned(), written.owner(relative, kind)));
        } else if empty_dir {
            entries.push((relative.to_owned(), Owner::Teacher));
        }
    })?;
    entries.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(Survey { entries })
}

/// Calls `visit(relative path, type, is an empty folder)` for every entry
/// under `dir`, each folder before what it holds, links never followed.
pub(crate) fn walk(dir: &Path, mut visit: impl FnMut(&Path, FileType, bool)) -> io::Result<()> {
    let mut stack = vec![PathBuf::new()];
    while let Some(folder) = stack.pop() {
        let mut names: Vec<PathBuf> = fs::read_dir(dir.join(&folder))?
            .map(|e| e.map(|e| folder.join(e.file_name())))
            .collect::<io::Result<_>>()?;
        names.sort();
        for relative in names {
            let path = dir.join(&relative);
            let kind = fs::symlink_metadata(&path)?.file_type();
            let empty = kind.is_dir() && fs::read_dir(&path)?.next().is_none();
            visit(&relative, kind, empty);
            if kind.is_dir() && !empty {
                stack.push(relative);
            }
        }
    }
    Ok(())
}

fn read_manifest(path: &Path) -> Option<BTreeMap<String, (u64, u64)>> {
    let meta = fs::symlink_metadata(path).ok()?;
    if !meta.is_file() || meta.len() > MAX_MANIFEST {
        return None;
    }
    let value: serde_json::Value = serde_json::from_slice(&fs::read(path).ok()?).ok()?;
    if value.get("written_by")?.as_str()? != "raystep grade" {
        return None;
    }
    let mut listed = BTreeMap::new();
    for file in value.get("files")?.as_array()? {
        let path = file.get("path")?.as_str()?;
        let bytes = file.get("bytes")?.as_u64()?;
        let hash = u64::from_str_radix(file.get("fnv1a64")?.as_str()?, 16).ok()?;
        listed.insert(path.to_owned(), (bytes, hash));
    }
    Some(listed)
}

/// Whether the file at `path` is `bytes` long with checksum `hash`: its
/// length first, its bytes read only when that agrees.
fn unchanged(path: &Path, bytes: u64, hash: u64) -> bool {
    if !fs::symlink_metadata(path).is_ok_and(|m| m.is_file() && m.len() == bytes) {
        return false;
    }
    let Ok(file) = File::open(path) else {
        return false;
    };
    let mut state = 0xcbf2_9ce4_8422_2325u64;
    let mut reader = io::BufReader::new(file.take(bytes + 1));
    let mut buffer = [0u8; 64 * 1024];
    let mut read = 0u64;
    loop {
        match reader.read(&mut buffer) {
            Ok(0) => break,
            Ok(n) => {
                read += n as u64;
                for &b in &buffer[..n] {
                    state = (state ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
                }
            }
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(_) => return false,
        }
    }
    read == bytes && state == hash
}

/// Whether `relative` is a file raystep's report layout holds.
fn in_layout(relative: &str) -> bool {
    let slug = |s: &str| {
        !s.is_empty()
            && s.bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_' || b == b'-')
    };
    let parts: Vec<&str> = relative.split('/').collect();
    match parts[..] {
        [name] => ["grades.csv", "grades.json", "index.html"].contains(&name),
        ["reference", name] => name.strip_suffix(".png").is_some_and(slug),
        ["students", name] => name.strip_suffix(".html").is_some_and(slug),
        ["images", student, name] => {
            slug(student)
                && (name
                    .strip_suffix(".yours.png")
                    .or(name.strip_suffix(".flip.png")))
                .is_some_and(slug)
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_checksum_is_fnv1a_64() {
        // The published test vectors of FNV-1a 64.
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn the_layout_is_raystep_s_names_only() {
        for ours in [
            "grades.csv",
            "index.html",
            "reference/shadows.png",
            "images/ada-2/shadows.yours.png",
            "images/ada/glass_1.flip.png",
            "students/o-brien-q.html",
        ] {
            assert!(in_layout(ours), "{ours}");
        }
        for theirs in [
            "notes.txt",
            "reference/Shadows.png",
            "images/ada/notes.txt",
            "images/ada/shadows.png",
            "students/ada.html.bak",
            "students/x/ada.html",
            "comments/grades.csv",
        ] {
            assert!(!in_layout(theirs), "{theirs}");
        }
    }
}
