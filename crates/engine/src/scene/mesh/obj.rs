//! Wavefront OBJ with `tobj`, after a pass of our own over the lines: tobj's
//! errors carry no line, so every error a file can have at a line (a number
//! that is not one, NaN or infinity, a coordinate past the model's bounds, a
//! `v` of other than 3, 4 or 6 numbers, a weight `w` that is 0 or moves the
//! vertex out of bounds, vertex colours on some vertices only, a `vn` of no
//! direction, a `\` line continuation, a face index out of range or zero, a
//! face of fewer than 3 vertices) is found here first, with its line and
//! column. Should tobj still refuse a line, the line it stopped at is named.
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
use super::{Loaded, Triangle, read_file};
use crate::input_file::byte_order_mark;
use crate::printable::printable;
use crate::scene::SceneError;
use crate::scene::limits::COORDINATE;
use raystep_model::math::exceeds;

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
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        SceneError::plain(format!(
            "{}:{line}: invalid UTF-8: OBJ files must be text",
            path.display()
        ))
    })?;
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

/// What the pass over the lines learns besides the errors.
struct Lines {
    /// The names `usemtl` lines use, each once, so that one naming no
    /// material is said.
    used_materials: Vec<String>,
    /// For each triangle of each face's fan, in file order: whether every
    /// corner of its face has a `vn`.
    smooth: Vec<bool>,
    /// Whether the file has `l` lines (polylines).
    polylines: bool,
    /// Whether a `v`, `vt`, `vn` or `f` line has a comment after its numbers.
    comments_after_numbers: bool,
    /// How many `v` and `f` lines it has.
    vertices: usize,
    faces: usize,
    /// Where its first word is, when it is `solid` (an ASCII STL's first).
    solid: Option<Range<usize>>,
}

/// The pass over the lines: counts `v`, `vt` and `vn` as they come and
/// checks every number and every face index against them.
fn check_lines(path: &Path, text: &str) -> Result<Lines, SceneError> {
    let mut counts = [0usize; 3]; // v, vt, vn
    let mut used_materials: Vec<String> = Vec::new();
    // The names in `used_materials`, to tell a new one at once (each new
    // name was checked against all before it: 100,000 names took 14 s).
    let mut used: HashSet<&str> = HashSet::new();
    let mut smooth = Vec::new();
    let mut polylines = false;
    let mut comments_after_numbers = false;
    let mut faces = 0;
    let mut solid = None;
    // Whether the first `v` has a colour, and its line.
    let mut first_colour: Option<(bool, usize)> = None;
    let mut start = 0;
    for (number, line) in text.split_inclusive('\n').enumerate() {
        let line_start = start;
        start += line.len();
        let content = line.split('#').next().unwrap_or("");
        let mut words = words(content).map(|(r, w)| (r.start + line_start..r.end + line_start, w));
        let Some((keyword_span, keyword)) = words.next() else {
            continue;
        };
        let error = |span: Range<usize>, message: String| SceneError::at(path, text, span, message);
        if number == 0 && keyword == "solid" {
            solid = Some(keyword_span.clone());
        }
        if matches!(keyword, "v" | "vt" | "vn" | "f") {
            comments_after_numbers |= content.len() < line.len();
            if let Some((span, last)) = words.clone().last()
                && last.ends_with('\\')
            {
                return Err(error(
                    span.end - 1..span.end,
                    "a `\\` line continuation is not read: write the whole statement on one line"
                        .into(),
                ));
            }
        }
        match keyword {
            "v" | "vn" | "vt" => {
                let needed = if keyword == "vt" { 1 } else { 3 };
                let mut numbers = [0.0; 3];
                let mut read = 0;
                for (span, word) in words.by_ref().take(3) {
                    let value = finite(word).map_err(|m| error(span.clone(), m))?;
                    if keyword == "v" && COORDINATE.check(value).is_err() {
                        return Err(error(
                            span,
                            format!(
                                "vertex coordinate {word} {}",
                                COORDINATE.check(value).unwrap_err()
                            ),
                        ));
                    }
                    numbers[read] = value;
                    read += 1;
                }
                if read < needed {
                    return Err(error(
                        keyword_span,
                        format!("`{keyword}` needs {needed} numbers, got {read}"),
                    ));
                }
                let whole = keyword_span.start..line_start + content.trim_end().len();
                match keyword {
                    "v" => {
                        let colour = vertex_tail(numbers, words).map_err(|(s, m)| error(s, m))?;
                        match first_colour {
                            None => first_colour = Some((colour, number + 1)),
                            Some((first, at)) if first != colour => {
                                let (this, that) = if colour {
                                    ("has one", "has none")
                                } else {
                                    ("has none", "has one")
                                };
                                return Err(error(
                                    whole,
                                    format!(
                                        "vertex colours on some vertices only: this `v` {this}, \
                                         the first `v` (line {at}) {that}: give every `v` a \
                                         colour (r g b after x y z) or none"
                                    ),
                                ));
                            }
                            Some(_) => {}
                        }
                    }
                    "vn" => check_normal(numbers).map_err(|m| error(whole, m))?,
                    _ => {}
                }
                let slot = match keyword {
                    "v" => 0,
                    "vt" => 1,
                    _ => 2,
                };
                counts[slot] += 1;
            }
            "f" => {
                let mut corners = 0;
                let mut with_normal = 0;
                for (span, word) in words {
                    corners += 1;
                    for (slot, part) in word.split('/').enumerate().take(3) {
                        if part.is_empty() && slot > 0 {
                            continue;
                        }
                        with_normal += usize::from(slot == 2);
                        check_index(part, slot, counts[slot])
                            .map_err(|m| error(span.clone(), m))?;
                    }
                }
                if corners < 3 {
                    return Err(error(
                        keyword_span,
                        format!("a face needs at least 3 vertices, got {corners}"),
                    ));
                }
                let all_normals = with_normal == corners;
                smooth.extend(std::iter::repeat_n(all_normals, corners - 2));
                faces += 1;
            }
            "l" => polylines = true,
            "usemtl" => {
                // tobj takes the rest of the line as the name.
                let name = content[keyword_span.end - line_start..].trim();
                if !name.is_empty() && used.insert(name) {
                    used_materials.push(name.to_string());
                }
            }
            _ => {}
        }
    }
    Ok(Lines {
        used_materials,
        smooth,
        polylines,
        comments_after_numbers,
        vertices: counts[0],
        faces,
        solid,
    })
}

/// A number of a `v`, `vt` or `vn` line: finite.
fn finite(word: &str) -> Result<f64, String> {
    let value: f64 = word
        .parse()
        .map_err(|_| format!("`{word}` is not a number"))?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("numbers must be finite, got {word}"))
    }
}

/// What may follow a `v` line's x y z: nothing, a weight w (tobj divides
/// x, y and z by it), or a colour r g b (which raystep does not use).
/// Whether it is a colour; else where the line is wrong, and why.
fn vertex_tail<'a>(
    xyz: [f64; 3],
    tail: impl Iterator<Item = (Range<usize>, &'a str)>,
) -> Result<bool, (Range<usize>, String)> {
    let mut first = None;
    let mut end = 0;
    let mut count = 0;
    let mut w = 0.0;
    for (span, word) in tail {
        count += 1;
        end = span.end;
        if count <= 3 {
            let value = finite(word).map_err(|m| (span.clone(), m))?;
            if count == 1 {
                w = value;
            }
        }
        first.get_or_insert(span);
    }
    let Some(first) = first else {
        return Ok(false);
    };
    match count {
        1 => {
            if w == 0.0 {
                return Err((
                    first,
                    "vertex weight w is 0: x/w, y/w and z/w are at infinity".into(),
                ));
            }
            // As tobj places it.
            if let Some(c) = xyz
                .map(|c| c / w)
                .into_iter()
                .find(|c| COORDINATE.check(*c).is_err())
            {
                return Err((
                    first,
                    format!(
                        "vertex weight w = {w:e} puts the vertex out of bounds: \
                         x/w, y/w and z/w {} (one is {c:e})",
                        COORDINATE.check(c).unwrap_err()
                    ),
                ));
            }
            Ok(false)
        }
        3 => Ok(true),
        _ => Err((
            first.start..end,
            format!(
                "`v` takes x y z, then a weight w or a colour r g b: this one has {} numbers",
                3 + count
            ),
        )),
    }
}

/// A `vn` must give a direction: its length (as a patch takes it) neither 0
/// nor past the largest number.
fn check_normal(n: [f64; 3]) -> Result<(), String> {
    let length = glam::DVec3::from_array(n).length();
    if !exceeds(length, 0.0) {
        return Err("this normal has no direction: its length is 0".into());
    }
    if !length.is_finite() {
        return Err("this normal is too long: its length overflows (give it length 1)".into());
    }
    Ok(())
}

/// Why a file with no `f` line gives nothing to draw.
fn no_faces(path: &Path, text: &str, lines: &Lines) -> SceneError {
    if let Some(span) = &lines.solid {
        return SceneError::at(
            path,
            text,
            span.clone(),
            "this is an ASCII STL (it starts with `solid`), not an OBJ: name it .stl",
        );
    }
    let polylines = if lines.polylines {
        " (its `l` lines are polylines, not surfaces)"
    } else {
        ""
    };
    SceneError::plain(format!(
        "{}: the mesh has no triangles to show: it has {} `v` line(s) and no `f` line{polylines}",
        path.display(),
        lines.vertices
    ))
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

/// One index of a face corner: 1..=count, or -count..=-1 counting back.
fn check_index(part: &str, slot: usize, count: usize) -> Result<(), String> {
    let what = ["vertex", "texture coordinate", "normal"][slot];
    let list = ["v", "vt", "vn"][slot];
    let index: i64 = part
        .parse()
        .map_err(|_| format!("face {what} index `{part}` is not a whole number"))?;
    if index == 0 {
        return Err(format!("face {what} index 0: OBJ indices start at 1"));
    }
    if index.unsigned_abs() > count as u64 {
        return Err(format!(
            "face {what} index {index} is out of range: {count} `{list}` line(s) come before this face"
        ));
    }
    Ok(())
}

/// The whitespace-separated words of a line and their byte ranges: split
/// as tobj splits them (Unicode whitespace, so U+000B too), so that both
/// read the same keyword.
fn words(line: &str) -> impl Iterator<Item = (Range<usize>, &str)> + Clone {
    line.split_whitespace().map(move |w| {
        let start = w.as_ptr() as usize - line.as_ptr() as usize;
        (start..start + w.len(), w)
    })
}
