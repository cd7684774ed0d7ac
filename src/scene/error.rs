//! Errors in scene files, located by file, line and column and shown with the
//! offending text, the way a compiler shows them.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceLocation {
    pub path: PathBuf,
    /// 1-based line and column (in characters).
    pub line: usize,
    pub column: usize,
    /// The whole offending line, and how many characters to underline.
    pub line_text: String,
    pub width: usize,
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
            message: message.into(),
            location: None,
        }
    }

    /// An error at a byte range of `text`, the contents of `path`.
    pub fn at(path: &Path, text: &str, span: Range<usize>, message: impl Into<String>) -> Self {
        let start = span.start.min(text.len());
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        let line_text = text[line_start..line_end]
            .trim_end_matches('\r')
            .to_string();
        let line = text[..start].matches('\n').count() + 1;
        let column = text[line_start..start].chars().count() + 1;
        let end = span.end.clamp(start, line_end);
        let width = text[start..end].chars().count().max(1);
        Self {
            message: message.into(),
            location: Some(SourceLocation {
                path: path.to_path_buf(),
                line,
                column,
                line_text,
                width,
            }),
        }
    }
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
        writeln!(f, "{} | {}", at.line, at.line_text)?;
        write!(
            f,
            "{:gutter$} | {}{}",
            "",
            " ".repeat(at.column - 1),
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
}
