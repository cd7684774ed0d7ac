//! Our pass over an OBJ's lines, before tobj reads it: tobj's errors carry
//! no line, so every error a file can have at a line is found here, with
//! its line and column: a number that is not one, NaN or infinity, a
//! coordinate past the model's bounds, a `v` of other than 3, 4 or 6
//! numbers, a weight `w` of 0 or one that moves the vertex out of bounds,
//! vertex colours on some vertices only, a `vn` of no direction, a `\` line
//! continuation, a face index out of range or zero, a face of fewer than 3
//! vertices. It also learns what tobj does not say (`Lines`).

use std::collections::HashSet;
use std::ops::Range;
use std::path::Path;

use crate::scene::SceneError;
use crate::scene::limits::COORDINATE;
use raystep_model::math::exceeds;

/// What the pass over the lines learns besides the errors.
pub(super) struct Lines {
    /// The names `usemtl` lines use, each once, so that one naming no
    /// material is said.
    pub(super) used_materials: Vec<String>,
    /// For each triangle of each face's fan, in file order: whether every
    /// corner of its face has a `vn`.
    pub(super) smooth: Vec<bool>,
    /// Whether the file has `l` lines (polylines).
    pub(super) polylines: bool,
    /// Whether a `v`, `vt`, `vn` or `f` line has a comment after its numbers.
    pub(super) comments_after_numbers: bool,
    /// How many `v` and `f` lines it has.
    pub(super) vertices: usize,
    pub(super) faces: usize,
    /// Where its first word is, when it is `solid` (an ASCII STL's first).
    pub(super) solid: Option<Range<usize>>,
}

/// The pass over the lines: counts `v`, `vt` and `vn` as they come and
/// checks every number and every face index against them.
pub(super) fn check_lines(path: &Path, text: &str) -> Result<Lines, SceneError> {
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
pub(super) fn no_faces(path: &Path, text: &str, lines: &Lines) -> SceneError {
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
