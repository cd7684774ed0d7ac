//! Wavefront OBJ with `tobj`, after a pass of our own over the lines: tobj's
//! errors carry no line, so every error a file can have at a line (a number
//! that is not one, NaN or infinity, a coordinate past the model's bounds, a
//! face index out of range or zero, a face of fewer than 3 vertices) is found
//! here first, with its line and column.

use std::collections::{HashMap, HashSet};
use std::ops::Range;
use std::path::{Path, PathBuf};

use glam::DVec3;

use super::mtl;
use super::{Loaded, Triangle, read_file};
use crate::scene::SceneError;
use crate::scene::limits::COORDINATE;

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
            Ok(bytes) => tobj::load_mtl_buf(&mut bytes.as_slice()).inspect_err(|e| {
                missing
                    .borrow_mut()
                    .push(format!("{}: {e}", full.display()));
            }),
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
    let lines = check_lines(path, text)?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    // tobj reads an `l` line of three or more points as a face, whatever
    // `ignore_lines` says: a polyline is no surface, so it never sees one.
    let without_polylines;
    let text = if lines.polylines {
        without_polylines = blank_polylines(text);
        without_polylines.as_str()
    } else {
        text
    };
    let (models, mtl) = tobj::load_obj_buf(&mut text.as_bytes(), &options, materials)
        .map_err(|e| SceneError::plain(format!("{}: {e}", path.display())))?;
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
    let mut start = 0;
    for line in text.split_inclusive('\n') {
        let line_start = start;
        start += line.len();
        let content = line.split('#').next().unwrap_or("");
        let mut words = words(content).map(|(r, w)| (r.start + line_start..r.end + line_start, w));
        let Some((keyword_span, keyword)) = words.next() else {
            continue;
        };
        let error = |span: Range<usize>, message: String| SceneError::at(path, text, span, message);
        match keyword {
            "v" | "vn" | "vt" => {
                let needed = if keyword == "vt" { 1 } else { 3 };
                let mut numbers = 0;
                for (span, word) in words.by_ref().take(3) {
                    let value: f64 = word
                        .parse()
                        .map_err(|_| error(span.clone(), format!("`{word}` is not a number")))?;
                    if !value.is_finite() {
                        return Err(error(span, format!("numbers must be finite, got {word}")));
                    }
                    if keyword == "v" && COORDINATE.check(value).is_err() {
                        return Err(error(
                            span,
                            format!(
                                "vertex coordinate {word} {}",
                                COORDINATE.check(value).unwrap_err()
                            ),
                        ));
                    }
                    numbers += 1;
                }
                if numbers < needed {
                    return Err(error(
                        keyword_span,
                        format!("`{keyword}` needs {needed} numbers, got {numbers}"),
                    ));
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
    })
}

/// `text` with each `l` line emptied (its line break kept).
fn blank_polylines(text: &str) -> String {
    text.split_inclusive('\n')
        .map(|line| {
            if line.split_whitespace().next() == Some("l") {
                "\n"
            } else {
                line
            }
        })
        .collect()
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
fn words(line: &str) -> impl Iterator<Item = (Range<usize>, &str)> {
    line.split_whitespace().map(move |w| {
        let start = w.as_ptr() as usize - line.as_ptr() as usize;
        (start..start + w.len(), w)
    })
}
