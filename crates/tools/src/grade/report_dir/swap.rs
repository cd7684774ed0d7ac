//! The new report put in REPORT's place, so that REPORT is never missing,
//! never half-written, and nothing of the teacher's is lost.
//!
//! - A report is built in a hidden folder beside REPORT,
//!   `.raystep-report-TAG-PID-N` (TAG: 16 hex digits, the FNV-1a of
//!   REPORT's name, so that each REPORT knows its own), locked (`flock`)
//!   while its run lives.
//! - The teacher's entries of the previous report are hard-linked into it
//!   (`carry`), then the two folders are exchanged in one step (Linux's
//!   `renameat2` with `RENAME_EXCHANGE`; elsewhere, or on a file system
//!   without it, two renames, the previous report in
//!   `.raystep-old-report-TAG-PID-N` between them), and the previous one is
//!   retired (`retire`): raystep's files as written and the teacher's
//!   entries now in REPORT are removed, anything else moved into REPORT.
//! - Every change beside REPORT (a hidden folder made, the exchange, a
//!   leftover cleaned up) happens while the run holds a lock on REPORT's
//!   parent folder, so two runs never exchange at once, and a hidden folder
//!   of REPORT found unlocked is a killed run's leftover (`repair`), retired
//!   as a previous report is: nothing in one is ever the only copy of the
//!   teacher's work, and what is not in REPORT is moved there.

use std::collections::BTreeSet;
use std::ffi::OsStr;
use std::fs::{self, File};
use std::io;
use std::path::{Path, PathBuf};

use anyhow::{Result, bail};

use super::manifest::{self, MANIFEST, Owner, Survey, Written};

/// A report being built.
pub(crate) const BUILDING_PREFIX: &str = ".raystep-report-";
/// The previous report between two renames, where REPORT cannot be
/// exchanged in one step.
const OLD_PREFIX: &str = ".raystep-old-report-";
/// The most entries a message names.
const NAMED: usize = 8;

/// The hidden folders of one REPORT: where they go and their TAG.
pub(crate) struct Hidden<'a> {
    parent: &'a Path,
    tag: String,
}

impl<'a> Hidden<'a> {
    /// The hidden folders of `report` (a canonical path, not the root).
    pub(crate) fn of(report: &'a Path) -> Hidden<'a> {
        let name = report.file_name().unwrap_or(OsStr::new(""));
        Hidden {
            parent: report.parent().unwrap_or(Path::new("/")),
            tag: format!("{:016x}", manifest::fnv1a64(name.as_encoded_bytes())),
        }
    }

    /// A new empty folder named `prefix`, TAG, this process and a free
    /// number, with the mode any new folder gets.
    pub(crate) fn new_folder(&self, prefix: &str) -> io::Result<PathBuf> {
        for n in 0u32.. {
            let name = format!("{prefix}{}-{}-{n}", self.tag, std::process::id());
            let path = self.parent.join(name);
            match fs::create_dir(&path) {
                Ok(()) => return Ok(path),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(e),
            }
        }
        Err(io::Error::other("no free folder name"))
    }

    /// The hidden folders of REPORT beside it, each with whether it is a
    /// previous report between two renames.
    fn found(&self) -> Vec<(PathBuf, bool)> {
        let Ok(entries) = fs::read_dir(self.parent) else {
            return Vec::new();
        };
        let mut found: Vec<(PathBuf, bool)> = entries
            .flatten()
            .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
            .filter_map(|e| {
                let name = e.file_name();
                let name = name.to_str()?;
                let old = [(BUILDING_PREFIX, false), (OLD_PREFIX, true)]
                    .into_iter()
                    .find(|(prefix, _)| {
                        name.strip_prefix(prefix)
                            .and_then(|rest| rest.strip_prefix(&self.tag))
                            .is_some_and(|rest| rest.starts_with('-'))
                    })?
                    .1;
                Some((e.path(), old))
            })
            .collect();
        // Previous reports first: one may have to go back into place.
        found.sort_by_key(|(path, old)| (!old, path.clone()));
        found
    }
}

/// A lock on REPORT's parent folder while a run changes what is in it:
/// `flock`, released when dropped or when the run dies. Where folders
/// cannot be locked (some network file systems), runs go unlocked.
pub(crate) struct ParentLock {
    _file: Option<File>,
}

impl ParentLock {
    /// Waits for the lock on `parent`.
    pub(crate) fn take(parent: &Path) -> ParentLock {
        let file = File::open(parent).ok().filter(|f| f.lock().is_ok());
        ParentLock { _file: file }
    }
}

/// A report being built: its hidden folder, locked while this run lives.
pub(crate) struct Building {
    pub(crate) path: PathBuf,
    _lock: Option<File>,
}

impl Building {
    /// Makes and locks the folder: with the parent locked, so that no other
    /// run takes it for a leftover in between.
    pub(crate) fn new(hidden: &Hidden, _parent_locked: &ParentLock) -> io::Result<Building> {
        let path = hidden.new_folder(BUILDING_PREFIX)?;
        let lock = File::open(&path).ok().filter(|f| f.try_lock().is_ok());
        Ok(Building { path, _lock: lock })
    }
}

/// Whether no living run holds `dir` (a hidden folder): a leftover. A
/// folder that cannot be locked is taken for a living run's.
fn abandoned(dir: &Path) -> bool {
    File::open(dir).is_ok_and(|f| f.try_lock().is_ok())
}

/// Cleans up what killed runs writing `report` left beside it, with the
/// parent locked: a previous report left between two renames goes back
/// into place when REPORT is missing; any other leftover (a build, whole
/// or not, or a previous report) is retired into REPORT. Says what it
/// could not clean up.
pub(crate) fn repair(report: &Path, _parent_locked: &ParentLock) -> Vec<String> {
    let mut warnings = Vec::new();
    for (dir, old) in Hidden::of(report).found() {
        if !abandoned(&dir) {
            continue;
        }
        if old && fs::symlink_metadata(report).is_err() && fs::rename(&dir, report).is_ok() {
            continue;
        }
        warnings.extend(retire(&dir, report));
    }
    warnings
}

/// Links the teacher's entries of the previous report `report` into the
/// new one, `building`, which holds `new` (raystep's files): refused when
/// one of them is where a new file goes, or when a file raystep wrote was
/// changed since.
pub(crate) fn carry(
    survey: &Survey,
    report: &Path,
    building: &Path,
    new: &[PathBuf],
) -> Result<()> {
    refuse_in_the_way(survey, new)?;
    for relative in survey.kept() {
        let from = report.join(relative);
        let to = building.join(relative);
        let placed = make_parents(report, building, relative).and_then(|()| {
            if fs::symlink_metadata(&from)?.is_dir() {
                make_folder_like(&from, &to)
            } else {
                fs::hard_link(&from, &to)
            }
        });
        if let Err(e) = placed {
            bail!(
                "cannot keep {} in the new report ({e}): move it out of the report folder, \
                 or name another folder",
                relative.display()
            );
        }
    }
    Ok(())
}

/// Refuses the teacher's entries where a new file or its folder goes, and
/// raystep's files changed since raystep wrote them.
pub(crate) fn refuse_in_the_way(survey: &Survey, new: &[PathBuf]) -> Result<()> {
    // The new files and every folder they lie in.
    let taken: BTreeSet<&Path> = new.iter().flat_map(|f| f.ancestors()).collect();
    let files: BTreeSet<&Path> = new.iter().map(PathBuf::as_path).collect();
    let clashes = |kept: &Path| taken.contains(kept) || kept.ancestors().any(|a| files.contains(a));
    let mut in_the_way: Vec<String> = survey
        .changed()
        .map(|p| format!("{} (changed since raystep wrote it)", p.display()))
        .collect();
    let changed: Vec<&Path> = survey.changed().collect();
    in_the_way.extend(
        survey
            .kept()
            .filter(|p| !changed.contains(p) && clashes(p))
            .map(|p| format!("{} (not written by raystep)", p.display())),
    );
    if in_the_way.is_empty() {
        return Ok(());
    }
    let count = in_the_way.len();
    let mut named = in_the_way[..count.min(NAMED)].join(", ");
    if count > NAMED {
        named += &format!(" and {} more", count - NAMED);
    }
    bail!(
        "files in the way of the new report, which raystep does not delete: {named}; \
         move them out of the folder, or name another folder"
    )
}

/// Puts `building` in `report`'s place, the previous report retired. Says
/// what of the previous report could not be retired.
pub(crate) fn swap(building: &Path, report: &Path, hidden: &Hidden) -> Result<Vec<String>> {
    if fs::symlink_metadata(report).is_err() {
        fs::rename(building, report)?;
        return Ok(Vec::new());
    }
    let old = match exchange(building, report) {
        // The previous report is now where the new one was built.
        Ok(()) => building.to_owned(),
        Err(e) if cannot_exchange(&e) => {
            let old = hidden.new_folder(OLD_PREFIX)?;
            fs::remove_dir(&old)?;
            fs::rename(report, &old)?;
            if let Err(e) = fs::rename(building, report) {
                let _ = fs::rename(&old, report);
                return Err(e.into());
            }
            old
        }
        Err(e) => return Err(e.into()),
    };
    Ok(retire(&old, report))
}

/// Exchanges two folders in one step.
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let a = CString::new(a.as_os_str().as_bytes())?;
    let b = CString::new(b.as_os_str().as_bytes())?;
    // The system call, not glibc's wrapper (glibc 2.28 and later only).
    let done = unsafe {
        libc::syscall(
            libc::SYS_renameat2,
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if done == 0 {
        Ok(())
    } else {
        Err(io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> io::Result<()> {
    Err(io::ErrorKind::Unsupported.into())
}

/// Whether `exchange` failed for want of support (an old kernel, a file
/// system without it), not for a reason the renames would meet too.
fn cannot_exchange(e: &io::Error) -> bool {
    #[cfg(target_os = "linux")]
    if matches!(e.raw_os_error(), Some(libc::EINVAL | libc::ENOSYS)) {
        return true;
    }
    e.kind() == io::ErrorKind::Unsupported
}

/// Empties and removes `old`, a previous report or a hidden folder a
/// killed run left, beside `report`: raystep's files as written (by the
/// manifest, or the layout where there is none) and entries that are the
/// same file in `report` (the teacher's, linked into it) are removed;
/// anything else is moved into `report` where nothing is in the way. What
/// is left stays, with its manifest, and is said.
pub(crate) fn retire(old: &Path, report: &Path) -> Vec<String> {
    let written = Written::read(old);
    let mut folders = Vec::new();
    let mut left = Vec::new();
    let walked = manifest::walk(old, |relative, kind, _| {
        if kind.is_dir() {
            folders.push(relative.to_owned());
            return;
        }
        // Kept until the rest is gone: it tells raystep's files.
        if relative == Path::new(MANIFEST) {
            return;
        }
        let from = old.join(relative);
        let to = report.join(relative);
        let gone = if same_file(&from, &to) || written.owner(relative, kind) == Owner::Raystep {
            fs::remove_file(&from).is_ok()
        } else {
            fs::symlink_metadata(&to).is_err()
                && make_parents(old, report, relative).is_ok()
                && fs::rename(&from, &to).is_ok()
        };
        if !gone {
            left.push(relative.to_owned());
        }
    });
    // Deepest first: a folder is walked before what it holds.
    for folder in folders.iter().rev() {
        let _ = fs::remove_dir(old.join(folder));
    }
    if walked.is_ok() && left.is_empty() {
        let _ = fs::remove_file(old.join(MANIFEST));
        if fs::remove_dir(old).is_ok() {
            return Vec::new();
        }
    }
    let mut named: Vec<String> = (left.iter().take(NAMED))
        .map(|p| p.display().to_string())
        .collect();
    if left.len() > NAMED {
        named.push(format!("and {} more", left.len() - NAMED));
    }
    let why = match walked {
        Err(e) => format!("it could not be read whole ({e})"),
        Ok(()) if named.is_empty() => "it could not be removed".to_owned(),
        Ok(()) => format!(
            "{} could be neither removed nor moved into {}",
            named.join(", "),
            report.display()
        ),
    };
    vec![format!(
        "a previous report is left in {}: {why}; look at it, and remove it",
        old.display()
    )]
}

/// Makes the folders `relative` lies in under `to`, each with the mode of
/// the one under `from`.
fn make_parents(from: &Path, to: &Path, relative: &Path) -> io::Result<()> {
    let Some(folder) = relative.parent() else {
        return Ok(());
    };
    let mut made = PathBuf::new();
    for part in folder.components() {
        made.push(part);
        let target = to.join(&made);
        if fs::symlink_metadata(&target).is_err() {
            make_folder_like(&from.join(&made), &target)?;
        }
    }
    Ok(())
}

/// Makes the folder `to` with the mode of the folder `from`, where it has one.
fn make_folder_like(from: &Path, to: &Path) -> io::Result<()> {
    fs::create_dir(to)?;
    if let Ok(meta) = fs::symlink_metadata(from)
        && meta.is_dir()
    {
        fs::set_permissions(to, meta.permissions())?;
    }
    Ok(())
}

/// Whether two paths are the same file (a hard link), links not followed.
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(a), Ok(b)) = (fs::symlink_metadata(a), fs::symlink_metadata(b)) {
            return (a.dev(), a.ino()) == (b.dev(), b.ino());
        }
    }
    let _ = (a, b);
    false
}
