//! One student's file for one scene, read without trusting the folder it
//! is in: what is not a PNG of the assignment's size is refused with the
//! reason, never followed out of the folder, never opened when it is not a
//! regular file (a FIFO would block the whole class).

use std::fs;
use std::io::{BufReader, Seek};
use std::path::Path;

use crate::compare::StudentImage;
use crate::compare::{png_chunks, student};
use raystep_engine::input_file;

/// A file larger than this many bytes per pixel (plus `SLACK_BYTES`) is
/// refused before its pixels are read: an uncompressed PNG of 16-bit RGBA
/// takes 8.
const MAX_BYTES_PER_PIXEL: u64 = 8;
const SLACK_BYTES: u64 = 1 << 20;

/// Reads `name` in `folder`, which is the student's `root` folder or one
/// inside it (both canonical); it must be a PNG of `width` x `height`. `Err`
/// says why it was refused.
pub(crate) fn read(
    root: &Path,
    folder: &Path,
    name: &str,
    (width, height): (u32, u32),
) -> Result<StudentImage, String> {
    let path = folder.join(name);
    match fs::symlink_metadata(&path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(format!("missing: the folder holds no {name}"));
        }
        Err(e) => return Err(format!("cannot read {name}: {e}")),
        Ok(_) => {}
    }
    let real = fs::canonicalize(&path).map_err(|e| match fs::read_link(&path) {
        Ok(to) => format!(
            "{name} is a symbolic link to {}, which cannot be read ({e})",
            to.display()
        ),
        Err(_) => format!("cannot read {name}: {e}"),
    })?;
    if !real.starts_with(root) || real == root || real == folder {
        return Err(format!(
            "{name} is a symbolic link that leads out of the student's folder: refused \
             (a submission must be a file in its folder)"
        ));
    }
    let meta = fs::metadata(&real).map_err(|e| format!("cannot read {name}: {e}"))?;
    if meta.is_dir() {
        return Err(format!("{name} is a folder, not a PNG file"));
    }
    if !meta.is_file() {
        return Err(format!(
            "{name} is a device, pipe or socket, not a PNG file"
        ));
    }
    let file =
        input_file::open_regular(&real, false).map_err(|e| format!("cannot read {name}: {e}"))?;
    let length = file
        .metadata()
        .map_err(|e| format!("cannot read {name}: {e}"))?
        .len();
    let mut reader = BufReader::new(file);
    // The size in the header first: a wrong size is told as such, before
    // the pixels are decoded. The header chunk alone is read, not the
    // image crate's decoder's, which inflates an ICC profile whole before
    // it says the size: compare's reader checks every chunk first.
    let header =
        png_chunks::header_size(&mut reader).map_err(|e| format!("cannot read {name}: {e}"))?;
    if let Some((w, h)) = header
        && (w, h) != (width, height)
    {
        return Err(format!(
            "rendered at {w}x{h}, the assignment asks for {width}x{height}"
        ));
    }
    // Then the file's length, before the pixels are decoded: what could
    // follow a right header is bounded by what such a PNG can take.
    let limit = MAX_BYTES_PER_PIXEL * u64::from(width) * u64::from(height) + SLACK_BYTES;
    if length > limit {
        return Err(format!(
            "{name} is too large: {length} bytes, more than a PNG of {width}x{height} takes \
             (at most {limit})"
        ));
    }
    reader
        .rewind()
        .map_err(|e| format!("cannot read {name}: {e}"))?;
    // compare's reader says what is wrong with anything else.
    student::read(reader, name).map_err(|e| format!("{e:#}"))
}
