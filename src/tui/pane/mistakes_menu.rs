//! The `M` menu: `view::mistakes_menu`'s lines in a centred box over the panes,
//! drawn like the help.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Stylize;
use ratatui::widgets::{Block, Clear, Paragraph};

use crate::tui::App;
use crate::tui::view::mistakes_menu::lines;

pub(crate) fn draw(frame: &mut Frame, app: &App, area: Rect, selected: usize) {
    let ranked = app
        .comparison()
        .map_or(&[][..], |c| &c.findings().mistakes[..]);
    let rows = app.overlay().menu_mistakes();
    let lines = lines(rows, app.session().settings().mistakes, selected, ranked);
    let bottom = " j/k select · Space turns on/off · Esc or M closes ";
    let width = lines
        .iter()
        .map(|l| l.width())
        .max()
        .unwrap_or(40)
        .max(bottom.len()) as u16
        + 2;
    let width = width.min(area.width);
    let height = (lines.len() as u16 + 2).min(area.height);
    let rect = Rect::new(
        area.x + (area.width - width) / 2,
        area.y + (area.height - height) / 2,
        width,
        height,
    );
    let block = Block::bordered()
        .title(" Classic student mistakes: trace as a student's tracer would ".bold())
        .title_bottom(bottom.dark_gray());
    frame.render_widget(Clear, rect);
    frame.render_widget(Paragraph::new(lines).block(block), rect);
}
