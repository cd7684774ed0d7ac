//! The step-through pane: `view::steps`'s lines around the current event,
//! the object breakpoint in the title.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::widgets::Paragraph;

use super::pane_block;
use crate::tui::view::steps::lines;
use crate::tui::{App, Pane};

pub(crate) fn draw(frame: &mut Frame, app: &App, area: Rect) {
    let (pixel, scene) = (app.pixel(), app.session().scene());
    let count = pixel.tree().events.len();
    let mut title = format!(" Step-through · event {} of {count} ", pixel.current() + 1);
    if let Some(object) = pixel.break_object().and_then(|o| scene.objects.get(o)) {
        title.push_str(&format!("· x stops at hits on {} ", object.name));
    }
    let block = pane_block(app, Pane::Steps, title);
    let height = block.inner(area).height as usize;
    let lines = lines(pixel.tree(), scene, pixel.current(), height);
    frame.render_widget(Paragraph::new(lines).block(block), area);
}
