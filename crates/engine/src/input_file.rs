//! Input files, opened without trusting the path: every file raystep reads
//! (scene, mesh, MTL, student image, ray log, assignment) comes through
//! here, so that none can hang it or exhaust its memory.
//!
//! - Only a regular file (or a symbolic link to one) is read. A FIFO, a
//!   socket, a character or block device (`/dev/zero`) or a directory is
//!   refused from its metadata, before it is opened: opening a FIFO for
//!   reading waits for a writer, and a device may never end.
//! - The file is then opened without blocking (should a FIFO have been put
//!   in its place since) and checked again, open, so what is read is what
//!   was checked.
//! - Its length is checked against the reader's size cap (docs/SCENES.md, "Bad
//!   input") before a byte is read, and no more than the cap is read should
//!   it grow meanwhile.
//!
//! Where there is no file system (the web page), the files a user gave are
//! served from memory instead (`with_files`), under the same caps.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::fs::{self, File, Metadata};
use std::io::{self, Read};
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

/// The most bytes a reader takes, and what the file is, for the message
/// ("a scene file").
#[derive(Clone, Copy, Debug)]
pub struct Cap {
    pub bytes: u64,
    pub of: &'static str,
}

/// Why an input was not read, a sentence naming the file.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct InputError(String);

/// Opens `path` for reading: a regular file no longer than `cap`. `what`
/// names it in messages before its path ("the ray log"), or is empty.
pub fn open(path: &Path, what: &str, cap: Cap) -> Result<File, InputError> {
    let fail = |why: String| refused(what, path, why);
    let meta = fs::metadata(path).map_err(|e| fail(e.to_string()))?;
    regular(&meta).map_err(fail)?;
    let file = open_regular(path, true).map_err(|e| fail(e.to_string()))?;
    let meta = file.metadata().map_err(|e| fail(e.to_string()))?;
    if meta.len() > cap.bytes {
        return Err(fail(too_large(meta.len(), cap)));
    }
    Ok(file)
}

/// Whether `path` is a file `open` would read, judged from its metadata
/// alone (nothing is opened): `Ok(false)` when there is nothing there,
/// `Err` naming what it is when it is a FIFO, a device or a directory.
pub fn is_regular(path: &Path, what: &str) -> Result<bool, InputError> {
    match fs::metadata(path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(false),
        Err(e) => Err(refused(what, path, e.to_string())),
        Ok(meta) => regular(&meta)
            .map(|()| true)
            .map_err(|why| refused(what, path, why)),
    }
}

/// Files given by a user where there is no file system to read (the web
/// page): their paths, as a scene names them, and their bytes.
pub type GivenFiles = BTreeMap<PathBuf, Arc<[u8]>>;

thread_local! {
    static GIVEN: RefCell<Option<GivenFiles>> = const { RefCell::new(None) };
}

/// Runs `work` with `read` taking files from `files` alone, never from the
/// file system, on this thread (scenes and meshes are read on the thread
/// that loads them).
pub fn with_files<T>(files: &GivenFiles, work: impl FnOnce() -> T) -> T {
    struct Restore(Option<GivenFiles>);
    impl Drop for Restore {
        fn drop(&mut self) {
            GIVEN.with(|given| *given.borrow_mut() = self.0.take());
        }
    }
    let before = GIVEN.with(|given| given.borrow_mut().replace(files.clone()));
    let _restore = Restore(before);
    work()
}

/// A path as its name among given files: `.` dropped and `..` taken back.
pub fn given_name(path: &Path) -> PathBuf {
    let mut name = PathBuf::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir => {
                if !name.pop() {
                    name.push("..");
                }
            }
            other => name.push(other),
        }
    }
    name
}

/// `path` among the given files, when files are given on this thread.
fn read_given(path: &Path, what: &str, cap: Cap) -> Option<Result<Vec<u8>, InputError>> {
    GIVEN.with(|given| {
        let given = given.borrow();
        let files = given.as_ref()?;
        let fail = |why: String| refused(what, path, why);
        Some(match files.get(&given_name(path)) {
            None => Err(fail(
                "no such file among those given (open it together with the scene)".into(),
            )),
            Some(bytes) if bytes.len() as u64 > cap.bytes => {
                Err(fail(too_large(bytes.len() as u64, cap)))
            }
            Some(bytes) => Ok(bytes.to_vec()),
        })
    })
}

/// Reads `path` whole, as `open` opens it (or from the given files, see
/// `with_files`).
pub fn read(path: &Path, what: &str, cap: Cap) -> Result<Vec<u8>, InputError> {
    if let Some(given) = read_given(path, what, cap) {
        return given;
    }
    let file = open(path, what, cap)?;
    let length = file.metadata().map_or(0, |m| m.len());
    let mut bytes = Vec::with_capacity(length as usize);
    let read = file.take(cap.bytes + 1).read_to_end(&mut bytes);
    let fail = |why: String| refused(what, path, why);
    read.map_err(|e| fail(e.to_string()))?;
    // It grew while it was read.
    if bytes.len() as u64 > cap.bytes {
        return Err(fail(too_large(bytes.len() as u64, cap)));
    }
    Ok(bytes)
}

/// UTF-8's byte-order mark (U+FEFF), which Notepad and PowerShell 5 put
/// before a text file's first line. It is no part of the text: TOML's
/// reader skips it, and every text reader of ours (NFF, OBJ, MTL, ASCII STL,
/// ray log) skips it with `byte_order_mark`.
pub const BYTE_ORDER_MARK: &[u8] = "\u{feff}".as_bytes();

/// How many bytes of a byte-order mark `text` starts with: 3 or 0. Skip
/// them, not strip them, where positions in the file are counted.
pub fn byte_order_mark(text: &[u8]) -> usize {
    if text.starts_with(BYTE_ORDER_MARK) {
        BYTE_ORDER_MARK.len()
    } else {
        0
    }
}

/// "cannot read the ray log LOG: why".
fn refused(what: &str, path: &Path, why: String) -> InputError {
    let space = if what.is_empty() { "" } else { " " };
    InputError(format!(
        "cannot read {what}{space}{}: {why}",
        path.display()
    ))
}

/// Opens `path` for reading only if it is a regular file, without waiting
/// (a FIFO put in its place after a check would otherwise wait for a
/// writer), and checks it again once open. With `follow` false a symbolic
/// link is refused (a path already made canonical).
pub fn open_regular(path: &Path, follow: bool) -> io::Result<File> {
    let mut options = fs::OpenOptions::new();
    options.read(true);
    #[cfg(not(unix))]
    let _ = follow;
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        let nofollow = if follow { 0 } else { libc::O_NOFOLLOW };
        options.custom_flags(libc::O_NONBLOCK | nofollow);
    }
    let file = options.open(path)?;
    regular(&file.metadata()?).map_err(io::Error::other)?;
    Ok(file)
}

/// Refuses anything but a regular file, saying what it is.
fn regular(meta: &Metadata) -> Result<(), String> {
    if meta.is_file() {
        return Ok(());
    }
    let kind = if meta.is_dir() {
        "a directory"
    } else {
        special_kind(meta)
    };
    Err(format!("it is {kind}, not a regular file"))
}

#[cfg(unix)]
fn special_kind(meta: &Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let kind = meta.file_type();
    if kind.is_fifo() {
        "a FIFO (a named pipe)"
    } else if kind.is_socket() {
        "a socket"
    } else if kind.is_char_device() {
        "a character device"
    } else if kind.is_block_device() {
        "a block device"
    } else {
        "a special file"
    }
}

#[cfg(not(unix))]
fn special_kind(_: &Metadata) -> &'static str {
    "a special file"
}

fn too_large(length: u64, cap: Cap) -> String {
    format!(
        "it is {length} bytes, more than the {} {} may be",
        size(cap.bytes),
        cap.of
    )
}

/// A cap in words: `256 MiB (268435456 bytes)`, `1 GiB (...)`, `10 bytes`.
fn size(bytes: u64) -> String {
    const MIB: u64 = 1 << 20;
    const GIB: u64 = 1 << 30;
    match bytes {
        b if b >= GIB && b % GIB == 0 => format!("{} GiB ({bytes} bytes)", b / GIB),
        b if b >= MIB && b % MIB == 0 => format!("{} MiB ({bytes} bytes)", b / MIB),
        _ => format!("{bytes} bytes"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SMALL: Cap = Cap {
        bytes: 10,
        of: "a test file",
    };

    #[test]
    fn given_files_are_read_from_memory_and_never_from_disk() {
        let dir = tempfile::tempdir().unwrap();
        let on_disk = dir.path().join("ten");
        fs::write(&on_disk, b"0123456789").unwrap();
        let files: GivenFiles = [
            (PathBuf::from("meshes/box.obj"), Arc::from(&b"v 0 0 0"[..])),
            (PathBuf::from("big"), Arc::from(&b"0123456789A"[..])),
        ]
        .into();
        with_files(&files, || {
            // Named as a scene in scenes/ names it from its own folder.
            let read_as = |p: &str| read(Path::new(p), "the mesh", SMALL);
            assert_eq!(read_as("./x/../meshes/box.obj").unwrap(), b"v 0 0 0");
            let missing = read(&on_disk, "", SMALL).unwrap_err().to_string();
            assert!(
                missing.contains("no such file among those given"),
                "{missing}"
            );
            // 11 bytes against a cap of 10, as from disk.
            let big = read_as("big").unwrap_err().to_string();
            assert!(
                big.contains("it is 11 bytes, more than the 10 bytes"),
                "{big}"
            );
        });
        // Outside, the file system again.
        assert_eq!(read(&on_disk, "", SMALL).unwrap(), b"0123456789");
    }

    #[test]
    fn a_byte_order_mark_is_its_three_bytes_at_the_start_only() {
        // U+FEFF in UTF-8: EF BB BF.
        assert_eq!(byte_order_mark(b"\xEF\xBB\xBFv 0 0 0"), 3);
        assert_eq!(byte_order_mark(b"v 0 0 0\xEF\xBB\xBF"), 0);
        assert_eq!(byte_order_mark(b"\xEF\xBB"), 0);
    }

    #[test]
    fn a_regular_file_within_its_cap_is_read_whole() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ten");
        fs::write(&path, b"0123456789").unwrap();
        assert_eq!(read(&path, "", SMALL).unwrap(), b"0123456789");
    }

    #[test]
    fn a_file_past_its_cap_is_refused_with_its_length_and_the_cap() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("eleven");
        fs::write(&path, b"0123456789A").unwrap();
        let message = read(&path, "the test file", SMALL).unwrap_err().to_string();
        assert_eq!(
            message,
            format!(
                "cannot read the test file {}: it is 11 bytes, more than the 10 bytes a test file may be",
                path.display()
            )
        );
    }

    #[test]
    fn caps_are_said_in_mebibytes_or_gibibytes() {
        assert_eq!(size(256 << 20), "256 MiB (268435456 bytes)");
        assert_eq!(size(1 << 30), "1 GiB (1073741824 bytes)");
        // 8 bytes a pixel of 8192 x 8192, and 1 MiB: 512 + 1 MiB.
        assert_eq!(size((8 << 26) + (1 << 20)), "513 MiB (537919488 bytes)");
        assert_eq!(size(10), "10 bytes");
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_and_a_device_are_refused_without_being_opened() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo");
        let name = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
        assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
        // Opened for a blocking read, the FIFO would wait here for ever.
        let message = read(&fifo, "", SMALL).unwrap_err().to_string();
        assert!(
            message.ends_with("it is a FIFO (a named pipe), not a regular file"),
            "{message}"
        );
        let message = read(Path::new("/dev/zero"), "", SMALL)
            .unwrap_err()
            .to_string();
        assert_eq!(
            message,
            "cannot read /dev/zero: it is a character device, not a regular file"
        );
        // Open without waiting, the FIFO is refused once open too.
        let error = open_regular(&fifo, true).unwrap_err();
        assert_eq!(
            error.to_string(),
            "it is a FIFO (a named pipe), not a regular file"
        );
    }
}
