//! The `?` overlay's text: every row of `keymap::KEYMAP`, the table the key
//! handling uses, and how much of it a short terminal hides.

use ratatui::style::Stylize;
use ratatui::text::{Line, Span};

use crate::tui::keymap::KEYMAP;

const KEY_WIDTH: usize = 22;

pub(crate) fn lines() -> Vec<Line<'static>> {
    // First, on every screen: how to quit (the quit row of "Other" lay
    // below the fold of an 80x24 terminal).
    let mut lines = vec![Line::from(QUIT).bold()];
    for (group, rows) in KEYMAP {
        lines.push(Line::raw(""));
        lines.push(Line::from(Span::raw(*group).bold().underlined()));
        for row in *rows {
            lines.push(Line::from(vec![
                Span::raw(format!("  {:<KEY_WIDTH$}", row.keys()))
                    .cyan()
                    .bold(),
                Span::raw(row.what),
            ]));
        }
    }
    lines
}

/// The help's first line.
pub(crate) const QUIT: &str =
    "To quit: q or Esc once this help is closed (any key); Ctrl+C at once.";

/// How many lines of the help a terminal `height` rows tall cannot show.
pub(crate) fn hidden_lines(height: u16) -> u16 {
    (lines().len() as u16 + 2).saturating_sub(height)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::keymap;

    fn text() -> Vec<String> {
        let line = |l: &Line| l.spans.iter().map(|s| s.content.as_ref()).collect();
        lines().iter().map(line).collect()
    }

    #[test]
    fn the_help_lists_every_row_of_the_key_table() {
        let text = text();
        for row in keymap::rows() {
            let want = format!("  {:<KEY_WIDTH$}{}", row.keys(), row.what);
            assert!(text.contains(&want), "{want:?} missing from the help");
        }
        for (group, _) in keymap::KEYMAP {
            assert!(text.iter().any(|l| l == group), "{group}");
        }
        // How to quit and a blank line, 8 titles, 7 blank lines between
        // groups, one line per row.
        assert_eq!(text[0], QUIT);
        assert_eq!(keymap::KEYMAP.len(), 8);
        assert_eq!(text.len(), 2 + 8 + 7 + keymap::rows().count());
    }

    #[test]
    fn the_help_shows_the_keys_the_old_help_left_out() {
        let text = text().join("\n");
        for key in [
            "PageUp PageDown",
            "g Home e End",
            "Enter Space",
            "Ctrl+C",
            "mouse wheel",
        ] {
            assert!(text.contains(key), "{key}");
        }
    }
}
