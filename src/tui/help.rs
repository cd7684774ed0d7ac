//! The `?` overlay: every row of `keymap::KEYMAP`, the table the key handling uses.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Stylize;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};

use super::keymap::KEYMAP;

const KEY_WIDTH: usize = 22;

pub fn lines() -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    for (group, rows) in KEYMAP {
        if !lines.is_empty() {
            lines.push(Line::raw(""));
        }
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

/// How many lines of the help a terminal `height` rows tall cannot show.
pub fn hidden_lines(height: u16) -> u16 {
    (lines().len() as u16 + 2).saturating_sub(height)
}

/// The overlay, scrolled by `scroll` lines when the terminal is too short.
pub fn draw(frame: &mut Frame, area: Rect, scroll: u16) {
    let lines = lines();
    let width = (lines.iter().map(|l| l.width()).max().unwrap_or(40) as u16 + 2).min(area.width);
    let height = (lines.len() as u16 + 2).min(area.height);
    let hidden = hidden_lines(area.height);
    let scroll = scroll.min(hidden);
    let rect = Rect::new(
        area.x + (area.width - width) / 2,
        area.y + (area.height - height) / 2,
        width,
        height,
    );
    let bottom = if hidden > 0 {
        " j/k scroll for more, any other key closes "
    } else {
        " any key closes this help "
    };
    let block = Block::bordered()
        .title(" raystep keys ".bold())
        .title_bottom(bottom.dark_gray());
    frame.render_widget(Clear, rect);
    frame.render_widget(Paragraph::new(lines).block(block).scroll((scroll, 0)), rect);
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
        // 5 titles, 4 blank lines between groups, one line per row.
        assert_eq!(text.len(), 5 + 4 + keymap::rows().count());
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
