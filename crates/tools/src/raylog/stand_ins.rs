//! NaN and the infinities as Python's `json` writes them (bare `NaN`,
//! `Infinity`, `-Infinity`), which JSON lacks: a line is made JSON by
//! turning them into stand-in strings, remembered so that an error's
//! column still points into the line as written; and the hint for C's
//! spellings (`nan`, `inf`).

use std::borrow::Cow;
use std::collections::HashMap;

use serde_json::Value;

/// The bare tokens JSON lacks, the strings they stand in as for serde_json
/// (a NUL no tracer prints in a key's value), and what they read as.
pub(super) const STAND_INS: [(&str, &str, f64); 3] = [
    ("-Infinity", "\u{0}-Infinity", f64::NEG_INFINITY),
    ("Infinity", "\u{0}Infinity", f64::INFINITY),
    ("NaN", "\u{0}NaN", f64::NAN),
];

/// A line made JSON: NaN and infinities outside strings become stand-in
/// strings, remembered so that an error's column points into the line as
/// written; and, when asked (for an error's column), where each top-level
/// key's value starts.
pub(super) struct Prepared<'a> {
    /// The line itself when it has no NaN or infinity, as most have.
    pub(super) json: Cow<'a, str>,
    /// (start in json, length there, start in the line, length there).
    replaced: Vec<(usize, usize, usize, usize)>,
    pub(super) value_at: HashMap<String, usize>,
}

impl Prepared<'_> {
    /// The byte offset in the line of byte `offset` of the JSON.
    pub(super) fn text_offset(&self, offset: usize) -> usize {
        let mut shift = 0isize;
        for &(json_start, json_len, text_start, text_len) in &self.replaced {
            if offset < json_start {
                break;
            }
            if offset < json_start + json_len {
                return text_start;
            }
            shift = (text_start + text_len) as isize - (json_start + json_len) as isize;
        }
        offset.saturating_add_signed(shift)
    }
}

/// `text` prepared; `locate_keys` fills `value_at`.
pub(super) fn prepare(text: &str, locate_keys: bool) -> Prepared<'_> {
    let bytes = text.as_bytes();
    let mut json = String::new();
    let mut prepared = Prepared {
        json: Cow::Borrowed(text),
        replaced: Vec::new(),
        value_at: HashMap::new(),
    };
    let (mut i, mut copied) = (0, 0);
    // The objects and arrays open (`{` or `[`), and the last byte outside a
    // string that was not blank (`"` after a string): a stand-in goes only
    // where a value may, so `{NaN: 1}` stays not JSON.
    let (mut open, mut last): (Vec<u8>, u8) = (Vec::new(), b' ');
    // A top-level string before its ':' (a key), and a key awaiting its value.
    let (mut key, mut awaiting): (Option<String>, Option<String>) = (None, None);
    while i < bytes.len() {
        match bytes[i] {
            b'"' => {
                let start = i;
                i += 1;
                while i < bytes.len() {
                    match bytes[i] {
                        b'\\' => i += 2,
                        b'"' => {
                            i += 1;
                            break;
                        }
                        _ => i += 1,
                    }
                }
                let end = i.min(bytes.len());
                if let Some(k) = awaiting.take() {
                    prepared.value_at.insert(k, start);
                } else if open.len() == 1 && locate_keys {
                    key = text
                        .get(start..end)
                        .and_then(|s| serde_json::from_str(s).ok());
                }
                last = b'"';
                continue;
            }
            b':' if open.len() == 1 => {
                awaiting = key.take();
                last = b':';
                i += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' | b'\n' => {
                i += 1;
                continue;
            }
            _ => {}
        }
        if let Some(k) = awaiting.take() {
            prepared.value_at.insert(k, i);
        }
        key = None;
        // The rest of a number at once (most of a line): none of its bytes
        // opens or closes anything, and none starts a stand-in (the `-` of
        // 1e-7 follows a digit, where no value goes).
        if bytes[i].is_ascii_digit() {
            while bytes
                .get(i)
                .is_some_and(|b| matches!(b, b'0'..=b'9' | b'.' | b'e' | b'E' | b'+' | b'-'))
            {
                i += 1;
            }
            last = bytes[i - 1];
            continue;
        }
        let in_array = open.last() == Some(&b'[');
        let value_goes_here = last == b':' || (in_array && matches!(last, b'[' | b','));
        let token = STAND_INS
            .iter()
            .filter(|_| value_goes_here)
            .find(|(token, _, _)| {
                let end = i + token.len();
                bytes[i..].starts_with(token.as_bytes())
                    && !bytes.get(end).is_some_and(|b| b.is_ascii_alphanumeric())
            });
        match token {
            Some((token, stand_in, _)) => {
                json.push_str(&text[copied..i]);
                let quoted = serde_json::to_string(stand_in).unwrap_or_default();
                prepared
                    .replaced
                    .push((json.len(), quoted.len(), i, token.len()));
                json.push_str(&quoted);
                i += token.len();
                copied = i;
                last = b'0';
            }
            None => {
                match bytes[i] {
                    b'{' | b'[' => open.push(bytes[i]),
                    b'}' | b']' => {
                        open.pop();
                    }
                    _ => {}
                }
                last = bytes[i];
                i += 1;
            }
        }
    }
    if !prepared.replaced.is_empty() {
        json.push_str(text.get(copied..).unwrap_or_default());
        prepared.json = Cow::Owned(json);
    }
    prepared
}

/// A hint when the word at byte `at` is NaN or infinity spelt as C's
/// printf spells it (`nan`, `inf`, `-inf`), which JSON does not read.
pub(super) fn spelling_hint(text: &str, at: usize) -> &'static str {
    let bytes = text.as_bytes();
    let mut start = at.min(bytes.len());
    while start > 0 && bytes[start - 1].is_ascii_alphabetic() {
        start -= 1;
    }
    // `at` may fall inside a character (serde_json counts bytes).
    let word: String = text
        .get(start..)
        .unwrap_or_default()
        .chars()
        .take_while(|c| c.is_ascii_alphabetic())
        .collect::<String>()
        .to_ascii_lowercase();
    if ["nan", "inf", "infinity"].contains(&word.as_str()) {
        " (write NaN, Infinity or -Infinity)"
    } else {
        ""
    }
}

/// The column (in characters, from 1) of byte `offset` of `text`.
pub(super) fn column_of(text: &str, offset: usize) -> usize {
    text.char_indices().take_while(|(i, _)| *i < offset).count() + 1
}

/// A number, or the student's NaN or infinity (`prepare`'s stand-ins).
pub fn number(value: &Value) -> Option<f64> {
    match value {
        Value::Number(n) => n.as_f64(),
        Value::String(s) => STAND_INS
            .iter()
            .find(|(_, stand_in, _)| &s.as_str() == stand_in)
            .map(|(_, _, x)| *x),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_and_infinities_become_stand_ins_outside_strings_only() {
        let prepared = prepare(
            r#"{"t": NaN, "c": [Infinity, -Infinity], "s": "NaN"}"#,
            true,
        );
        let value: Value = serde_json::from_str(&prepared.json).unwrap();
        assert!(number(&value["t"]).unwrap().is_nan());
        assert_eq!(number(&value["c"][0]), Some(f64::INFINITY));
        assert_eq!(number(&value["c"][1]), Some(f64::NEG_INFINITY));
        assert_eq!(value["s"], "NaN");
        assert_eq!(number(&value["s"]), None);
        // Where each value starts in the line as written.
        assert_eq!(prepared.value_at["t"], 6);
        assert_eq!(prepared.value_at["c"], 16);
        assert_eq!(prepared.value_at["s"], 44);
    }

    #[test]
    fn an_offset_past_a_stand_in_maps_back_into_the_line() {
        // `NaN` (3 bytes) became `"\u0000NaN"` (11 bytes): 8 more.
        let prepared = prepare(r#"{"t": NaN, x}"#, true);
        let e = serde_json::from_str::<Value>(&prepared.json).unwrap_err();
        // The `x` is byte 11 of the line (from 0), its column 12.
        assert_eq!(
            column_of(r#"{"t": NaN, x}"#, prepared.text_offset(e.column() - 1)),
            12
        );
        assert_eq!(prepared.text_offset(8), 6, "inside the stand-in: its token");
    }

    #[test]
    fn numbers_beside_stand_ins_are_read_whole() {
        // A value after a number and a comma is replaced; a token glued to
        // a number (`1-Infinity`, `2eNaN`) is not, and stays not JSON.
        let prepared = prepare(r#"{"c": [1e-7, -Infinity, 2.5E+3, NaN], "t": -0.5}"#, true);
        assert_eq!(prepared.replaced.len(), 2);
        let value: Value = serde_json::from_str(&prepared.json).unwrap();
        assert_eq!(number(&value["c"][0]), Some(1e-7));
        assert_eq!(number(&value["c"][1]), Some(f64::NEG_INFINITY));
        assert_eq!(number(&value["c"][2]), Some(2500.0));
        assert!(number(&value["c"][3]).unwrap().is_nan());
        assert_eq!(number(&value["t"]), Some(-0.5));
        for line in ["{\"a\": [1-Infinity]}", "{\"a\": 2eNaN}"] {
            assert_eq!(prepare(line, true).json, line);
        }
    }

    #[test]
    fn words_that_merely_contain_the_tokens_are_left_alone() {
        assert_eq!(prepare("{\"a\": xNaN}", true).json, "{\"a\": xNaN}");
        assert_eq!(prepare("{\"a\": NaNx}", true).json, "{\"a\": NaNx}");
    }

    #[test]
    fn only_a_value_becomes_a_stand_in() {
        // A key, a second word, or a word at the top are left as written.
        for line in ["{NaN: 1}", "{\"a\": 1 NaN}", "NaN", "{\"a\": [1 NaN]}"] {
            assert_eq!(prepare(line, true).json, line);
        }
        let prepared = prepare("{\"a\": [NaN, Infinity], \"b\": {\"c\": -Infinity}}", true);
        assert_eq!(prepared.replaced.len(), 3);
    }
}
