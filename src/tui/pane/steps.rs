//! The step-through pane: `view::steps`'s lines around the current event,
//! the object breakpoint in the title.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::widgets::Paragraph;

use super::pane_block;
use crate::tui::view::steps::lines;
use crate::tui::{App, Pane};

pub fn draw(frame: &mut Frame, app: &App, area: Rect) {
    let count = app.tree().events.len();
    let mut title = format!(" Step-through · event {} of {count} ", app.current() + 1);
    if let Some(object) = app.break_object().and_then(|o| app.scene().objects.get(o)) {
        title.push_str(&format!("· x stops at hits on {} ", object.name));
    }
    let block = pane_block(app, Pane::Steps, title);
    let height = block.inner(area).height as usize;
    let lines = lines(app.tree(), app.scene(), app.current(), height);
    frame.render_widget(Paragraph::new(lines).block(block), area);
}
