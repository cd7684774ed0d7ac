//! Errors in scene files, located by file, line and column and shown with the
//! offending text, the way a compiler shows them.
//!
//! What an error prints is bounded whatever the file holds: the quoted line
//! is cut to an excerpt around the column and the message to a few hundred
//! characters (a value quoted by the TOML reader may be megabytes long), so a
//! bad 100 MB line gives a few lines of output, not 100 MB of it.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The most characters of the offending line quoted, ellipses aside.
pub(crate) const MAX_EXCERPT_CHARS: usize = 120;
/// How many of them come before the column, when the line is cut.
const EXCERPT_CONTEXT_BEFORE: usize = 40;
/// The most characters of a message kept, ellipsis aside.
pub(crate) const MAX_MESSAGE_CHARS: usize = 400;
/// Marks where a quoted line or a message was cut.
const ELLIPSIS: char = '…';

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceLocation {
    pub(crate) path: PathBuf,
    /// 1-based line and column (in characters) in the file.
    pub line: usize,
    pub column: usize,
    /// The offending line, or at most `MAX_EXCERPT_CHARS` of it around the
    /// column with `…` where it was cut.
    pub(crate) excerpt: String,
    /// 1-based column of the error within `excerpt`, and how many
    /// characters to underline there.
    pub(crate) excerpt_column: usize,
    pub(crate) width: usize,
}

#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub struct SceneError {
    pub message: String,
    pub location: Option<SourceLocation>,
}

impl SceneError {
    /// An error that belongs to no place in a file (an unreadable file, a bad size).
    pub fn plain(message: impl Into<String>) -> Self {
        Self {
            message: bounded(message.into(), MAX_MESSAGE_CHARS),
            location: None,
        }
    }

    /// An error at a byte range of `text`, the contents of `path`. The range
    /// is moved back to character boundaries if it falls inside one.
    pub fn at(path: &Path, text: &str, span: Range<usize>, message: impl Into<String>) -> Self {
        let start = floor_boundary(text, span.start);
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        let line_end = if text[..line_end].ends_with('\r') && line_end > start {
            line_end - 1
        } else {
            line_end
        };
        let line = text[..start].matches('\n').count() + 1;
        let column = text[line_start..start].chars().count() + 1;
        let end = floor_boundary(text, span.end.clamp(start, line_end));
        let (excerpt, excerpt_column, width) = excerpt(
            &text[line_start..line_end],
            start - line_start,
            end - line_start,
        );
        Self {
            message: bounded(message.into(), MAX_MESSAGE_CHARS),
            location: Some(SourceLocation {
                path: path.to_path_buf(),
                line,
                column,
                excerpt,
                excerpt_column,
                width,
            }),
        }
    }
}

/// At most `MAX_EXCERPT_CHARS` of `line` around the byte range `start..end`
/// (on character boundaries), the 1-based column of `start` in it and the
/// number of characters of the range it shows (at least 1, for the caret).
fn excerpt(line: &str, start: usize, end: usize) -> (String, usize, usize) {
    // Walk back from the column by at most the context, then forward by at
    // most the whole excerpt: only those characters are ever visited.
    let first = line[..start]
        .char_indices()
        .rev()
        .nth(EXCERPT_CONTEXT_BEFORE - 1)
        .map_or(0, |(i, _)| i);
    let first = if line[first..].chars().nth(MAX_EXCERPT_CHARS).is_none() {
        // The tail from `first` fits: start earlier to fill the excerpt.
        line.char_indices()
            .rev()
            .nth(MAX_EXCERPT_CHARS - 1)
            .map_or(0, |(i, _)| i)
            .min(first)
    } else {
        first
    };
    let last = line[first..]
        .char_indices()
        .nth(MAX_EXCERPT_CHARS)
        .map_or(line.len(), |(i, _)| first + i);
    let mut shown = String::new();
    if first > 0 {
        shown.push(ELLIPSIS);
    }
    shown.push_str(&line[first..last]);
    if last < line.len() {
        shown.push(ELLIPSIS);
    }
    let column = usize::from(first > 0) + line[first..start].chars().count() + 1;
    let width = line[start..end.clamp(start, last)].chars().count().max(1);
    (shown, column, width)
}

/// `text` cut to at most `max` characters, with `…` where it was cut. The cut
/// is near the end, so that what follows a long quoted value ("…, expected
/// f64") is kept.
pub(super) fn bounded(text: String, max: usize) -> String {
    let tail = max / 4;
    let Some((head_end, _)) = text.char_indices().nth(max - tail) else {
        return text;
    };
    let Some((tail_start, _)) = text.char_indices().nth_back(tail - 1) else {
        return text;
    };
    if tail_start <= head_end {
        return text;
    }
    let mut cut = String::with_capacity(max + ELLIPSIS.len_utf8() * 4);
    cut.push_str(&text[..head_end]);
    cut.push(ELLIPSIS);
    cut.push_str(&text[tail_start..]);
    cut
}

/// The largest character boundary of `text` at or before `index`.
fn floor_boundary(text: &str, index: usize) -> usize {
    let mut index = index.min(text.len());
    while !text.is_char_boundary(index) {
        index -= 1;
    }
    index
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Some(at) = &self.location else {
            return write!(f, "{}", self.message);
        };
        writeln!(
            f,
            "{}:{}:{}: {}",
            at.path.display(),
            at.line,
            at.column,
            self.message
        )?;
        let gutter = at.line.to_string().len();
        writeln!(f, "{:gutter$} |", "")?;
        writeln!(f, "{} | {}", at.line, at.excerpt)?;
        write!(
            f,
            "{:gutter$} | {}{}",
            "",
            " ".repeat(at.excerpt_column - 1),
            "^".repeat(at.width)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn location_counts_lines_and_characters() {
        let text = "a = 1\nfov = abc\n";
        // "abc" starts at byte 12: line 2, column 7.
        let error = SceneError::at(Path::new("s.toml"), text, 12..15, "bad number");
        let at = error.location.as_ref().unwrap();
        assert_eq!((at.line, at.column, at.width), (2, 7, 3));
        assert_eq!(
            error.to_string(),
            "s.toml:2:7: bad number\n  |\n2 | fov = abc\n  |       ^^^"
        );
    }

    #[test]
    fn a_long_line_is_quoted_as_an_excerpt_around_the_column() {
        // Line 2 is "x = " then 3 million 'é' (2 bytes each), "BAD", more 'é'.
        let before = "é".repeat(3_000_000);
        let text = format!("a = 1\nx = {before}BAD{}\n", "é".repeat(1_000_000));
        let start = text.find("BAD").unwrap();
        let error = SceneError::at(Path::new("s.toml"), &text, start..start + 3, "bad");
        let at = error.location.as_ref().unwrap();
        // Column: "x = " (4) + 3,000,000 'é' before it, plus one.
        assert_eq!((at.line, at.column, at.width), (2, 3_000_005, 3));
        // 40 characters before the column, 'BAD' and 77 after, each side cut.
        let expected = format!("…{}BAD{}…", "é".repeat(40), "é".repeat(77));
        assert_eq!(at.excerpt, expected);
        assert_eq!(at.excerpt_column, 42);
        let shown = error.to_string();
        assert!(shown.len() < 600, "{} bytes", shown.len());
        assert!(shown.starts_with("s.toml:2:3000005: bad\n"));
        // The caret line puts the three carets under "BAD".
        let caret_line = shown.lines().last().unwrap();
        assert_eq!(caret_line, format!("  | {}^^^", " ".repeat(41)));
    }

    #[test]
    fn an_excerpt_near_a_line_end_is_filled_from_before() {
        // 200 'a' then "!" at column 201: the last 120 characters are shown.
        let text = format!("{}!", "a".repeat(200));
        let error = SceneError::at(Path::new("s"), &text, 200..201, "bang");
        let at = error.location.as_ref().unwrap();
        assert_eq!(at.excerpt, format!("…{}!", "a".repeat(119)));
        // '…' then 119 'a': the '!' is the 121st character.
        assert_eq!((at.column, at.excerpt_column, at.width), (201, 121, 1));
    }

    #[test]
    fn long_messages_are_cut_and_spans_inside_a_character_do_not_panic() {
        let long = format!("value `{}` is wrong", "m".repeat(10_000));
        let error = SceneError::at(Path::new("s"), "ab\u{e9}c", 3..4, long);
        let at = error.location.as_ref().unwrap();
        // Byte 3 is inside 'é' (bytes 2..4): the error moves back to it, column 3.
        assert_eq!((at.column, at.width), (3, 1));
        // The first 300 characters ("value `" and 293 'm'), '…', the last 100
        // (90 'm' and "` is wrong").
        let expected = format!("value `{}…{}` is wrong", "m".repeat(293), "m".repeat(90));
        assert_eq!(error.message, expected);
        assert_eq!(error.message.chars().count(), MAX_MESSAGE_CHARS + 1);
        let plain = SceneError::plain("p".repeat(10_000));
        assert_eq!(plain.message.chars().count(), MAX_MESSAGE_CHARS + 1);
    }
}
