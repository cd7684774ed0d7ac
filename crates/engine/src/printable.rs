//! Names are data: a scene may name an object, a material or a light with
//! any character TOML can spell (`"\u001b"` is legal), but a control
//! character written raw moves a terminal's cursor, changes its colours or
//! rings its bell, and XML and Graphviz cannot carry one at all. Every
//! output meant to be read (text on a terminal, SVG, dot) spells each such
//! character as Rust does, `\u{1b}`, so that two names differing only
//! there still look different; JSON keeps the exact name (serde escapes it).

use std::borrow::Cow;
use std::fmt::Write;

/// Whether `c` may not be written raw: the C0 controls (U+0000-U+001F), DEL
/// (U+007F), the C1 controls (U+0080-U+009F, some terminals obey them too)
/// and the noncharacters U+FFFE and U+FFFF, which XML forbids.
pub fn unprintable(c: char) -> bool {
    c.is_control() || c == '\u{fffe}' || c == '\u{ffff}'
}

/// `name` with each unprintable character spelled `\u{..}` (lower-case
/// hex, as Rust's `escape_unicode`): ESC is `\u{1b}`, NUL `\u{0}`.
pub fn printable(name: &str) -> Cow<'_, str> {
    escaped(name, false)
}

/// As `printable`, for a whole text written to a terminal: its own line
/// breaks stay.
pub fn printable_text(text: &str) -> Cow<'_, str> {
    escaped(text, true)
}

fn escaped(text: &str, keep_lines: bool) -> Cow<'_, str> {
    let bad = |c: char| unprintable(c) && !(keep_lines && c == '\n');
    if !text.contains(bad) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if bad(c) {
            let _ = write!(out, "\\u{{{:x}}}", c as u32);
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_spelled_out() {
        // ESC is 0x1B, BEL 0x07, BS 0x08, DEL 0x7F, NUL 0; U+0085 is a C1
        // control, U+FFFE a noncharacter.
        assert_eq!(
            printable("a\x1b[31mb\x07\x08\x7f\0\u{85}\u{fffe}\u{ffff}"),
            "a\\u{1b}[31mb\\u{7}\\u{8}\\u{7f}\\u{0}\\u{85}\\u{fffe}\\u{ffff}"
        );
        // A name's line break or tab is spelled out too; a text's line
        // breaks stay, its tabs do not.
        assert_eq!(printable("two\nlines\t"), "two\\u{a}lines\\u{9}");
        assert_eq!(printable_text("two\nlines\t"), "two\nlines\\u{9}");
        // Every other letter stays, and a clean name is not copied.
        assert_eq!(printable("é 漢 \u{fffd} \\ \""), "é 漢 \u{fffd} \\ \"");
        assert!(matches!(printable("red ball"), Cow::Borrowed(_)));
    }
}
