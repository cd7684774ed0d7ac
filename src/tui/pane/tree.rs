//! The ray tree pane: the rows of `view::tree`, scrolled to keep the current
//! event's row in sight and that row highlighted. With a ray log whose
//! pixel this is, each row starts with its ray's mark against the log
//! (`view::your_rays`), the rays only in the log follow the tree, and the
//! marks' legend is on the bottom border.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::pane_block;
use std::collections::BTreeSet;

use crate::tui::view::tree::{
    LogLabel, Row, row_line, scroll_offset, selected_row, selected_style,
};
use crate::tui::view::your_rays::{RowMarks, legend, mark, only_yours_lines};
use crate::tui::{App, Pane};
use raystep_engine::record::{NodeId, RayTree, count};
use raystep_tools::divergence::RayStatus;

pub(crate) fn draw(frame: &mut Frame, app: &App, area: Rect) {
    let pixel = app.pixel();
    let tree = pixel.tree();
    let rays = tree.nodes.len();
    let log = app.ray_log();
    let report = log.and_then(|l| l.report());
    let against = match (log, report) {
        (None, _) => String::new(),
        (Some(l), None) if l.comparing() => " · comparing with your log…".into(),
        (Some(_), None) => " · not in your log".into(),
        (Some(_), Some(r)) if r.matches => " · your log matches".into(),
        (Some(_), Some(_)) => " · your log differs".into(),
    };
    // Beside a log, the rays counted as `compare --rays` counts them: the
    // shadow rays too, and it says so.
    let rays = match report {
        Some(r) => format!(
            "{} ({} shadow)",
            count(r.rays_ours as u64, "ray", "rays"),
            r.rays_ours - rays
        ),
        None => count(rays as u64, "ray", "rays"),
    };
    let title = format!(
        " Ray tree · pixel ({}, {}) · {rays}{against} ",
        tree.pixel.0, tree.pixel.1,
    );
    let mut block = pane_block(app, Pane::Tree, title);
    if report.is_some() {
        block = block.title_bottom(legend(area.width as usize));
    }
    let inside = block.inner(area);
    let rows = pixel.rows();
    let selected = selected_row(tree, rows, pixel.current());
    let first = scroll_offset(selected.unwrap_or(0), inside.height as usize);
    let marks = report.map(|r| RowMarks::new(tree, r));
    let width = inside.width as usize;
    // Only the lines shown are made (a tree of 65,536 rays has twice as
    // many rows): the rows from `first`, then the rays only in the log.
    let height = inside.height as usize;
    let mut lines: Vec<Line> = (rows.iter().enumerate())
        .skip(first)
        .take(height)
        .map(|(i, row)| {
            let line = match &marks {
                None => row_line(tree, pixel.collapsed(), row, LogLabel::default(), width),
                Some(marks) => marked_row(marks, tree, pixel.collapsed(), row, width),
            };
            if Some(i) == selected {
                line.patch_style(selected_style(app.screen().focus() == Pane::Tree))
            } else {
                line
            }
        })
        .collect();
    if let Some(report) = report {
        let (symbol, color) = mark(RayStatus::OnlyYours);
        let room = height - lines.len();
        let only_yours = (only_yours_lines(report).into_iter())
            .skip(first.saturating_sub(rows.len()))
            .take(room);
        for (text, is_first) in only_yours {
            let text: String = text.chars().take(width.saturating_sub(2)).collect();
            let style = if is_first {
                Style::new().add_modifier(Modifier::BOLD)
            } else {
                Style::new()
            };
            lines.push(Line::from(vec![
                Span::styled(format!("{symbol} "), Style::new().fg(color)),
                Span::styled(text, style),
            ]));
        }
    }
    frame.render_widget(Paragraph::new(lines).block(block), area);
}

/// A row with its ray's mark in front and its path in the log's words;
/// the first divergence's row says so.
fn marked_row(
    marks: &RowMarks,
    tree: &RayTree,
    collapsed: &BTreeSet<NodeId>,
    row: &Row,
    width: usize,
) -> Line<'static> {
    let path = marks.path(row.kind).map(|p| p.to_string());
    let first = marks.is_first(row.kind);
    let label = LogLabel {
        path: path.as_deref(),
        note: first.then_some("◀ first divergence"),
    };
    let line = row_line(tree, collapsed, row, label, width.saturating_sub(2));
    let head = match marks.status(row.kind) {
        Some(status) => {
            let (symbol, color) = mark(status);
            let mut style = Style::new().fg(color);
            if first {
                style = style.add_modifier(Modifier::BOLD | Modifier::REVERSED);
            }
            Span::styled(symbol.to_string(), style)
        }
        None => Span::raw(" "),
    };
    let mut spans = vec![head, Span::raw(" ")];
    spans.extend(line.spans);
    Line::from(spans)
}
