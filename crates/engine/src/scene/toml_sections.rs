//! Cuts a TOML scene into its `[[object]]` sections and the rest, so that a
//! scene of a million objects is read one object at a time.
//!
//! The `toml` crate reads a whole document into a tree of tokens, events and
//! spanned values before any of it is deserialized: about 4 KB for each
//! three-line `[[object]]`, 4.6 GB for a million spheres. Read section by
//! section, only one object's tree exists at a time (BENCHMARKS.md, "TOML
//! scenes and memory").
//!
//! A section runs from a line starting with `[[object]]` to the next table
//! header that does not extend it (`[object.sphere]` and `[[object.x]]`
//! belong to the last object). The rest is the file with every section
//! replaced by spaces: same length, so every byte offset and therefore every
//! line and column in it is the file's own. Where that cut would change what
//! the file means (an `[object.…]` header after another table, a key spelt
//! with escapes), `split` gives up and the caller reads the whole file.

use std::ops::Range;

use toml_parser::Source;
use toml_parser::lexer::{Token, TokenKind};

/// A TOML document cut into its object sections and everything else.
pub(crate) struct Sections {
    /// The document with each object section blanked out by spaces.
    pub(crate) rest: String,
    /// Byte ranges of the `[[object]]` sections, in file order.
    pub(crate) objects: Vec<Range<usize>>,
}

/// The TOML reader refuses dotted keys of this many parts (its recursion
/// limit) without saying where they are; `split` finds them.
pub(crate) const MAX_KEY_PARTS: usize = 81;

/// Cuts `text` into sections, or `Ok(None)` when the cut could change its
/// meaning. `Err` is the span of a dotted key of `MAX_KEY_PARTS` or more parts.
pub(crate) fn split(text: &str) -> Result<Option<Sections>, Range<usize>> {
    let mut keys = KeyParts::default();
    let mut tokens = Source::new(text).lex().inspect(|t| keys.see(t));
    let mut cut = true;
    let mut objects: Vec<Range<usize>> = Vec::new();
    // The start of the object section being read, if one is.
    let mut open: Option<usize> = None;
    // Brackets and braces open in a value: a `[` opens a header only outside
    // any value and first on its line.
    let mut depth = 0usize;
    let mut line_start = true;
    while let Some(token) = tokens.next() {
        match token.kind() {
            TokenKind::Whitespace | TokenKind::Comment => {}
            TokenKind::Newline => line_start = true,
            TokenKind::LeftSquareBracket if line_start && depth == 0 => {
                let start = token.span().start();
                let (header, newline) = read_header(text, token, &mut tokens);
                line_start = newline;
                match header {
                    Header::ObjectItem => {
                        objects.extend(open.replace(start).map(|s| s..start));
                    }
                    Header::InsideObject if open.is_some() => {}
                    // A sub-table of an object after other tables, or
                    // anything spelt so that we cannot tell.
                    Header::InsideObject if !objects.is_empty() => cut = false,
                    Header::Unclear => cut = false,
                    Header::InsideObject | Header::Other => {
                        objects.extend(open.take().map(|s| s..start));
                    }
                }
            }
            TokenKind::LeftSquareBracket | TokenKind::LeftCurlyBracket => {
                depth += 1;
                line_start = false;
            }
            TokenKind::RightSquareBracket | TokenKind::RightCurlyBracket => {
                depth = depth.saturating_sub(1);
                line_start = false;
            }
            _ => line_start = false,
        }
    }
    drop(tokens);
    if let Some(span) = keys.too_many {
        return Err(span);
    }
    if !cut {
        return Ok(None);
    }
    objects.extend(open.map(|s| s..text.len()));
    let mut rest = text.as_bytes().to_vec();
    for range in &objects {
        rest[range.clone()].fill(b' ');
    }
    // Whole sections, which start and end on token boundaries, became ASCII.
    let rest = String::from_utf8(rest).expect("blanking whole sections keeps UTF-8");
    Ok(Some(Sections { rest, objects }))
}

/// Counts the parts of each dotted key as its tokens go by. Floats and dates
/// lex as at most a few dotted parts too; only keys can be long and valid.
#[derive(Default)]
struct KeyParts {
    parts: usize,
    after_dot: bool,
    start: usize,
    too_many: Option<Range<usize>>,
}

impl KeyParts {
    fn see(&mut self, token: &Token) {
        match token.kind() {
            TokenKind::Whitespace => {}
            TokenKind::Dot => self.after_dot = self.parts > 0,
            TokenKind::Atom | TokenKind::BasicString | TokenKind::LiteralString => {
                if !self.after_dot {
                    self.parts = 0;
                    self.start = token.span().start();
                }
                self.parts += 1;
                self.after_dot = false;
                if self.parts == MAX_KEY_PARTS && self.too_many.is_none() {
                    self.too_many = Some(self.start..token.span().end());
                }
            }
            _ => {
                self.parts = 0;
                self.after_dot = false;
            }
        }
    }
}

/// What a table header names, as far as splitting is concerned.
enum Header {
    /// `[[object]]`: a new object.
    ObjectItem,
    /// `[object.sphere]`, `[[object.x]]`, `[object]`: part of the last object
    /// (or an error the whole file's reader will report).
    InsideObject,
    /// Any other table.
    Other,
    /// A first key with escapes, which may or may not spell `object`.
    Unclear,
}

/// Reads the header that `open` starts, up to the end of its line; also says
/// whether that line's newline was read.
fn read_header(
    text: &str,
    open: Token,
    tokens: &mut impl Iterator<Item = Token>,
) -> (Header, bool) {
    let mut array = false;
    // The first key and how many there are (a header line may be megabytes).
    let mut first: Option<&str> = None;
    let mut keys = 0usize;
    let mut previous_end = open.span().end();
    let mut closed = false;
    for token in tokens.by_ref() {
        let raw = &text[token.span().start()..token.span().end()];
        match token.kind() {
            TokenKind::Newline => return (classify(array, first, keys), true),
            TokenKind::LeftSquareBracket if keys == 0 && !array => {
                array = token.span().start() == previous_end;
            }
            TokenKind::RightSquareBracket => closed = true,
            TokenKind::Atom | TokenKind::BasicString | TokenKind::LiteralString if !closed => {
                first.get_or_insert(raw);
                keys += 1;
            }
            _ => {}
        }
        previous_end = token.span().end();
    }
    (classify(array, first, keys), false)
}

fn classify(array: bool, first: Option<&str>, keys: usize) -> Header {
    let Some(first) = first else {
        return Header::Other;
    };
    if first.starts_with('"') && first.contains('\\') {
        return Header::Unclear;
    }
    let is_object = matches!(first, "object" | "\"object\"" | "'object'");
    match (is_object, array, keys) {
        (true, true, 1) => Header::ObjectItem,
        (true, _, _) => Header::InsideObject,
        (false, _, _) => Header::Other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cut(text: &str) -> Vec<&str> {
        let sections = split(text).unwrap().expect("splits");
        assert_eq!(sections.rest.len(), text.len());
        sections.objects.iter().map(|r| &text[r.clone()]).collect()
    }

    #[test]
    fn objects_and_their_sub_tables_are_cut_out() {
        let text = "[camera]\nfov = 1\n[[object]]\nmaterial = \"m\"\n[object.sphere]\nradius = 1\n\
                    [[ 'object' ]]\na = 1\n[[light]]\nposition = [0, 0, 0]\n[[object]]\nb = 2\n";
        assert_eq!(
            cut(text),
            [
                "[[object]]\nmaterial = \"m\"\n[object.sphere]\nradius = 1\n",
                "[[ 'object' ]]\na = 1\n",
                "[[object]]\nb = 2\n"
            ]
        );
        let rest = split(text).unwrap().unwrap().rest;
        assert!(rest.starts_with("[camera]\nfov = 1\n   "));
        assert!(rest.contains(" [[light]]\nposition = [0, 0, 0]\n  "));
        assert!(!rest.contains("object"));
    }

    #[test]
    fn brackets_inside_values_and_strings_are_not_headers() {
        // The `[[object]]` lines here are inside an array and a string.
        let text = "[[object]]\nv = [\n[[object]]\n]\ns = \"\"\"\n[[object]]\n\"\"\"\n[x]\n";
        assert_eq!(
            cut(text),
            ["[[object]]\nv = [\n[[object]]\n]\ns = \"\"\"\n[[object]]\n\"\"\"\n"]
        );
    }

    #[test]
    fn sub_tables_of_an_object_after_other_tables_are_not_cut() {
        // Valid TOML: `[object.sphere]` extends the object before `[x]`.
        assert!(
            split("[[object]]\n[x]\n[object.sphere]\n")
                .unwrap()
                .is_none()
        );
        assert!(split("[[\"obj\\u0065ct\"]]\n").unwrap().is_none());
    }

    #[test]
    fn dotted_keys_of_81_parts_are_found() {
        // "a" and 80 ".a": 81 parts, the first at byte 4 of "[x]\n", the
        // 81st ending at 4 + 81 + 80 = 165. 80 parts (which the TOML reader
        // takes), or floats, pass.
        let key = |parts: usize| vec!["a"; parts].join(".");
        assert_eq!(
            split(&format!("[x]\n{} = 1\n", key(81))).err(),
            Some(4..165)
        );
        assert_eq!(split(&format!("[{}]\n", key(100))).err(), Some(1..162));
        assert!(split(&format!("{} = [1.5, 2.5]\n", key(80))).is_ok());
    }
}
