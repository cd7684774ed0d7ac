//! The `?` overlay: `view::help`'s lines in a centred box over the panes.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Stylize;
use ratatui::widgets::{Block, Clear, Paragraph};

use crate::tui::view::help::{hidden_lines, lines};

/// The overlay, scrolled by `scroll` lines when the terminal is too short.
pub(crate) fn draw(frame: &mut Frame, area: Rect, scroll: u16) {
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
