//! REPORT/, written as `render` writes its files (see `crate::output`):
//! checked before grading starts, built whole in a hidden folder beside it,
//! and renamed into place only when every file is written, so a failure
//! leaves nothing half-written and the old report as it was.
//!
//! An existing REPORT is replaced only when it is empty or a previous
//! report (its grades.json is one `raystep grade` wrote). REPORT may not
//! be, hold or lie inside the assignment, a scene file or the submissions,
//! however its path is spelt: paths are compared once made canonical.

use std::fs;
use std::io::{self, Write};
use std::path::{Component, Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};

/// The hidden folder a report is built in, beside REPORT.
const BUILDING_PREFIX: &str = ".raystep-report-";
/// Where the previous report goes while the new one takes its place.
const OLD_PREFIX: &str = ".raystep-old-report-";
/// A previous report's grades.json larger than this is not read.
const MAX_GRADES_JSON: u64 = 1 << 30;

/// The report folder, checked.
#[derive(Debug)]
pub struct ReportDir {
    /// As the user gave it, for messages.
    shown: PathBuf,
    /// Canonical: its existing part resolved, the missing part appended.
    real: PathBuf,
}

impl ReportDir {
    /// Checks `dir` as REPORT/: `inputs` are the files and folders it may
    /// neither be, hold nor lie in, each with what it is for messages.
    pub fn check(dir: &Path, inputs: &[(&Path, String)]) -> Result<ReportDir> {
        let fail = |why: String| anyhow!("cannot write the report into {}: {why}", dir.display());
        let real = resolve(dir).map_err(|e| fail(format!("{e:#}")))?;
        if real.parent().is_none() {
            return Err(fail("it is the root folder".into()));
        }
        for (input, what) in inputs {
            let Ok(input_real) = fs::canonicalize(input) else {
                continue;
            };
            if input_real == real {
                return Err(fail(format!("it is {what} {}", input.display())));
            }
            if input_real.starts_with(&real) {
                return Err(fail(format!("it holds {what} {}", input.display())));
            }
            if real.starts_with(&input_real) {
                return Err(fail(format!("it lies inside {what} {}", input.display())));
            }
        }
        // Where the report will be built must be writable now, not only
        // once the class is graded.
        let existing = real
            .ancestors()
            .skip(1)
            .find(|d| fs::symlink_metadata(d).is_ok())
            .unwrap_or(Path::new("/"));
        let probe = new_folder_in(existing, BUILDING_PREFIX)
            .map_err(|e| fail(format!("{} is not writable ({e})", existing.display())))?;
        let _ = fs::remove_dir(probe);
        let report = ReportDir {
            shown: dir.to_owned(),
            real,
        };
        report.check_replaceable()?;
        Ok(report)
    }

    /// Refuses an output file of the same run (`flag` names it) that is
    /// REPORT, lies in it (REPORT is replaced whole), or would hold it.
    pub fn refuse_overlap(&self, path: &Path, flag: &str) -> Result<()> {
        // A path that cannot be resolved is refused by its own checks.
        let Ok(real) = resolve(path) else {
            return Ok(());
        };
        let (file, report) = (path.display(), self.shown.display());
        if real == self.real {
            bail!("cannot write {file} ({flag}): it is the report folder {report} (-o)");
        }
        if real.starts_with(&self.real) {
            bail!(
                "cannot write {file} ({flag}): it lies inside the report folder {report} (-o), \
                 which raystep replaces whole"
            );
        }
        if self.real.starts_with(&real) {
            bail!("cannot write {file} ({flag}): the report folder {report} (-o) lies inside it");
        }
        Ok(())
    }

    /// An existing REPORT must be a folder that is empty or a previous report.
    fn check_replaceable(&self) -> Result<()> {
        let fail = |why: &str| {
            anyhow!(
                "cannot write the report into {}: {why}",
                self.shown.display()
            )
        };
        let meta = match fs::symlink_metadata(&self.shown) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(()),
            Err(e) => return Err(fail(&e.to_string())),
            Ok(meta) => meta,
        };
        if meta.file_type().is_symlink() {
            return Err(fail("it is a symbolic link: name the folder itself"));
        }
        if !meta.is_dir() {
            return Err(fail("it is a file, not a folder"));
        }
        let empty = fs::read_dir(&self.real)
            .map_err(|e| fail(&e.to_string()))?
            .next()
            .is_none();
        if !empty && !is_report(&self.real) {
            return Err(fail(
                "it is a folder that is not a raystep report (no grades.json of `raystep grade` \
                 in it), and it would be replaced: name a new folder, or empty this one",
            ));
        }
        Ok(())
    }

    /// Writes `files` (paths relative to REPORT/, with `/`) as the whole
    /// report, replacing the previous one.
    pub fn write(&self, files: &[(String, Vec<u8>)]) -> Result<()> {
        let fail = || format!("cannot write the report into {}", self.shown.display());
        let parent = self.real.parent().expect("checked: not the root");
        let made = create_folders(parent).with_context(fail)?;
        let placed = self.write_beside(parent, files);
        if placed.is_err() {
            // Only the folders this run made, deepest first, if empty.
            for dir in made.iter().rev() {
                let _ = fs::remove_dir(dir);
            }
        }
        placed.with_context(fail)
    }

    fn write_beside(&self, parent: &Path, files: &[(String, Vec<u8>)]) -> Result<()> {
        let building = new_folder_in(parent, BUILDING_PREFIX)?;
        let written = fill(&building, files).and_then(|()| {
            // Grading took a while: look again before replacing anything.
            self.check_replaceable()?;
            self.put_in_place(&building, parent)
        });
        if written.is_err() {
            let _ = fs::remove_dir_all(&building);
        }
        written
    }

    /// Renames the built folder to REPORT, the previous one out of the way
    /// first and back if that fails.
    fn put_in_place(&self, building: &Path, parent: &Path) -> Result<()> {
        if fs::symlink_metadata(&self.real).is_err() {
            fs::rename(building, &self.real)?;
            return Ok(());
        }
        let old = new_folder_in(parent, OLD_PREFIX)?;
        fs::remove_dir(&old)?;
        fs::rename(&self.real, &old)?;
        if let Err(e) = fs::rename(building, &self.real) {
            let _ = fs::rename(&old, &self.real);
            return Err(e.into());
        }
        fs::remove_dir_all(&old).with_context(|| {
            format!(
                "the new report is in place, but the old one is left in {}",
                old.display()
            )
        })
    }
}

/// `dir` made canonical: its nearest existing ancestor resolved (links,
/// `..`), the missing rest appended (where `..` cannot be resolved).
fn resolve(dir: &Path) -> Result<PathBuf> {
    let mut existing = dir;
    let mut missing = Vec::new();
    while !existing.as_os_str().is_empty() && fs::symlink_metadata(existing).is_err() {
        match existing.components().next_back() {
            Some(Component::Normal(name)) => missing.push(name),
            Some(Component::CurDir) => {}
            _ => bail!("it goes through `..` below a missing folder"),
        }
        existing = existing.parent().unwrap_or(Path::new(""));
    }
    if existing.as_os_str().is_empty() {
        existing = Path::new(".");
    }
    let mut real = fs::canonicalize(existing)?;
    real.extend(missing.iter().rev());
    Ok(real)
}

/// Whether `dir` holds a grades.json that `raystep grade` wrote: a JSON
/// object with its `title`, `scenes`, `students` and `max_total`.
fn is_report(dir: &Path) -> bool {
    let path = dir.join("grades.json");
    let small_file =
        fs::symlink_metadata(&path).is_ok_and(|m| m.is_file() && m.len() <= MAX_GRADES_JSON);
    if !small_file {
        return false;
    }
    let Ok(text) = fs::read(&path) else {
        return false;
    };
    serde_json::from_slice::<serde_json::Value>(&text).is_ok_and(|v| {
        ["title", "scenes", "students", "max_total"]
            .iter()
            .all(|key| v.get(key).is_some())
    })
}

/// Creates `dir` and its missing ancestors; the ones made, outermost first.
fn create_folders(dir: &Path) -> io::Result<Vec<PathBuf>> {
    let made: Vec<PathBuf> = dir
        .ancestors()
        .take_while(|d| fs::symlink_metadata(d).is_err())
        .map(Path::to_owned)
        .collect();
    fs::create_dir_all(dir)?;
    Ok(made.into_iter().rev().collect())
}

/// A new empty folder in `parent` named `prefix` and a free suffix, with
/// the mode any new folder gets.
fn new_folder_in(parent: &Path, prefix: &str) -> io::Result<PathBuf> {
    for n in 0u32.. {
        let path = parent.join(format!("{prefix}{}-{n}", std::process::id()));
        match fs::create_dir(&path) {
            Ok(()) => return Ok(path),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::other("no free folder name"))
}

/// Writes each file into `root`, refusing a path that could leave it.
fn fill(root: &Path, files: &[(String, Vec<u8>)]) -> Result<()> {
    for (relative, bytes) in files {
        let path = inside(root, relative)?;
        if let Some(folder) = path.parent() {
            fs::create_dir_all(folder)?;
        }
        let mut file =
            fs::File::create_new(&path).with_context(|| format!("cannot write {relative}"))?;
        file.write_all(bytes)
            .with_context(|| format!("cannot write {relative}"))?;
    }
    Ok(())
}

/// `root` joined to `relative`, which must be plain names joined by `/`
/// (the report's own names are slugs: anything else is a bug).
fn inside(root: &Path, relative: &str) -> Result<PathBuf> {
    let plain = |part: &str| {
        !part.is_empty()
            && part != "."
            && part != ".."
            && part
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "._-".contains(c))
    };
    if !relative.split('/').all(plain) {
        bail!("refused to write {relative:?}: not a plain path inside the report");
    }
    Ok(root.join(relative))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_plain_paths_are_written_inside_the_report() {
        let root = Path::new("/r");
        assert_eq!(
            inside(root, "images/ada/glass.yours.png").unwrap(),
            Path::new("/r/images/ada/glass.yours.png")
        );
        for bad in [
            "../x",
            "a/../../x",
            "/etc/passwd",
            "a//b",
            "a/./b",
            "<script>.html",
            "",
        ] {
            assert!(inside(root, bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_missing_folder_resolves_below_its_existing_ancestor() {
        let top = tempfile::tempdir().unwrap();
        let real_top = fs::canonicalize(top.path()).unwrap();
        fs::create_dir(top.path().join("a")).unwrap();
        let spelt = top.path().join("a/../a/./new/report");
        assert_eq!(resolve(&spelt).unwrap(), real_top.join("a/new/report"));
        let below = top.path().join("missing/../x");
        assert!(resolve(&below).is_err());
    }
}
