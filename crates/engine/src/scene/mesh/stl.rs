//! STL, ASCII or binary, read here (the format is small: `stl_io` named no
//! line for a bad ASCII file, and read a binary file whose 80-byte header
//! starts with `solid` as ASCII). STL triangles carry a facet normal but no
//! vertex normals: every triangle is flat (its normal comes from its
//! vertices' order, as an OBJ face's does; the stored one is not used).
//! Coordinates are 32-bit floats in both forms, read as such.
//!
//! Which form: a file that starts with `solid` is ASCII unless it is binary
//! by the usual test (its length is 84 + 50 × the count in bytes 80..84) or
//! holds a NUL byte (which no text does, and a binary STL's header padding
//! and attribute bytes nearly always do: a truncated one is told so).

use std::ops::Range;
use std::path::Path;

use glam::DVec3;

use super::{Loaded, Triangle, read_file};
use crate::input_file::byte_order_mark;
use crate::scene::limits::COORDINATE;
use crate::scene::{SceneError, utf8_text};

/// A binary STL's header and triangle count, and each triangle's bytes
/// (normal, three vertices, attribute count).
const HEADER: usize = 84;
const TRIANGLE: usize = 50;

pub(super) fn load(path: &Path) -> Result<Loaded, SceneError> {
    let bytes = read_file(path, "mesh file").map_err(SceneError::plain)?;
    parse(path, &bytes)
}

pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Loaded, SceneError> {
    let stem = path
        .file_stem()
        .map_or("mesh".into(), |s| s.to_string_lossy().into_owned());
    let mut loaded = Loaded {
        groups: vec![stem],
        ..Loaded::default()
    };
    let text = &bytes[byte_order_mark(bytes)..];
    let vertices = if is_ascii(text) {
        ascii(path, text)?
    } else {
        binary(bytes).map_err(|e| SceneError::plain(format!("{}: {e}", path.display())))?
    };
    for vertices in vertices {
        loaded.triangles.push(Triangle {
            vertices,
            normals: None,
            group: 0,
            material: None,
        });
    }
    Ok(loaded)
}

/// Whether a file is an ASCII STL (the module's comment says how it is told).
fn is_ascii(bytes: &[u8]) -> bool {
    let solid = bytes.starts_with(b"solid") && bytes.get(5).is_none_or(|b| b.is_ascii_whitespace());
    solid && !binary_length(bytes) && !bytes.contains(&0)
}

/// Whether the file's length is what its triangle count says, as a binary
/// STL's is. No text can pass: four printable bytes count at least
/// 0x20202020 triangles, 27 GB.
fn binary_length(bytes: &[u8]) -> bool {
    count(bytes).is_some_and(|n| bytes.len() as u64 == HEADER as u64 + TRIANGLE as u64 * n)
}

/// The triangle count of a binary STL, bytes 80..84.
fn count(bytes: &[u8]) -> Option<u64> {
    let count: [u8; 4] = bytes.get(80..HEADER)?.try_into().ok()?;
    Some(u32::from_le_bytes(count).into())
}

/// A binary STL's triangles: a file shorter than its count says is
/// truncated (said with both lengths, before any is read); bytes past the
/// last triangle are not read.
fn binary(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, String> {
    let Some(count) = count(bytes) else {
        return Err(format!(
            "a binary STL starts with 84 bytes (header and triangle count); the file has {}",
            bytes.len()
        ));
    };
    let expected = HEADER as u64 + TRIANGLE as u64 * count;
    if (bytes.len() as u64) < expected {
        return Err(format!(
            "truncated binary STL: {count} triangles need {expected} bytes, the file has {}",
            bytes.len()
        ));
    }
    let float = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    let mut triangles = Vec::with_capacity(count as usize);
    for index in 0..count as usize {
        // The normal's 12 bytes first, unused.
        let at = HEADER + TRIANGLE * index + 12;
        let vertex = |v: usize| {
            let at = at + 12 * v;
            DVec3::new(float(at) as f64, float(at + 4) as f64, float(at + 8) as f64)
        };
        let vertices = [vertex(0), vertex(1), vertex(2)];
        for v in &vertices {
            if let Some(c) = v.to_array().into_iter().find(|c| !c.is_finite()) {
                return Err(format!("triangle {index}: numbers must be finite, got {c}"));
            }
            if v.to_array().iter().any(|c| COORDINATE.check(*c).is_err()) {
                return Err(format!(
                    "triangle {index}: vertex {v} is outside the model's bounds ({}..{})",
                    COORDINATE.min, COORDINATE.max
                ));
            }
        }
        triangles.push(vertices);
    }
    Ok(triangles)
}

/// What an ASCII STL's lines say, in order (blank lines aside): `solid
/// NAME`, then for each triangle `facet normal x y z`, `outer loop`, three
/// `vertex x y z`, `endloop`, `endfacet`; then `endsolid NAME`, after
/// which nothing is read.
fn ascii(path: &Path, bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, SceneError> {
    let text = utf8_text(path, bytes, "ASCII STL files")?;
    let error = |span: Range<usize>, message: String| SceneError::at(path, text, span, message);
    let mut lines = Lines::new(text);
    // The `solid` line, as `is_ascii` found it.
    lines.next();
    let mut triangles = Vec::new();
    loop {
        let Some(line) = lines.next() else {
            return Err(error(
                text.len()..text.len(),
                format!(
                    "the file ends after {} triangle(s) without `endsolid`: is it cut short?",
                    triangles.len()
                ),
            ));
        };
        match line.words.first().map(|w| w.1) {
            Some("endsolid") => return Ok(triangles),
            Some("facet") if line.words.get(1).map(|w| w.1) == Some("normal") => {}
            _ => {
                return Err(error(
                    line.span(),
                    expected("`facet normal x y z` or `endsolid`", &line),
                ));
            }
        }
        // The stored normal is not used, but must be three numbers.
        if line.words.len() != 5 {
            return Err(error(line.span(), expected("`facet normal x y z`", &line)));
        }
        for (span, word) in &line.words[2..] {
            word.parse::<f32>()
                .map_err(|_| error(span.clone(), format!("`{word}` is not a number")))?;
        }
        lines
            .expect(&["outer", "loop"])
            .map_err(|(s, m)| error(s, m))?;
        let mut vertices = [DVec3::ZERO; 3];
        for vertex in &mut vertices {
            let line = lines
                .next_or_end()
                .map_err(|(s, m)| error(s, format!("{m}: expected `vertex x y z`")))?;
            if line.words.len() != 4 || line.words[0].1 != "vertex" {
                return Err(error(line.span(), expected("`vertex x y z`", &line)));
            }
            let mut xyz = [0.0; 3];
            for ((span, word), c) in line.words[1..].iter().zip(&mut xyz) {
                let value = word
                    .parse::<f32>()
                    .map_err(|_| error(span.clone(), format!("`{word}` is not a number")))?;
                if !value.is_finite() {
                    return Err(error(
                        span.clone(),
                        format!("numbers must be finite, got {word}"),
                    ));
                }
                *c = value as f64;
                COORDINATE.check(*c).map_err(|why| {
                    error(span.clone(), format!("vertex coordinate {word} {why}"))
                })?;
            }
            *vertex = DVec3::from_array(xyz);
        }
        lines.expect(&["endloop"]).map_err(|(s, m)| error(s, m))?;
        lines.expect(&["endfacet"]).map_err(|(s, m)| error(s, m))?;
        triangles.push(vertices);
    }
}

/// "expected `what`, got `the line`".
fn expected(what: &str, line: &Line) -> String {
    let got: Vec<&str> = line.words.iter().map(|w| w.1).collect();
    format!("expected {what}, got `{}`", got.join(" "))
}

/// One non-blank line: its words and their byte ranges in the file.
struct Line<'a> {
    words: Vec<(Range<usize>, &'a str)>,
}

impl Line<'_> {
    /// From its first word to its last.
    fn span(&self) -> Range<usize> {
        let first = self.words.first().map_or(0, |w| w.0.start);
        first..self.words.last().map_or(first, |w| w.0.end)
    }
}

/// The non-blank lines of a text, in order.
struct Lines<'a> {
    text: &'a str,
    at: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str) -> Self {
        Lines { text, at: 0 }
    }

    fn next(&mut self) -> Option<Line<'a>> {
        while self.at < self.text.len() {
            let start = self.at;
            let end = self.text[start..]
                .find('\n')
                .map_or(self.text.len(), |i| start + i);
            self.at = end + 1;
            let line = &self.text[start..end];
            let words: Vec<_> = line
                .split_whitespace()
                .map(|w| {
                    let from = start + (w.as_ptr() as usize - line.as_ptr() as usize);
                    (from..from + w.len(), w)
                })
                .collect();
            if !words.is_empty() {
                return Some(Line { words });
            }
        }
        None
    }

    /// The next line, or where the file ends.
    fn next_or_end(&mut self) -> Result<Line<'a>, (Range<usize>, String)> {
        let end = self.text.len();
        self.next()
            .ok_or((end..end, "the file ends inside a facet".into()))
    }

    /// The next line, which must be `words`.
    fn expect(&mut self, words: &[&str]) -> Result<(), (Range<usize>, String)> {
        let want = format!("`{}`", words.join(" "));
        let line = self
            .next_or_end()
            .map_err(|(s, m)| (s, format!("{m}: expected {want}")))?;
        if line.words.iter().map(|w| w.1).eq(words.iter().copied()) {
            Ok(())
        } else {
            Err((line.span(), expected(&want, &line)))
        }
    }
}
