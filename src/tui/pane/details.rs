//! The details pane: `view::details`'s lines for the selected ray, scrolled
//! to the current event's lines unless the user scrolled. With a ray log
//! whose pixel this is, the selected ray's numbers beside the log's come
//! first (`view::your_rays`), and arriving at a ray shows them.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::widgets::Paragraph;

use super::pane_block;
use crate::tui::view::details::{compare_line, lines, what_if_lines};
use crate::tui::view::your_rays::{detail_lines, selected_path};
use crate::tui::{App, Pane};
use raystep_engine::record::{EventKind, kind_name};

pub fn draw(frame: &mut Frame, app: &App, area: Rect) {
    let pixel = app.pixel();
    let id = pixel.selected_node();
    let node = &pixel.tree().nodes[id];
    let title = format!(" Details · r{id} {} ray ", kind_name(node.kind));
    let block = pane_block(app, Pane::Details, title);
    let inside = block.inner(area);
    let (mut lines, mut marked) = lines(
        pixel.tree(),
        id,
        Some(pixel.current()),
        inside.width as usize,
    );
    let (x, y) = pixel.cursor();
    if let Some(what_if) = pixel.what_if() {
        let changed = what_if_lines(what_if, inside.width as usize);
        marked = marked.map(|m| m + changed.len());
        lines.splice(0..0, changed);
    }
    let report = app.ray_log().and_then(|log| log.report());
    let path = report.and_then(|_| selected_path(pixel.tree(), pixel.current()));
    if let (Some(report), Some(path)) = (report, path) {
        let scene = app.session().scene();
        let yours = detail_lines(report, &path, pixel.tree(), scene, inside.width as usize);
        let arriving = pixel.tree().events.get(pixel.current()).is_some_and(|e| {
            matches!(
                e.kind,
                EventKind::RayCast { .. } | EventKind::ShadowCast { .. }
            )
        });
        marked = if arriving && !yours.is_empty() {
            Some(0)
        } else {
            marked.map(|m| m + yours.len())
        };
        lines.splice(0..0, yours);
    }
    if let Some(yours) = app.comparison().map(|c| c.yours().get_pixel(x, y).0) {
        lines.insert(0, compare_line(yours, app.our_pixel()));
        marked = marked.map(|m| m + 1);
    }
    let height = inside.height as usize;
    let auto = marked.map_or(0, |m| {
        if m + 4 <= height {
            0
        } else {
            m.saturating_sub(1)
        }
    });
    let most = lines.len().saturating_sub(height);
    let offset = pixel
        .details_scroll()
        .map_or(auto, |s| s as usize)
        .min(most);
    frame.render_widget(
        Paragraph::new(lines)
            .block(block)
            .scroll((offset as u16, 0)),
        area,
    );
}
