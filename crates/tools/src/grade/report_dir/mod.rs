//! REPORT/, written as `render` writes its files (see `crate::output`):
//! checked before grading starts, built whole in a hidden folder beside it,
//! and put in place in one step when every file is written (`swap`), so a
//! failure, a kill or a second run at once leaves REPORT whole, the
//! previous report or the new one.
//!
//! An existing REPORT is replaced only when it is empty or a previous
//! report (its grades.json is one `raystep grade` wrote, or its manifest);
//! of a previous report only what raystep wrote is replaced, the teacher's
//! own files kept (`manifest`). REPORT may not be, hold or lie inside the
//! assignment, a scene file or the submissions, however its path is spelt:
//! paths are compared once made canonical.

mod manifest;
mod swap;

use std::fs;
use std::io::{self, Write};
use std::path::{Component, Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};

use swap::{Building, Hidden, ParentLock};

/// A previous report's grades.json larger than this is not read.
const MAX_GRADES_JSON: u64 = 1 << 30;

/// The report folder, checked.
#[derive(Debug)]
pub struct ReportDir {
    /// As the user gave it, for messages.
    shown: PathBuf,
    /// Canonical: its existing part resolved, the missing part appended.
    real: PathBuf,
    /// What cleaning up after a killed run could not do.
    warnings: Vec<String>,
}

impl ReportDir {
    /// Checks `dir` as REPORT/: `inputs` are the files and folders it may
    /// neither be, hold nor lie in, each with what it is for messages.
    /// What killed runs left beside it is cleaned up (`warnings` says what
    /// could not be).
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
            .unwrap_or(Path::new("/"))
            .to_owned();
        let mut report = ReportDir {
            shown: dir.to_owned(),
            real,
            warnings: Vec::new(),
        };
        let parent = report.real.parent().expect("checked: not the root");
        if existing != parent {
            tempfile::Builder::new()
                .prefix(".raystep-probe-")
                .tempdir_in(&existing)
                .and_then(|probe| probe.close())
                .map_err(|e| fail(format!("{} is not writable ({e})", existing.display())))?;
            return Ok(report);
        }
        // With the parent locked, as every hidden folder is made, every
        // leftover cleaned up and REPORT read: no other run is changing it.
        let locked = ParentLock::take(parent);
        // Named as a build is, so that a kill here leaves nothing that a
        // re-run does not remove.
        (Hidden::of(&report.real).new_folder(swap::BUILDING_PREFIX))
            .and_then(fs::remove_dir)
            .map_err(|e| fail(format!("{} is not writable ({e})", parent.display())))?;
        report.warnings = swap::repair(&report.real, &locked);
        (report.check_replaceable(None)).map_err(|e| fail(format!("{e:#}")))?;
        Ok(report)
    }

    /// What cleaning up after killed runs could not do, for warnings.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
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

    /// An existing REPORT must be a folder that is empty or a previous
    /// report, whose files raystep wrote are as it wrote them, and none of
    /// the teacher's where a file of `new` goes.
    fn check_replaceable(&self, new: Option<&[PathBuf]>) -> Result<Option<manifest::Survey>> {
        let meta = match fs::symlink_metadata(&self.shown) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(e.into()),
            Ok(meta) => meta,
        };
        if meta.file_type().is_symlink() {
            bail!("it is a symbolic link: name the folder itself");
        }
        if !meta.is_dir() {
            bail!("it is a file, not a folder");
        }
        let empty = fs::read_dir(&self.real)?.next().is_none();
        if empty {
            return Ok(None);
        }
        if !is_report(&self.real) {
            bail!(
                "it is a folder that is not a raystep report (no grades.json of `raystep grade` \
                 in it), and it would be replaced: name a new folder, or empty this one"
            );
        }
        let survey = manifest::survey(&self.real)?;
        swap::refuse_in_the_way(&survey, new.unwrap_or_default())?;
        Ok(Some(survey))
    }

    /// Writes `files` (paths relative to REPORT/, with `/`) as the whole
    /// report, replacing the previous one (the teacher's files in it kept).
    /// Says what of the previous report could not be removed.
    pub fn write(&self, files: &[(String, Vec<u8>)]) -> Result<Vec<String>> {
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

    fn write_beside(&self, parent: &Path, files: &[(String, Vec<u8>)]) -> Result<Vec<String>> {
        let hidden = Hidden::of(&self.real);
        let building = Building::new(&hidden, &ParentLock::take(parent))?;
        let written = fill(&building.path, files).and_then(|new| {
            let locked = ParentLock::take(parent);
            // Grading took a while: look again before replacing anything.
            if let Some(survey) = self.check_replaceable(Some(&new))? {
                swap::carry(&survey, &self.real, &building.path, &new)?;
                keep_mode(&self.real, &building.path)?;
            }
            let warnings = swap::swap(&building.path, &self.real, &hidden)?;
            drop(locked);
            Ok(warnings)
        });
        if written.is_err() {
            // raystep's new files, and second links to the teacher's.
            let _ = fs::remove_dir_all(&building.path);
        }
        written
    }
}

/// The new report gets the previous one's mode (a teacher's `chmod 700`).
fn keep_mode(previous: &Path, new: &Path) -> io::Result<()> {
    fs::set_permissions(new, fs::metadata(previous)?.permissions())
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

/// Whether `dir` holds a manifest or a grades.json that `raystep grade`
/// wrote: a JSON object with its `title`, `scenes`, `students` and
/// `max_total`.
fn is_report(dir: &Path) -> bool {
    if manifest::Written::read(dir).has_manifest() {
        return true;
    }
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

/// Writes each file into `root`, refusing a path that could leave it, and
/// last the manifest, so that every file it lists is whole; the files
/// written.
fn fill(root: &Path, files: &[(String, Vec<u8>)]) -> Result<Vec<PathBuf>> {
    let manifest = (manifest::MANIFEST.to_owned(), manifest::write(files));
    let mut written = Vec::new();
    for (relative, bytes) in files.iter().chain([&manifest]) {
        let path = inside(root, relative)?;
        if let Some(folder) = path.parent() {
            fs::create_dir_all(folder)?;
        }
        let mut file =
            fs::File::create_new(&path).with_context(|| format!("cannot write {relative}"))?;
        file.write_all(bytes)
            .with_context(|| format!("cannot write {relative}"))?;
        written.push(PathBuf::from(relative));
    }
    Ok(written)
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

    /// A small report: a grades.json `raystep grade` could have written,
    /// and a grades.csv and an image that say which run wrote them.
    fn a_report(run: &str) -> Vec<(String, Vec<u8>)> {
        let grades = format!(
            "{{\"title\": \"{run}\", \"scenes\": [], \"students\": [], \"max_total\": 0}}\n"
        );
        vec![
            (
                "grades.csv".into(),
                format!("student,total\r\n{run},0\r\n").into(),
            ),
            ("grades.json".into(), grades.into()),
            (
                "images/ada/shadows.yours.png".into(),
                run.as_bytes().to_vec(),
            ),
        ]
    }

    /// Asserts that `dir` holds exactly `files` (paths with `/`), these bytes.
    fn holds(dir: &Path, files: &[(&str, &[u8])]) {
        let mut found = Vec::new();
        let mut stack = vec![dir.to_owned()];
        while let Some(folder) = stack.pop() {
            for entry in fs::read_dir(&folder).unwrap() {
                let path = entry.unwrap().path();
                let name = path.strip_prefix(dir).unwrap().to_str().unwrap().to_owned();
                if path.is_dir() {
                    stack.push(path);
                } else if name != ".raystep-manifest.json" {
                    found.push((name, fs::read(&path).unwrap()));
                }
            }
        }
        found.sort();
        let mut expected: Vec<(String, Vec<u8>)> = (files.iter())
            .map(|(name, bytes)| (name.to_string(), bytes.to_vec()))
            .collect();
        expected.sort();
        assert_eq!(found, expected);
    }

    /// The names in `dir`, sorted.
    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        names
    }

    /// TAG of the hidden folders of a REPORT named `name`: FNV-1a 64 of
    /// its bytes (offset basis 0xcbf29ce484222325, prime 0x100000001b3),
    /// in 16 hex digits, computed here from its definition.
    fn tag(name: &str) -> String {
        let mut hash: u64 = 14695981039346656037;
        for b in name.bytes() {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(1099511628211);
        }
        format!("{hash:016x}")
    }

    fn write_report(report: &Path, run: &str) {
        let checked = ReportDir::check(report, &[]).unwrap();
        checked.write(&a_report(run)).unwrap();
    }

    #[test]
    fn a_rerun_puts_back_the_report_a_kill_left_hidden_between_two_renames() {
        // Issue 41: killed between its two renames, `grade` left no REPORT
        // at all, the previous one hidden; a re-run cleaned nothing.
        let top = tempfile::tempdir().unwrap();
        let report = top.path().join("REPORT");
        write_report(&report, "first");
        fs::write(report.join("notes.txt"), "the teacher's").unwrap();
        let hidden = top
            .path()
            .join(format!(".raystep-old-report-{}-999-0", tag("REPORT")));
        fs::rename(&report, &hidden).unwrap();
        write_report(&report, "second");
        // The previous report came back, and was replaced, the teacher's
        // notes kept; nothing is left beside it.
        holds(
            &report,
            &[
                ("grades.csv", b"student,total\r\nsecond,0\r\n"),
                ("grades.json", &a_report("second")[1].1),
                ("images/ada/shadows.yours.png", b"second"),
                ("notes.txt", b"the teacher's"),
            ],
        );
        assert_eq!(names(top.path()), ["REPORT"]);
    }

    #[test]
    fn a_rerun_removes_the_unfinished_build_a_kill_left_and_only_that() {
        let top = tempfile::tempdir().unwrap();
        let report = top.path().join("REPORT");
        write_report(&report, "first");
        // A build killed half-way (no manifest yet), a build still running
        // (locked by its run), and another report's leftover.
        let killed = top
            .path()
            .join(format!(".raystep-report-{}-999-0", tag("REPORT")));
        fs::create_dir_all(killed.join("images/ada")).unwrap();
        fs::write(killed.join("grades.csv"), "half").unwrap();
        let running = top
            .path()
            .join(format!(".raystep-report-{}-998-0", tag("REPORT")));
        fs::create_dir(&running).unwrap();
        let held = fs::File::open(&running).unwrap();
        held.lock().unwrap();
        let other = format!(".raystep-report-{}-999-0", tag("OTHER"));
        fs::create_dir(top.path().join(&other)).unwrap();
        write_report(&report, "second");
        let mut left = vec![
            other,
            format!(".raystep-report-{}-998-0", tag("REPORT")),
            "REPORT".to_string(),
        ];
        left.sort();
        assert_eq!(names(top.path()), left);
        assert_eq!(
            fs::read(report.join("grades.json")).unwrap(),
            a_report("second")[1].1
        );
    }

    #[test]
    fn a_rerun_retires_the_previous_report_a_kill_left_after_the_exchange() {
        // Killed once the new report was in place and the previous one
        // beside it: the previous one's files are raystep's (removed), the
        // teacher's linked into REPORT (removed) or saved there while the
        // run was placing it (moved into REPORT, not lost).
        let top = tempfile::tempdir().unwrap();
        let report = top.path().join("REPORT");
        let previous = top.path().join("previous");
        write_report(&previous, "first");
        fs::write(previous.join("notes.txt"), "the teacher's").unwrap();
        write_report(&report, "second");
        fs::hard_link(previous.join("notes.txt"), report.join("notes.txt")).unwrap();
        fs::write(previous.join("late.txt"), "saved late").unwrap();
        let hidden = top
            .path()
            .join(format!(".raystep-report-{}-999-0", tag("REPORT")));
        fs::rename(&previous, &hidden).unwrap();
        write_report(&report, "third");
        holds(
            &report,
            &[
                ("grades.csv", b"student,total\r\nthird,0\r\n"),
                ("grades.json", &a_report("third")[1].1),
                ("images/ada/shadows.yours.png", b"third"),
                ("notes.txt", b"the teacher's"),
                ("late.txt", b"saved late"),
            ],
        );
        assert_eq!(names(top.path()), ["REPORT"]);
        // Two different files of the teacher's at one place: the one in
        // REPORT stays, and so does the other, where it was, said.
        let previous = top.path().join("previous");
        write_report(&previous, "fourth");
        fs::write(previous.join("late.txt"), "another").unwrap();
        fs::rename(&previous, &hidden).unwrap();
        let checked = ReportDir::check(&report, &[]).unwrap();
        let warnings = format!("{checked:?}");
        assert!(
            warnings.contains("late.txt could be neither removed nor moved"),
            "{warnings}"
        );
        assert_eq!(fs::read(report.join("late.txt")).unwrap(), b"saved late");
        assert_eq!(fs::read(hidden.join("late.txt")).unwrap(), b"another");
        assert_eq!(names(&hidden), [".raystep-manifest.json", "late.txt"]);
    }

    #[test]
    fn the_new_report_keeps_the_previous_one_s_permissions() {
        // A teacher's `chmod 700 REPORT` keeps the grades to the teacher.
        use std::os::unix::fs::PermissionsExt;
        let top = tempfile::tempdir().unwrap();
        let report = top.path().join("REPORT");
        write_report(&report, "first");
        fs::set_permissions(&report, fs::Permissions::from_mode(0o700)).unwrap();
        write_report(&report, "second");
        let mode = fs::metadata(&report).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o700);
    }

    #[test]
    fn report_is_never_missing_while_it_is_replaced() {
        // Issue 41: between the two renames there was no REPORT at all. A
        // reader looking all the time must always find one, whole.
        let top = tempfile::tempdir().unwrap();
        let report = top.path().join("REPORT");
        write_report(&report, "run 0");
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let looking = {
            let (stop, report) = (stop.clone(), report.clone());
            std::thread::spawn(move || {
                let (mut looks, mut missing) = (0u64, 0u64);
                while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                    looks += 1;
                    if fs::symlink_metadata(report.join("grades.json")).is_err() {
                        missing += 1;
                    }
                }
                (looks, missing)
            })
        };
        for run in 1..=100 {
            write_report(&report, &format!("run {run}"));
        }
        stop.store(true, std::sync::atomic::Ordering::Relaxed);
        let (looks, missing) = looking.join().unwrap();
        assert!(looks > 100, "the reader looked {looks} times");
        assert_eq!(missing, 0, "missing {missing} times in {looks} looks");
        assert_eq!(names(top.path()), ["REPORT"]);
    }

    #[test]
    fn two_runs_writing_the_same_report_at_once_both_end_whole() {
        // Issue 41: two runs finishing together failed with "Directory not
        // empty". Each of two threads writes its own report 40 times.
        let top = tempfile::tempdir().unwrap();
        let report = top.path().join("REPORT");
        let runs: Vec<_> = ["a", "b"]
            .into_iter()
            .map(|run| {
                let report = report.clone();
                std::thread::spawn(move || {
                    (0..40)
                        .map(|_| {
                            let checked = ReportDir::check(&report, &[])?;
                            checked.write(&a_report(run)).map(|_| ())
                        })
                        .filter_map(Result::err)
                        .map(|e| format!("{e:#}"))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        let failures: Vec<String> = runs.into_iter().flat_map(|r| r.join().unwrap()).collect();
        assert!(failures.is_empty(), "{failures:#?}");
        // One of the two, whole; nothing beside it.
        let last = fs::read(report.join("grades.csv")).unwrap();
        let run = if last.ends_with(b"a,0\r\n") { "a" } else { "b" };
        holds(
            &report,
            &[
                ("grades.csv", &a_report(run)[0].1),
                ("grades.json", &a_report(run)[1].1),
                ("images/ada/shadows.yours.png", run.as_bytes()),
            ],
        );
        assert_eq!(names(top.path()), ["REPORT"]);
    }
}
