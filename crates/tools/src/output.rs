//! Output files: where each one lands and how it is written, so that a
//! render never destroys anything it was not asked to replace.
//!
//! - Every output is resolved and checked before the render starts: an
//!   existing output must be a regular file (a symbolic link is followed, and
//!   the file it points to is replaced); directories, devices, pipes and
//!   sockets are refused, and so is an output that is any input of the
//!   command (the scene file, a mesh or MTL file it reads, the student's
//!   image, a ray log, the assignment) or another output of the same
//!   command, however its path is spelt (`Inputs`, `refuse_clashes`).
//! - All files of one command go to temporary files beside their targets and
//!   are renamed into place only when all are complete; on failure the
//!   temporaries are removed and every target is left as it was.
//! - A new file gets the mode any new file gets (0666 less the umask); a
//!   replaced file keeps its mode.
//! - A temporary (`.raystep-*.png.tmp`) is locked while its run lives; one
//!   that a killed run left behind is unlocked, and the next run writing
//!   into that folder removes it.

use std::collections::BTreeSet;
use std::fs::{self, File, Permissions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use image::RgbImage;
use tempfile::NamedTempFile;

use raystep_engine::scene::Scene;

const TEMP_PREFIX: &str = ".raystep-";
const TEMP_SUFFIX: &str = ".png.tmp";

/// One output file, resolved: `real` is where it lands, links followed.
#[derive(Debug)]
pub struct Target {
    /// The path as the user gave it, for messages.
    pub(crate) shown: PathBuf,
    real: PathBuf,
    /// The mode of the file being replaced, kept for the new one.
    mode: Option<Permissions>,
}

/// Resolves an output file whose folder must exist.
pub fn file(path: &Path) -> Result<Target> {
    resolve(path, || {
        let fail = |why: &str| anyhow!("cannot write {}: {why}", path.display());
        let name = path.file_name().ok_or_else(|| fail("not a file name"))?;
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        let folder = fs::canonicalize(parent)
            .map_err(|e| fail(&format!("no folder {} ({e})", parent.display())))?;
        drop(
            temp_in(&folder)
                .map_err(|e| fail(&format!("{} is not writable ({e})", folder.display())))?,
        );
        Ok(folder.join(name))
    })
}

/// Resolves `path`, which lands at `landing()` unless it already exists.
fn resolve(path: &Path, landing: impl FnOnce() -> Result<PathBuf>) -> Result<Target> {
    let fail = || format!("cannot write {}", path.display());
    let link = match fs::symlink_metadata(path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            return Ok(Target {
                shown: path.to_owned(),
                real: landing()?,
                mode: None,
            });
        }
        Err(e) => return Err(e).with_context(fail),
        Ok(meta) => meta.file_type().is_symlink(),
    };
    let meta = fs::metadata(path).map_err(|e| match fs::read_link(path) {
        Ok(to) if e.kind() == io::ErrorKind::NotFound => anyhow!(
            "cannot write {}: it is a symbolic link to {}, which does not exist",
            path.display(),
            to.display()
        ),
        _ => anyhow::Error::new(e).context(fail()),
    })?;
    let what = if link { "it leads to" } else { "it is" };
    if meta.is_dir() {
        bail!("cannot write {}: {what} a directory", path.display());
    }
    if !meta.is_file() {
        bail!(
            "cannot write {}: {what} a device, pipe or socket, not a regular file; \
             raystep only replaces regular files",
            path.display()
        );
    }
    Ok(Target {
        shown: path.to_owned(),
        real: fs::canonicalize(path).with_context(fail)?,
        mode: Some(meta.permissions()),
    })
}

/// A folder for several outputs, created when the files are written if it
/// does not exist yet.
#[derive(Debug)]
pub struct Folder {
    shown: PathBuf,
    real: PathBuf,
    exists: bool,
}

/// Resolves and checks a folder: it exists and is a directory, or its
/// nearest existing ancestor is one; either way it is writable.
pub fn folder(dir: &Path) -> Result<Folder> {
    let fail = |why: &str| anyhow!("cannot write into {}: {why}", dir.display());
    let mut existing = dir;
    let mut missing = Vec::new();
    while !existing.as_os_str().is_empty() && fs::symlink_metadata(existing).is_err() {
        // `new/..` cannot be resolved before `new` exists.
        let name = existing.file_name();
        missing.push(name.ok_or_else(|| fail("it goes through `..` below a missing folder"))?);
        existing = existing.parent().unwrap_or(Path::new(""));
    }
    if existing.as_os_str().is_empty() {
        existing = Path::new(".");
    }
    if !fs::metadata(existing).is_ok_and(|m| m.is_dir()) {
        return Err(fail(&format!("{} is not a folder", existing.display())));
    }
    let mut real = fs::canonicalize(existing).map_err(|e| fail(&e.to_string()))?;
    drop(temp_in(&real).map_err(|e| fail(&format!("{} is not writable ({e})", real.display())))?);
    real.extend(missing.iter().rev());
    Ok(Folder {
        shown: dir.to_owned(),
        real,
        exists: missing.is_empty(),
    })
}

impl Folder {
    /// The output `name` inside this folder.
    pub fn file(&self, name: &str) -> Result<Target> {
        resolve(&self.shown.join(name), || Ok(self.real.join(name)))
    }
}

/// Every file a command reads, each with what it is for messages: no
/// output of the command may be one of them, however either path is spelt.
#[derive(Debug, Default)]
pub struct Inputs {
    files: Vec<(PathBuf, String)>,
    /// Files read through a descriptor (standard input): their identity.
    opened: Vec<(FileId, String)>,
}

impl Inputs {
    /// `path`, named `what` ("your image").
    pub fn with(mut self, path: &Path, what: &str) -> Inputs {
        self.files.push((path.to_owned(), what.to_owned()));
        self
    }

    /// Standard input, named `what`, when it is a regular file
    /// (`--rays - < rays.jsonl`): no output may be that file, by any name.
    pub fn with_stdin(mut self, what: &str) -> Inputs {
        if let Some(id) = stdin_file() {
            self.opened.push((id, what.to_owned()));
        }
        self
    }

    /// A scene's file and every file it read: its meshes and MTL files.
    pub fn with_scene(mut self, scene: &Scene) -> Inputs {
        for (i, path) in scene.files.iter().enumerate() {
            let what = if i == 0 {
                "the scene file"
            } else {
                "a file the scene reads,"
            };
            self = self.with(path, what);
        }
        self
    }

    /// Each input, with what it is.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (&Path, &str)> {
        self.files.iter().map(|(p, w)| (p.as_path(), w.as_str()))
    }
}

/// A file's device and inode: the file, whatever its names.
type FileId = (u64, u64);

fn file_id(path: &Path) -> Option<FileId> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        fs::metadata(path).ok().map(|m| (m.dev(), m.ino()))
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        None
    }
}

/// The regular file standard input reads, if it is one.
fn stdin_file() -> Option<FileId> {
    #[cfg(unix)]
    {
        use std::os::fd::AsFd;
        use std::os::unix::fs::MetadataExt;
        // A second descriptor of it, closed when dropped.
        let fd = io::stdin().as_fd().try_clone_to_owned().ok()?;
        let meta = File::from(fd).metadata().ok()?;
        meta.is_file().then(|| (meta.dev(), meta.ino()))
    }
    #[cfg(not(unix))]
    {
        None
    }
}

/// Refuses an output that is one of the command's inputs or another of its
/// outputs. Each target comes with what it is, for the message.
pub fn refuse_clashes(inputs: &Inputs, targets: &[(&Target, String)]) -> Result<()> {
    for (i, (target, what)) in targets.iter().enumerate() {
        if let Some((input, input_what)) = inputs.iter().find(|(input, _)| lands_at(input, target))
        {
            bail!(
                "cannot write {}: it is {input_what} {}",
                target.shown.display(),
                input.display()
            );
        }
        let id = file_id(&target.real);
        if let Some((_, input_what)) = inputs.opened.iter().find(|(i, _)| Some(*i) == id) {
            bail!(
                "cannot write {}: it is {input_what}, read from standard input",
                target.shown.display()
            );
        }
        let same = |(other, _): &&(&Target, String)| {
            other.real == target.real || same_file(&other.real, &target.real)
        };
        if let Some((_, other_what)) = targets[..i].iter().find(same) {
            bail!(
                "cannot write {}: it would be both {other_what} and {what}",
                target.shown.display()
            );
        }
    }
    Ok(())
}

/// Whether `input` is where `target` lands: the same file (a link, a hard
/// link) or, for an input that does not exist (an MTL the scene names that
/// is missing), the same place, which the output would create.
fn lands_at(input: &Path, target: &Target) -> bool {
    if same_file(input, &target.real) {
        return true;
    }
    let real = fs::canonicalize(input).ok().or_else(|| {
        let name = input.file_name()?;
        let parent = match input.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        Some(fs::canonicalize(parent).ok()?.join(name))
    });
    real.as_ref() == Some(&target.real)
}

/// Whether two existing paths are the same file (hard links included).
fn same_file(a: &Path, b: &Path) -> bool {
    matches!((file_id(a), file_id(b)), (Some(a), Some(b)) if a == b)
}

/// Writes every image to a temporary beside its target, then renames them
/// all into place. `create` is a folder to create first when missing.
pub fn write_all<'a>(
    create: Option<&Folder>,
    files: impl IntoIterator<Item = (&'a Target, RgbImage)>,
) -> Result<()> {
    let created = match create {
        Some(folder) if !folder.exists => Some(create_folder(folder)?),
        _ => None,
    };
    let written = write_temps(files);
    let placed = written.and_then(|temps| {
        for (temp, target) in temps {
            temp.persist(&target.real)
                .map_err(|e| e.error)
                .with_context(|| format!("cannot write {}", target.shown.display()))?;
        }
        Ok(())
    });
    if placed.is_err()
        && let Some(dirs) = created
    {
        // Only the folders this run made, deepest first, and only if empty.
        for dir in dirs.iter().rev() {
            let _ = fs::remove_dir(dir);
        }
    }
    placed
}

/// Writes `text` to `target` as `write_all` writes images: to a temporary
/// beside it first, then renamed into place.
pub fn write_text(target: &Target, text: &str) -> Result<()> {
    let fail = || format!("cannot write {}", target.shown.display());
    let dir = target.real.parent().unwrap_or(Path::new("/"));
    remove_stale_temps(dir);
    let temp = temp_in(dir).with_context(fail)?;
    let mut out = BufWriter::new(temp.as_file());
    out.write_all(text.as_bytes()).with_context(fail)?;
    out.flush().with_context(fail)?;
    drop(out);
    if let Some(mode) = &target.mode {
        temp.as_file()
            .set_permissions(mode.clone())
            .with_context(fail)?;
    }
    temp.persist(&target.real)
        .map_err(|e| e.error)
        .with_context(fail)?;
    Ok(())
}

fn write_temps<'a>(
    files: impl IntoIterator<Item = (&'a Target, RgbImage)>,
) -> Result<Vec<(NamedTempFile, &'a Target)>> {
    let mut cleaned = BTreeSet::new();
    let mut temps = Vec::new();
    for (target, image) in files {
        let fail = || format!("cannot write {}", target.shown.display());
        let dir = target.real.parent().unwrap_or(Path::new("/"));
        if cleaned.insert(dir.to_owned()) {
            remove_stale_temps(dir);
        }
        let temp = temp_in(dir).with_context(fail)?;
        encode(temp.as_file(), &image).with_context(fail)?;
        if let Some(mode) = &target.mode {
            temp.as_file()
                .set_permissions(mode.clone())
                .with_context(fail)?;
        }
        temps.push((temp, target));
    }
    Ok(temps)
}

fn encode(file: &File, image: &RgbImage) -> Result<()> {
    let mut out = BufWriter::new(file);
    write_png(image, &mut out)?;
    out.flush()?;
    Ok(())
}

/// The one PNG encoding of an image raystep writes, to a file or to the web
/// page's download: the same image gives the same bytes everywhere.
pub fn write_png(image: &RgbImage, out: &mut impl Write) -> image::ImageResult<()> {
    image.write_with_encoder(image::codecs::png::PngEncoder::new(out))
}

/// Creates the folder, returning the directories made, outermost first.
fn create_folder(folder: &Folder) -> Result<Vec<PathBuf>> {
    let made: Vec<PathBuf> = folder
        .real
        .ancestors()
        .take_while(|d| !d.exists())
        .map(Path::to_owned)
        .collect();
    fs::create_dir_all(&folder.real)
        .with_context(|| format!("cannot create {}", folder.shown.display()))?;
    Ok(made.into_iter().rev().collect())
}

/// A locked temporary file in `dir` with the mode a new file gets.
fn temp_in(dir: &Path) -> io::Result<NamedTempFile> {
    loop {
        let mut builder = tempfile::Builder::new();
        builder.prefix(TEMP_PREFIX).suffix(TEMP_SUFFIX);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            // The umask is applied on creation, as for any new file.
            builder.permissions(Permissions::from_mode(0o666));
        }
        let temp = builder.tempfile_in(dir)?;
        temp.as_file().lock()?;
        // Another run may have removed it between its creation and the lock.
        if still_there(&temp)? {
            return Ok(temp);
        }
    }
}

#[cfg(unix)]
fn still_there(temp: &NamedTempFile) -> io::Result<bool> {
    use std::os::unix::fs::MetadataExt;
    let open = temp.as_file().metadata()?;
    Ok(fs::symlink_metadata(temp.path())
        .is_ok_and(|named| (named.dev(), named.ino()) == (open.dev(), open.ino())))
}

#[cfg(not(unix))]
fn still_there(temp: &NamedTempFile) -> io::Result<bool> {
    Ok(temp.path().exists())
}

/// Removes our temporaries that no living run holds locked: leftovers of a
/// run that was killed while writing.
fn remove_stale_temps(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let name = name.to_string_lossy();
        let ours = name.starts_with(TEMP_PREFIX) && name.ends_with(TEMP_SUFFIX);
        if !ours || !entry.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        if let Ok(file) = File::open(entry.path())
            && file.try_lock().is_ok()
        {
            let _ = fs::remove_file(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image() -> RgbImage {
        RgbImage::new(2, 1)
    }

    #[test]
    fn a_failure_part_way_places_nothing_and_leaves_no_temporary() {
        let top = tempfile::tempdir().unwrap();
        let kept = top.path().join("kept.png");
        fs::write(&kept, b"old").unwrap();
        let gone = top.path().join("gone");
        fs::create_dir(&gone).unwrap();
        let new = folder(&top.path().join("new/sub")).unwrap();
        let targets = [
            file(&kept).unwrap(),
            new.file("a.png").unwrap(),
            file(&gone.join("b.png")).unwrap(),
        ];
        // The third file's folder vanishes after the checks: its temporary
        // cannot be made, after the first two were written.
        fs::remove_dir(&gone).unwrap();
        let result = write_all(Some(&new), targets.iter().map(|t| (t, image())));
        let message = format!("{:#}", result.unwrap_err());
        assert!(message.contains("gone/b.png"), "{message}");
        assert_eq!(fs::read(&kept).unwrap(), b"old");
        // Only what was there before: no temporary, no new folder.
        let names: Vec<_> = fs::read_dir(top.path())
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names, ["kept.png"]);
    }
}
