//! The `?` overlay: every key, from the same table the key handling uses.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Stylize;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};

use super::event::KEYS;

const KEY_WIDTH: usize = 22;

pub fn lines() -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    for (group, keys) in KEYS {
        if !lines.is_empty() {
            lines.push(Line::raw(""));
        }
        lines.push(Line::from(Span::raw(*group).bold().underlined()));
        for (key, what) in *keys {
            lines.push(Line::from(vec![Span::raw(format!("  {key:<KEY_WIDTH$}")).cyan().bold(), Span::raw(*what)]));
        }
    }
    lines
}

pub fn draw(frame: &mut Frame, area: Rect) {
    let lines = lines();
    let width = (lines.iter().map(|l| l.width()).max().unwrap_or(40) as u16 + 4).min(area.width);
    let height = (lines.len() as u16 + 2).min(area.height);
    let rect = Rect::new(area.x + (area.width - width) / 2, area.y + (area.height - height) / 2, width, height);
    let block = Block::bordered().title(" Keys · any key closes this help ".bold()).title_bottom(" raystep ".dark_gray());
    frame.render_widget(Clear, rect);
    frame.render_widget(Paragraph::new(lines).block(block), rect);
}
