//! Text from the model made safe and legible in HTML. Student names are
//! folder names, so anything at all: markup characters become entities (the
//! same in element text and in quoted attributes), and control characters,
//! which HTML does not allow and a browser would show as nothing, become
//! visible stand-ins, so that two names differing only there still look
//! different.

/// `text` for an element's content or a quoted attribute value.
pub(super) fn escape(text: &str) -> String {
    escaped(text, false)
}

/// `text` for a `<pre>` block: as `escape`, but line breaks and tabs stay.
pub(super) fn escape_block(text: &str) -> String {
    escaped(text, true)
}

fn escaped(text: &str, keep_lines: bool) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            '\n' | '\t' if keep_lines => out.push(c),
            '\r' if keep_lines => {}
            c => out.push(visible(c)),
        }
    }
    out
}

/// A control character's stand-in: C0 controls and DEL as their Unicode
/// Control Pictures (U+0007 shows as ␇), C1 controls as U+FFFD.
fn visible(c: char) -> char {
    match c {
        '\0'..='\x1f' => char::from_u32(0x2400 + c as u32).unwrap_or('\u{fffd}'),
        '\x7f' => '\u{2421}',
        '\u{80}'..='\u{9f}' => '\u{fffd}',
        c => c,
    }
}

/// A relative path from the model as a URL for `href` or `src`: every byte
/// outside `A-Z a-z 0-9 - . _ ~ /` percent-encoded, so that no file name
/// can start a scheme (`javascript:`), a query or a fragment, or end the
/// attribute.
pub(super) fn url(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    for byte in path.bytes() {
        if byte.is_ascii_alphanumeric() || b"-._~/".contains(&byte) {
            out.push(byte as char);
        } else {
            out.push_str(&format!("%{byte:02X}"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_and_quotes_become_entities() {
        assert_eq!(
            escape("<script>alert('x & \"y\"')</script>"),
            "&lt;script&gt;alert(&#39;x &amp; &quot;y&quot;&#39;)&lt;/script&gt;"
        );
    }

    #[test]
    fn control_characters_become_visible() {
        // BEL is U+0007: its picture is U+2400 + 7 = U+2407; NUL is U+2400,
        // DEL U+2421, and U+0085 (a C1 control) has no picture.
        assert_eq!(
            escape("a\x07b\0c\x7fd\u{85}e"),
            "a\u{2407}b\u{2400}c\u{2421}d\u{fffd}e"
        );
        // A line break in a name would be invisible too: U+2400 + 10.
        assert_eq!(escape("two\nlines"), "two\u{240a}lines");
        assert_eq!(escape_block("two\nlines\tand\r\n"), "two\nlines\tand\n");
        // What is already a replacement character, or any other letter, stays.
        assert_eq!(escape("\u{fffd}é漢"), "\u{fffd}é漢");
    }

    #[test]
    fn a_url_can_only_name_a_relative_file() {
        assert_eq!(url("students/ada_1.png"), "students/ada_1.png");
        // ':' is 3A, ' ' 20, '"' 22, '#' 23, '?' 3F; é is C3 A9 in UTF-8.
        assert_eq!(url("javascript:x"), "javascript%3Ax");
        assert_eq!(url("a b\"#?é"), "a%20b%22%23%3F%C3%A9");
    }
}
