//! The JSON of a ray log's line, read in one pass: JSON, and the bare
//! `NaN`, `Infinity` and `-Infinity` that Python's `json` writes wherever a
//! value goes (docs/RAYLOG.md). It hands out one value at a time, typed, so
//! that `line.rs` reads each key's value straight into what it means; a
//! value it does not want (an unknown key's, say) is read and checked
//! whole all the same. An error is where reading stopped and what was
//! expected there, in serde_json's words.

use std::borrow::Cow;

/// Where reading stopped (a byte offset in the line; its length past the
/// end) and what was expected there.
#[derive(Debug, PartialEq)]
pub(super) struct SyntaxError {
    pub(super) at: usize,
    pub(super) words: String,
}

/// One value, as `Scanner::item` reads it.
#[derive(Debug, PartialEq)]
pub(super) enum Item<'a> {
    Null,
    Number(Number),
    Text(Cow<'a, str>),
    /// A `[` read: its elements follow (`Scanner::next_element`).
    List,
    /// `true`, `false` or an object, read whole.
    Other,
}

/// A number (or a stand-in); `whole` when it is written as an integer from
/// 0 (no sign, fraction or exponent) of at most 19 digits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Number {
    pub(super) value: f64,
    pub(super) whole: Option<u64>,
}

/// As deep as serde_json reads: a line nested deeper is refused, not a
/// stack overflowed.
const MAX_DEPTH: usize = 128;

pub(super) struct Scanner<'a> {
    text: &'a str,
    bytes: &'a [u8],
    /// The next byte to read.
    pub(super) at: usize,
    /// The lists and objects open.
    depth: usize,
}

impl<'a> Scanner<'a> {
    pub(super) fn new(text: &'a str) -> Self {
        Self {
            text,
            bytes: text.as_bytes(),
            at: 0,
            depth: 0,
        }
    }

    /// Past blanks.
    pub(super) fn blank(&mut self) {
        while let Some(b' ' | b'\t' | b'\n' | b'\r') = self.bytes.get(self.at) {
            self.at += 1;
        }
    }

    /// The next byte, past blanks.
    pub(super) fn peek(&mut self) -> Option<u8> {
        self.blank();
        self.bytes.get(self.at).copied()
    }

    /// The line's text from `start` to here.
    pub(super) fn since(&self, start: usize) -> &'a str {
        self.text.get(start..self.at).unwrap_or_default()
    }

    fn error(&self, at: usize, words: impl Into<String>) -> SyntaxError {
        SyntaxError {
            at,
            words: words.into(),
        }
    }

    /// The line ended inside `what`.
    fn end_inside(&self, what: &str) -> SyntaxError {
        self.error(self.bytes.len(), format!("EOF while parsing {what}"))
    }

    /// Nothing but blanks is left.
    pub(super) fn end(&mut self) -> Result<(), SyntaxError> {
        match self.peek() {
            None => Ok(()),
            Some(_) => Err(self.error(self.at, "trailing characters")),
        }
    }

    /// One value. A list is only opened: its elements are the caller's to
    /// read, or to skip with `skip_list`.
    pub(super) fn item(&mut self) -> Result<Item<'a>, SyntaxError> {
        match self.peek() {
            None => Err(self.end_inside("a value")),
            Some(b'"') => self.string().map(Item::Text),
            Some(b'[') => {
                self.open()?;
                Ok(Item::List)
            }
            Some(b'{') => {
                self.skip_object()?;
                Ok(Item::Other)
            }
            Some(b'n') => self.word("null").map(|_| Item::Null),
            Some(b't') => self.word("true").map(|_| Item::Other),
            Some(b'f') => self.word("false").map(|_| Item::Other),
            Some(b'N' | b'I') => self.stand_in(),
            Some(b'-') if self.bytes.get(self.at + 1) == Some(&b'I') => self.stand_in(),
            Some(b'-' | b'0'..=b'9') => self.number().map(Item::Number),
            Some(_) => Err(self.error(self.at, format!("expected value{}", self.hint(self.at)))),
        }
    }

    /// One value, whatever it is, read and checked whole.
    pub(super) fn skip(&mut self) -> Result<(), SyntaxError> {
        if let Item::List = self.item()? {
            self.skip_list()?;
        }
        Ok(())
    }

    /// The rest of a list opened by `item`.
    pub(super) fn skip_list(&mut self) -> Result<(), SyntaxError> {
        let mut first = true;
        while self.next_element(first)? {
            self.skip()?;
            first = false;
        }
        Ok(())
    }

    /// In a list opened by `item`, before its first element (`first`) or
    /// after one: whether another follows (its `,` read), or the list is
    /// closed (its `]` read).
    pub(super) fn next_element(&mut self, first: bool) -> Result<bool, SyntaxError> {
        match self.peek() {
            Some(b']') => {
                self.at += 1;
                self.depth -= 1;
                Ok(false)
            }
            _ if first => Ok(true),
            Some(b',') => {
                self.at += 1;
                Ok(true)
            }
            None => Err(self.end_inside("a list")),
            Some(_) => Err(self.error(self.at, "expected `,` or `]`")),
        }
    }

    /// In an object opened by `open`, before its first key (`first`) or
    /// after a value: the next key and its `:`, or `None` when the object
    /// is closed (its `}` read).
    pub(super) fn next_key(&mut self, first: bool) -> Result<Option<Cow<'a, str>>, SyntaxError> {
        match self.peek() {
            Some(b'}') if first => {
                self.at += 1;
                self.depth -= 1;
                return Ok(None);
            }
            _ if first => {}
            Some(b',') => self.at += 1,
            Some(b'}') => {
                self.at += 1;
                self.depth -= 1;
                return Ok(None);
            }
            None => return Err(self.end_inside("an object")),
            Some(_) => return Err(self.error(self.at, "expected `,` or `}`")),
        }
        let key = match self.peek() {
            Some(b'"') => self.string()?,
            None => return Err(self.end_inside("an object")),
            Some(_) => return Err(self.error(self.at, "key must be a string")),
        };
        match self.peek() {
            Some(b':') => self.at += 1,
            None => return Err(self.end_inside("an object")),
            Some(_) => return Err(self.error(self.at, "expected `:`")),
        }
        Ok(Some(key))
    }

    /// A `[` or `{`, one level deeper.
    pub(super) fn open(&mut self) -> Result<(), SyntaxError> {
        if self.depth == MAX_DEPTH {
            return Err(self.error(self.at, "recursion limit exceeded"));
        }
        self.depth += 1;
        self.at += 1;
        Ok(())
    }

    fn skip_object(&mut self) -> Result<(), SyntaxError> {
        self.open()?;
        let mut first = true;
        while self.next_key(first)?.is_some() {
            self.skip()?;
            first = false;
        }
        Ok(())
    }

    /// `word` (null, true, false or a stand-in), exactly.
    fn word(&mut self, word: &str) -> Result<(), SyntaxError> {
        let start = self.at;
        for &expected in word.as_bytes() {
            match self.bytes.get(self.at) {
                Some(&b) if b == expected => self.at += 1,
                Some(_) => {
                    return Err(self.error(self.at, format!("expected ident{}", self.hint(start))));
                }
                None => return Err(self.end_inside("a value")),
            }
        }
        Ok(())
    }

    /// NaN, Infinity or -Infinity, bare, by its first byte.
    fn stand_in(&mut self) -> Result<Item<'a>, SyntaxError> {
        let (token, value) = match self.bytes[self.at] {
            b'N' => ("NaN", f64::NAN),
            b'I' => ("Infinity", f64::INFINITY),
            _ => ("-Infinity", f64::NEG_INFINITY),
        };
        self.word(token)?;
        Ok(Item::Number(Number { value, whole: None }))
    }

    /// A JSON number, read to the nearest double (as Rust and serde_json
    /// with `float_roundtrip` read it): the same bits as written.
    fn number(&mut self) -> Result<Number, SyntaxError> {
        let start = self.at;
        let negative = self.bytes[self.at] == b'-';
        if negative {
            self.at += 1;
        }
        // The integer's digits as one integer (exact while at most 19).
        let mut digits = 0;
        let integer = self.at;
        match self.bytes.get(self.at) {
            Some(b'0') => {
                self.at += 1;
                if let Some(b'0'..=b'9') = self.bytes.get(self.at) {
                    return Err(self.error(self.at, "invalid number"));
                }
            }
            Some(b'1'..=b'9') => self.digits(&mut digits),
            None => return Err(self.end_inside("a value")),
            Some(_) => {
                return Err(self.error(self.at, format!("invalid number{}", self.hint(start))));
            }
        }
        let count = self.at - integer;
        let (value, whole) = match self.bytes.get(self.at) {
            Some(b'.' | b'e' | b'E') => (self.fraction(start)?, None),
            // At most 19 digits are exact in a u64, whose cast to f64
            // rounds to the nearest double (ties to even) as parsing does.
            _ if count <= 19 => {
                let x = digits as f64;
                let whole = (!negative).then_some(digits);
                (if negative { -x } else { x }, whole)
            }
            _ => (self.parsed(start)?, None),
        };
        if value.is_infinite() {
            return Err(self.error(self.at - 1, "number out of range"));
        }
        Ok(Number { value, whole })
    }

    /// The number from `start` to here, by Rust's own parse.
    fn parsed(&self, start: usize) -> Result<f64, SyntaxError> {
        self.since(start)
            .parse()
            .map_err(|_| self.error(start, "invalid number"))
    }

    /// A number from `start` that has a fraction or an exponent (the
    /// integer part read, up to its `.`, `e` or `E`): its digits are read
    /// and turned into the double in one pass by fast_float (the algorithm
    /// of Rust's own parse, so the same bits), not found here and then
    /// read again. fast_float takes a little more than JSON: `1.` and a
    /// number stopped short (at `1.5e`, say); those are read again below,
    /// for the error's words and where it is.
    fn fraction(&mut self, start: usize) -> Result<f64, SyntaxError> {
        // A `.` at the line's end too goes the slow way, to its own error.
        let dot_then_digit = match &self.bytes[self.at..] {
            [b'.', after @ ..] => after.first().is_some_and(u8::is_ascii_digit),
            _ => true,
        };
        if dot_then_digit
            && let Ok((value, length)) = fast_float2::parse_partial(&self.bytes[start..])
            && !matches!(
                self.bytes.get(start + length),
                Some(b'0'..=b'9' | b'.' | b'e' | b'E' | b'+' | b'-')
            )
        {
            self.at = start + length;
            return Ok(value);
        }
        if self.bytes.get(self.at) == Some(&b'.') {
            self.at += 1;
            self.first_digit()?;
            self.digits(&mut 0);
        }
        if let Some(b'e' | b'E') = self.bytes.get(self.at) {
            self.at += 1;
            if let Some(b'-' | b'+') = self.bytes.get(self.at) {
                self.at += 1;
            }
            self.first_digit()?;
            self.digits(&mut 0);
        }
        // Valid JSON after all (fast_float reads all of it, so this is
        // not reached): read as Rust reads it.
        self.parsed(start)
    }

    /// A digit must come next (in a fraction or an exponent).
    fn first_digit(&self) -> Result<(), SyntaxError> {
        match self.bytes.get(self.at) {
            Some(b'0'..=b'9') => Ok(()),
            None => Err(self.end_inside("a value")),
            Some(_) => Err(self.error(self.at, "invalid number")),
        }
    }

    /// Digits, appended to `value` (which wraps past 19 of them). Only an
    /// integer part comes here on the way to a value (fast_float reads the
    /// rest), mostly a digit or two: one at a time.
    fn digits(&mut self, value: &mut u64) {
        while let Some(&digit @ b'0'..=b'9') = self.bytes.get(self.at) {
            *value = value.wrapping_mul(10).wrapping_add(u64::from(digit - b'0'));
            self.at += 1;
        }
    }

    /// A string, at its `"`: borrowed from the line unless it has an
    /// escape.
    fn string(&mut self) -> Result<Cow<'a, str>, SyntaxError> {
        self.at += 1;
        let start = self.at;
        loop {
            match self.bytes.get(self.at) {
                Some(b'"') => {
                    let text = self.since(start);
                    self.at += 1;
                    return Ok(Cow::Borrowed(text));
                }
                Some(b'\\') => return self.escaped_string(start).map(Cow::Owned),
                Some(0..=0x1f) => return Err(self.control_character()),
                Some(_) => self.at += 1,
                None => return Err(self.end_inside("a string")),
            }
        }
    }

    /// The rest of a string from its first `\`, `start` its first byte.
    fn escaped_string(&mut self, start: usize) -> Result<String, SyntaxError> {
        let mut text = self.since(start).to_string();
        loop {
            let run = self.at;
            while let Some(&b) = self.bytes.get(self.at) {
                if b == b'"' || b == b'\\' || b < 0x20 {
                    break;
                }
                self.at += 1;
            }
            text.push_str(self.since(run));
            match self.bytes.get(self.at) {
                Some(b'"') => {
                    self.at += 1;
                    return Ok(text);
                }
                Some(b'\\') => {
                    self.at += 1;
                    let escaped = self.escape()?;
                    text.push(escaped);
                }
                Some(_) => return Err(self.control_character()),
                None => return Err(self.end_inside("a string")),
            }
        }
    }

    /// The character an escape stands for, after its `\`.
    fn escape(&mut self) -> Result<char, SyntaxError> {
        let Some(&b) = self.bytes.get(self.at) else {
            return Err(self.end_inside("a string"));
        };
        self.at += 1;
        Ok(match b {
            b'"' => '"',
            b'\\' => '\\',
            b'/' => '/',
            b'b' => '\u{8}',
            b'f' => '\u{c}',
            b'n' => '\n',
            b'r' => '\r',
            b't' => '\t',
            b'u' => return self.unicode_escape(),
            _ => return Err(self.error(self.at - 1, "invalid escape")),
        })
    }

    /// `\uXXXX`, after its `u`: a surrogate pair is two of them.
    fn unicode_escape(&mut self) -> Result<char, SyntaxError> {
        let first = self.hex4()?;
        if !(0xD800..0xDC00).contains(&first) {
            return char::from_u32(first)
                .ok_or_else(|| self.error(self.at - 1, "lone trailing surrogate in hex escape"));
        }
        if !self.bytes[self.at..].starts_with(b"\\u") {
            return Err(self.error(self.at, "unexpected end of hex escape"));
        }
        self.at += 2;
        let second = self.hex4()?;
        if !(0xDC00..0xE000).contains(&second) {
            return Err(self.error(self.at - 1, "lone leading surrogate in hex escape"));
        }
        let code = 0x10000 + ((first - 0xD800) << 10) + (second - 0xDC00);
        char::from_u32(code).ok_or_else(|| self.error(self.at - 1, "invalid unicode code point"))
    }

    fn hex4(&mut self) -> Result<u32, SyntaxError> {
        let mut code = 0;
        for _ in 0..4 {
            let digit = match self.bytes.get(self.at) {
                Some(&b) => (b as char).to_digit(16),
                None => return Err(self.end_inside("a string")),
            };
            let Some(digit) = digit else {
                return Err(self.error(self.at, "invalid escape"));
            };
            code = code * 16 + digit;
            self.at += 1;
        }
        Ok(code)
    }

    fn control_character(&self) -> SyntaxError {
        self.error(
            self.at,
            "control character (\\u0000-\\u001F) found while parsing a string",
        )
    }

    /// How to write NaN and the infinities when the value at `start` is one
    /// spelt as C's printf spells it (`nan`, `inf`, `-inf`).
    fn hint(&self, start: usize) -> &'static str {
        let rest = self.text.get(start..).unwrap_or_default();
        let word: String = rest
            .strip_prefix('-')
            .unwrap_or(rest)
            .chars()
            .take_while(char::is_ascii_alphabetic)
            .collect::<String>()
            .to_ascii_lowercase();
        if ["nan", "inf", "infinity"].contains(&word.as_str()) {
            " (write NaN, Infinity or -Infinity)"
        } else {
            ""
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `text` read as one value, then its end.
    fn read(text: &str) -> Result<(), SyntaxError> {
        let mut s = Scanner::new(text);
        s.skip()?;
        s.end()
    }

    /// The error of `text`: where (`at` is the text it starts with; "" for
    /// the end of the line) and its words.
    fn error_at(text: &str, at: &str, words: &str) {
        let error = read(text).expect_err(text);
        let offset = if at.is_empty() {
            text.len()
        } else {
            text.find(at).unwrap()
        };
        assert_eq!(
            error,
            SyntaxError {
                at: offset,
                words: words.into()
            },
            "{text}"
        );
    }

    #[test]
    fn json_and_the_stand_ins_read() {
        for text in [
            r#"{"a": [1, -0.5e-3, 2E+2, 0, -0], "b": {"c": [true, false, null]}, "d": "\"\\\/\b\f\n\r\t\u00e9\ud83d\ude00"}"#,
            "{\"a\": [NaN, Infinity, -Infinity], \"b\": {\"c\": NaN}}",
            " \t[ ] ",
            "{}",
        ] {
            assert_eq!(read(text), Ok(()), "{text}");
        }
        let mut s = Scanner::new(r#""p\u0061th\/é" 12 -3 4.0 NaN -Infinity"#);
        assert_eq!(s.item(), Ok(Item::Text(Cow::Owned("path/é".into()))));
        let number = |value, whole| Ok(Item::Number(Number { value, whole }));
        assert_eq!(s.item(), number(12.0, Some(12)));
        assert_eq!(s.item(), number(-3.0, None));
        assert_eq!(s.item(), number(4.0, None));
        assert!(matches!(s.item(), Ok(Item::Number(n)) if n.value.is_nan() && n.whole.is_none()));
        assert_eq!(s.item(), number(f64::NEG_INFINITY, None));
        assert_eq!(s.end(), Ok(()));
    }

    #[test]
    fn numbers_read_to_the_nearest_double() {
        for text in [
            "0.1",
            "5e-324",
            "1.7976931348623157e308",
            "9007199254740993",
            "2.2250738585072011e-308",
            "0.30000000000000004",
            "-0.1",
            "12.0",
            "1e2",
        ] {
            let mut s = Scanner::new(text);
            assert_eq!(
                s.item(),
                Ok(Item::Number(Number {
                    value: text.parse().unwrap(),
                    whole: text.parse().ok(),
                })),
                "{text}"
            );
        }
        // Past u64, an integer is still a number, but not a whole one.
        let mut s = Scanner::new("18446744073709551616");
        assert!(matches!(
            s.item(),
            Ok(Item::Number(Number { whole: None, .. }))
        ));
    }

    /// Numbers as tracers print them (shortest, `%.17g`, `%e`, short
    /// decimals) and longer ones read to the bits Rust's own parsing gives,
    /// on both sides of the fast path's limits (2^53, 10^22, 19 digits).
    #[test]
    fn numbers_read_as_rust_reads_them() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..20_000 {
            let bits = next();
            let x = f64::from_bits(bits);
            let short = next() % 100_000_000;
            let power = (next() % 61) as i32 - 30;
            let texts = [
                format!("{x}"),
                format!("{x:e}"),
                format!("{x:.16e}"),
                format!("{}", x.abs() * 1e-3),
                format!("{short}e{power}"),
                format!("-{}.{:05}", short, next() % 100_000),
                format!("{}", (1u64 << 53) + next() % 4),
                // Past 19 significant digits (fast_float's slower path).
                format!("{x:.24e}"),
                format!("{}{:019}", short, next() % 10_000_000_000_000_000_000),
            ];
            for text in texts.iter().filter(|t| x.is_finite() || !t.contains("inf")) {
                let Ok(expected) = text.parse::<f64>() else {
                    continue;
                };
                if text.contains("NaN") || expected.is_infinite() {
                    continue;
                }
                let mut s = Scanner::new(text);
                match s.item() {
                    Ok(Item::Number(n)) => {
                        assert_eq!(n.value.to_bits(), expected.to_bits(), "{text}")
                    }
                    other => panic!("{text}: {other:?}"),
                }
            }
        }
    }

    #[test]
    fn an_error_is_where_reading_stopped() {
        error_at(r#"{"a": 1 "b": 2}"#, r#""b""#, "expected `,` or `}`");
        error_at(r#"{"a" 1}"#, "1}", "expected `:`");
        error_at("{1: 2}", "1:", "key must be a string");
        error_at("{NaN: 2}", "NaN", "key must be a string");
        error_at("[1 2]", "2]", "expected `,` or `]`");
        error_at("[1,]", "]", "expected value");
        error_at("[01]", "1]", "invalid number");
        error_at("[1.]", "]", "invalid number");
        error_at("[1e+]", "]", "invalid number");
        error_at("[-]", "]", "invalid number");
        // What fast_float would take but JSON does not (a bare `.`, an
        // exponent without digits), and a number stopped by another's byte.
        error_at("[1.e5]", "e5", "invalid number");
        error_at("[0.5e]", "]", "invalid number");
        error_at("[2.5E-x]", "x", "invalid number");
        error_at("[1.5.2]", ".2", "expected `,` or `]`");
        error_at("[1e5e1]", "e1", "expected `,` or `]`");
        error_at("[-0.5-1]", "-1", "expected `,` or `]`");
        error_at("[1.", "", "EOF while parsing a value");
        error_at("[1e", "", "EOF while parsing a value");
        error_at("[1e400]", "0]", "number out of range");
        error_at("[-1e400]", "0]", "number out of range");
        error_at(r#"["\q"]"#, "q", "invalid escape");
        error_at(r#"["\u12x4"]"#, "x", "invalid escape");
        error_at(r#"["\ud800"]"#, r#""]"#, "unexpected end of hex escape");
        error_at(
            r#"["\ud800\u0041"]"#,
            r#"1""#,
            "lone leading surrogate in hex escape",
        );
        error_at(
            "[\"a\tb\"]",
            "\t",
            "control character (\\u0000-\\u001F) found while parsing a string",
        );
        error_at("[tru]", "]", "expected ident");
        error_at(
            "[Nan]",
            "n]",
            "expected ident (write NaN, Infinity or -Infinity)",
        );
        error_at(
            "[-Inf]",
            "]",
            "expected ident (write NaN, Infinity or -Infinity)",
        );
        error_at(
            "[1, inf]",
            "inf",
            "expected value (write NaN, Infinity or -Infinity)",
        );
        error_at("[1] 2", "2", "trailing characters");
        // A line that ends too soon: past its end.
        error_at(r#"{"a": "#, "", "EOF while parsing a value");
        error_at(r#"{"a": "é"#, "", "EOF while parsing a string");
        error_at(r#"{"a": 1"#, "", "EOF while parsing an object");
        error_at("[1", "", "EOF while parsing a list");
        error_at("[Infin", "", "EOF while parsing a value");
    }

    #[test]
    fn a_line_nested_too_deep_is_refused_not_overflowed() {
        let deep = "[".repeat(100_000);
        let error = read(&deep).unwrap_err();
        assert_eq!(
            error,
            SyntaxError {
                at: MAX_DEPTH,
                words: "recursion limit exceeded".into()
            }
        );
        let fine = format!("{}{}", "[".repeat(MAX_DEPTH), "]".repeat(MAX_DEPTH));
        assert_eq!(read(&fine), Ok(()));
    }
}
