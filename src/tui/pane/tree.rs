//! The ray tree pane: the rows of `view::tree`, scrolled to keep the current
//! event's row in sight and that row highlighted.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::Paragraph;

use super::pane_block;
use crate::tui::view::tree::{row_line, rows, scroll_offset, selected_row, selected_style};
use crate::tui::{App, Pane};

pub(crate) fn draw(frame: &mut Frame, app: &App, area: Rect) {
    let pixel = app.pixel();
    let tree = pixel.tree();
    let rays = tree.nodes.len();
    let title = format!(
        " Ray tree · pixel ({}, {}) · {rays} ray{} ",
        tree.pixel.0,
        tree.pixel.1,
        if rays == 1 { "" } else { "s" }
    );
    let block = pane_block(app, Pane::Tree, title);
    let inside = block.inner(area);
    let rows = rows(tree, pixel.collapsed());
    let selected = selected_row(tree, &rows, pixel.current());
    let first = scroll_offset(selected.unwrap_or(0), inside.height as usize);
    let lines: Vec<Line> = rows
        .iter()
        .enumerate()
        .skip(first)
        .take(inside.height as usize)
        .map(|(i, row)| {
            let line = row_line(tree, pixel.collapsed(), row, inside.width as usize);
            if Some(i) == selected {
                line.patch_style(selected_style(app.screen().focus() == Pane::Tree))
            } else {
                line
            }
        })
        .collect();
    frame.render_widget(Paragraph::new(lines).block(block), area);
}
