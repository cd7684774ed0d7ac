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
pub struct Sections {
    /// The document with each object section blanked out by spaces.
    pub rest: String,
    /// Byte ranges of the `[[object]]` sections, in file order.
    pub objects: Vec<Range<usize>>,
}

/// Cuts `text` into sections, or `None` when the cut could change its meaning.
pub fn split(text: &str) -> Option<Sections> {
    let mut tokens = Source::new(text).lex();
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
                    Header::InsideObject if !objects.is_empty() => return None,
                    Header::Unclear => return None,
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
    objects.extend(open.map(|s| s..text.len()));
    let mut rest = text.as_bytes().to_vec();
    for range in &objects {
        rest[range.clone()].fill(b' ');
    }
    // Whole sections, which start and end on token boundaries, became ASCII.
    let rest = String::from_utf8(rest).expect("blanking whole sections keeps UTF-8");
    Some(Sections { rest, objects })
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
    let mut keys: Vec<&str> = Vec::new();
    let mut previous_end = open.span().end();
    let mut closed = false;
    for token in tokens.by_ref() {
        let raw = &text[token.span().start()..token.span().end()];
        match token.kind() {
            TokenKind::Newline => return (classify(array, &keys), true),
            TokenKind::LeftSquareBracket if keys.is_empty() && !array => {
                array = token.span().start() == previous_end;
            }
            TokenKind::RightSquareBracket => closed = true,
            TokenKind::Atom | TokenKind::BasicString | TokenKind::LiteralString if !closed => {
                keys.push(raw)
            }
            _ => {}
        }
        previous_end = token.span().end();
    }
    (classify(array, &keys), false)
}

fn classify(array: bool, keys: &[&str]) -> Header {
    let Some(first) = keys.first() else {
        return Header::Other;
    };
    if first.starts_with('"') && first.contains('\\') {
        return Header::Unclear;
    }
    let is_object = matches!(*first, "object" | "\"object\"" | "'object'");
    match (is_object, array, keys.len()) {
        (true, true, 1) => Header::ObjectItem,
        (true, _, _) => Header::InsideObject,
        (false, _, _) => Header::Other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cut(text: &str) -> Vec<&str> {
        let sections = split(text).expect("splits");
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
        let rest = split(text).unwrap().rest;
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
        assert!(split("[[object]]\n[x]\n[object.sphere]\n").is_none());
        assert!(split("[[\"obj\\u0065ct\"]]\n").is_none());
    }
}
