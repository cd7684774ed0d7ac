//! Wavefront OBJ with `tobj`, after a pass of our own over the lines
//! (`obj_lines.rs`), which finds every error a file can have at a line with
//! its line and column (tobj's errors carry none). Should tobj still refuse
//! a line, the line it stopped at is named.
//!
//! A byte-order mark is skipped, and a comment after a `v`, `vt`, `vn` or
//! `f` line's numbers (`f 1 2 3 # tri`) is read as a comment, as Blender's
//! and most OBJ readers read it (tobj refused the face).

use std::borrow::Cow;
use std::collections::{HashMap, HashSet};
use std::io::Cursor;
use std::ops::Range;
use std::path::{Path, PathBuf};

use glam::DVec3;

use super::mtl;
use super::obj_lines::{Lines, check_lines, no_faces};
use super::{Loaded, Triangle, read_file};
use crate::input_file::byte_order_mark;
use crate::printable::printable;
use crate::scene::{SceneError, utf8_text};

/// Reads `path` and the MTL files its `mtllib` lines name (beside it),
/// each file once however many lines name it (10,000 `mtllib` lines of one
/// MTL added its materials 10,000 times: a gigabyte from 150 KB).
pub(super) fn load(path: &Path) -> Result<Loaded, SceneError> {
    let bytes = read_file(path, "mesh file").map_err(SceneError::plain)?;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let missing = std::cell::RefCell::new(Vec::new());
    let libraries = std::cell::RefCell::new(Vec::new());
    // Each file by its canonical path (by the path as named when it
    // cannot be had: a missing file), so that `./m.mtl` or `d/../m.mtl`
    // is the same file as `m.mtl`.
    let seen = std::cell::RefCell::new(HashSet::new());
    let loader = |mtl: &Path| -> tobj::MTLLoadResult {
        let full: PathBuf = dir.join(mtl);
        let file = std::fs::canonicalize(&full).unwrap_or_else(|_| full.clone());
        if !seen.borrow_mut().insert(file) {
            // Read already: its materials are in, or its warning said.
            return Ok((Vec::new(), HashMap::new()));
        }
        libraries.borrow_mut().push(full.clone());
        // Read only as MTL: whatever the path names, its bytes go to the
        // MTL parser and nowhere else, and nothing is written.
        match read_file(&full, "MTL file") {
            Ok(bytes) => {
                let text = &bytes[byte_order_mark(&bytes)..];
                let mut reader = Cursor::new(text);
                tobj::load_mtl_buf(&mut reader).inspect_err(|e| {
                    let line = stopped_at(text, reader.position());
                    let number = text[..line.start].iter().filter(|&&b| b == b'\n').count() + 1;
                    let shown = String::from_utf8_lossy(&text[line]);
                    missing.borrow_mut().push(format!(
                        "{}:{number}: {e} in `{}`",
                        full.display(),
                        cut(&printable(shown.trim_end()), 80)
                    ));
                })
            }
            Err(message) => {
                missing.borrow_mut().push(message);
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    };
    let mut loaded = parse(path, &bytes, &loader)?;
    loaded.libraries = libraries.into_inner();
    let missing = missing.into_inner();
    if !missing.is_empty() {
        // The missing file says it already: every `usemtl` falls back.
        loaded.warnings.retain(|w| !w.contains("`usemtl "));
    }
    for m in missing {
        loaded.warnings.push(format!(
            "{}: {m}: the default material is used",
            path.display()
        ));
    }
    Ok(loaded)
}

/// Parses OBJ bytes; `materials` reads an `mtllib`.
pub(super) fn parse(
    path: &Path,
    bytes: &[u8],
    materials: &dyn Fn(&Path) -> tobj::MTLLoadResult,
) -> Result<Loaded, SceneError> {
    let text = utf8_text(path, bytes, "OBJ files")?;
    let text = &text[byte_order_mark(text.as_bytes())..];
    let lines = check_lines(path, text)?;
    if lines.faces == 0 {
        return Err(no_faces(path, text, &lines));
    }
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let for_tobj = for_tobj(text, &lines);
    let mut reader = Cursor::new(for_tobj.as_bytes());
    let (models, mtl) = tobj::load_obj_buf(&mut reader, &options, materials).map_err(|e| {
        // Its lines are the file's, one for one: where it stopped is the
        // file's line.
        let line = stopped_at(for_tobj.as_bytes(), reader.position());
        SceneError::at(path, text, line, format!("{e} (tobj refused this line)"))
    })?;
    let mut loaded = Loaded::default();
    if let Ok(list) = mtl {
        loaded.materials = list.iter().map(mtl::Read::from_tobj).collect();
    }
    let defined: HashSet<&str> = loaded.materials.iter().map(|m| m.name.as_str()).collect();
    for name in lines.used_materials {
        if !defined.contains(name.as_str()) {
            loaded.warnings.push(format!(
                "{}: `usemtl {name}` names no material of the file's MTL: the default material is used",
                path.display()
            ));
        }
    }
    let stem = path
        .file_stem()
        .map_or("mesh".into(), |s| s.to_string_lossy().into_owned());
    // tobj gives every face in file order, a face of n corners as the n - 2
    // triangles of its fan; when the count agrees, each triangle knows
    // whether its own face gave every corner a `vn`.
    let total: usize = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
    let smooth = (total == lines.smooth.len()).then_some(lines.smooth.as_slice());
    let mut triangle_in_file = 0;
    for model in &models {
        let mesh = &model.mesh;
        let group = loaded.groups.len();
        loaded
            .groups
            .push(if model.name.is_empty() || model.name == "unnamed_object" {
                stem.clone()
            } else {
                model.name.clone()
            });
        let material = mesh.material_id.filter(|&m| m < loaded.materials.len());
        let point = |i: u32| {
            let i = i as usize * 3;
            DVec3::new(
                mesh.positions[i],
                mesh.positions[i + 1],
                mesh.positions[i + 2],
            )
        };
        let normal = |i: u32| {
            let i = i as usize * 3;
            DVec3::new(mesh.normals[i], mesh.normals[i + 1], mesh.normals[i + 2])
        };
        let has_normals = mesh.normal_indices.len() == mesh.indices.len();
        for (k, corner) in mesh.indices.chunks_exact(3).enumerate() {
            // tobj makes up a normal for a corner without one (the first
            // or the last seen): such a face stays flat.
            let own_normals = smooth.is_none_or(|s| s[triangle_in_file]);
            triangle_in_file += 1;
            let normals = (has_normals && own_normals).then(|| {
                let n = &mesh.normal_indices[k * 3..k * 3 + 3];
                [normal(n[0]), normal(n[1]), normal(n[2])]
            });
            loaded.triangles.push(Triangle {
                vertices: [point(corner[0]), point(corner[1]), point(corner[2])],
                normals,
                group,
                material,
            });
        }
    }
    Ok(loaded)
}

/// The text tobj reads, line for line the file's: each `l` line emptied
/// (tobj reads an `l` line of three or more points as a face, whatever
/// `ignore_lines` says, and a polyline is no surface), and a comment after
/// numbers cut off (tobj read `f 1 2 3 # tri` as a face with a vertex `#`).
fn for_tobj<'a>(text: &'a str, lines: &Lines) -> Cow<'a, str> {
    if !lines.polylines && !lines.comments_after_numbers {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let ending = if line.ends_with('\n') { "\n" } else { "" };
        match line.split_whitespace().next() {
            Some("l") => out.push_str(ending),
            Some("v" | "vt" | "vn" | "f") if line.contains('#') => {
                out.push_str(line.split('#').next().unwrap_or(""));
                out.push_str(ending);
            }
            _ => out.push_str(line),
        }
    }
    Cow::Owned(out)
}

/// The byte range of the line a line-by-line reader was reading when it
/// stopped at `position` (just past that line's end).
fn stopped_at(text: &[u8], position: u64) -> Range<usize> {
    let end = usize::try_from(position).map_or(text.len(), |p| p.min(text.len()));
    let last = end.saturating_sub(1);
    let start = text[..last]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    start..end
}

/// At most `chars` characters of `text`, then "…".
fn cut(text: &str, chars: usize) -> Cow<'_, str> {
    match text.char_indices().nth(chars) {
        Some((end, _)) => Cow::Owned(format!("{}…", &text[..end])),
        None => Cow::Borrowed(text),
    }
}
