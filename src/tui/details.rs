//! The details pane: the lines `raystep inspect` prints for the selected ray
//! (the intersection working and every term), a swatch after every colour,
//! and the lines of the current event highlighted.

use glam::DVec3;
use ratatui::style::{Color as TermColor, Modifier, Style};
use ratatui::text::{Line, Span};

use crate::record::{EventKind, NodeId, RayTree, color, kind_name, node_lines, num};

use super::app::App;
use super::layout::Pane;
use super::tree_view::swatch;
use super::ui::pane_block;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::widgets::Paragraph;

/// The text lines of a ray, and which of them the event `at` is about.
pub fn text_lines(tree: &RayTree, id: NodeId, at: Option<usize>) -> (Vec<String>, Vec<usize>) {
    let node = &tree.nodes[id];
    let mut header = format!("r{id}: {} ray, depth {}", kind_name(node.kind), node.depth);
    if node.parent.is_some() {
        header.push_str(&format!(", weight {}", num(node.weight)));
    }
    let mut lines = vec![header];
    let mut body = node_lines(tree, id);
    let children: Vec<String> = tree
        .children(id)
        .map(|c| {
            let child = &tree.nodes[c];
            format!(
                "{} ray r{c} adds {}",
                kind_name(child.kind),
                color(child.contribution)
            )
        })
        .collect();
    let colour_line = body
        .iter()
        .position(|l| l.starts_with("colour "))
        .unwrap_or(body.len());
    body.splice(colour_line..colour_line, children);
    lines.extend(body);
    let event = at.and_then(|i| tree.events.get(i)).filter(|e| e.node == id);
    let marked = event.map_or(Vec::new(), |e| marked_lines(tree, &lines, &e.kind));
    (lines, marked)
}

/// The lines an event is about: a line, with its indented continuation.
fn marked_lines(tree: &RayTree, lines: &[String], kind: &EventKind) -> Vec<usize> {
    let start = |prefix: &str, nth: usize| {
        lines
            .iter()
            .enumerate()
            .filter(|(_, l)| l.starts_with(prefix))
            .nth(nth)
            .map(|(i, _)| i)
    };
    let first = match kind {
        EventKind::RayCast { .. } => start("from ", 0),
        EventKind::Hit { .. } => start("hit ", 0),
        EventKind::Miss { .. } => start("missed ", 0),
        EventKind::Ambient { .. } => start("ambient ", 0),
        EventKind::ShadowCast { light }
        | EventKind::Blocker { light, .. }
        | EventKind::Light { light, .. } => {
            let node = lines_node(tree, lines);
            let nth = node.and_then(|n| {
                tree.nodes[n]
                    .lights
                    .iter()
                    .position(|l| l.light_index == *light)
            });
            nth.and_then(|n| start("light ", n))
        }
        EventKind::Refraction { .. } => start("refraction", 0),
        EventKind::ChildReturned { child, .. } => lines
            .iter()
            .position(|l| l.contains(&format!(" ray r{child} adds "))),
        EventKind::NotCast(ray) => start(&format!("{} ray not cast", kind_name(ray.kind)), 0),
        EventKind::RayDone { .. } => start("colour ", 0),
    };
    let Some(first) = first else {
        return Vec::new();
    };
    let rest = lines[first + 1..]
        .iter()
        .take_while(|l| l.starts_with("  "))
        .count();
    (first..=first + rest).collect()
}

/// The node whose lines these are, from the header `rN: ...`.
fn lines_node(tree: &RayTree, lines: &[String]) -> Option<NodeId> {
    let id: NodeId = lines
        .first()?
        .strip_prefix('r')?
        .split(':')
        .next()?
        .parse()
        .ok()?;
    (id < tree.nodes.len()).then_some(id)
}

/// `(r, g, b)` with three decimals each, as `record::color` writes colours.
fn parse_color(token: &str) -> Option<DVec3> {
    let inner = token
        .strip_prefix('(')?
        .trim_end_matches([',', ':'])
        .strip_suffix(')')?;
    let parts: Vec<&str> = inner.split(", ").collect();
    let three_decimals = |p: &&str| p.split_once('.').is_some_and(|(_, d)| d.len() == 3);
    if parts.len() != 3 || !parts.iter().all(three_decimals) {
        return None;
    }
    let v: Vec<f64> = parts.iter().filter_map(|p| p.parse().ok()).collect();
    (v.len() == 3).then(|| DVec3::new(v[0], v[1], v[2]))
}

/// Words, keeping a parenthesised group such as a colour in one piece.
fn tokens(text: &str) -> Vec<String> {
    let mut tokens: Vec<String> = Vec::new();
    let mut open = false;
    for word in text.split(' ') {
        match tokens.last_mut() {
            Some(last) if open => {
                last.push(' ');
                last.push_str(word);
            }
            _ => tokens.push(word.to_string()),
        }
        let last = tokens.last().map_or("", |s| s.as_str());
        open = last.matches('(').count() > last.matches(')').count();
    }
    tokens
}

/// One text line wrapped to `width`, with swatches, continuation indented.
fn wrap(text: &str, width: usize, style: Style) -> Vec<Line<'static>> {
    let indent = text.len() - text.trim_start().len() + 4;
    let mut lines = Vec::new();
    let mut spans: Vec<Span<'static>> = Vec::new();
    let mut used = 0;
    for (i, token) in tokens(text).into_iter().enumerate() {
        let swatch_color = parse_color(&token);
        let len = token.chars().count() + if swatch_color.is_some() { 3 } else { 0 };
        if i > 0 && used + 1 + len > width && used > indent {
            lines.push(Line::from(std::mem::take(&mut spans)).style(style));
            spans.push(Span::raw(" ".repeat(indent)));
            used = indent;
        } else if i > 0 {
            spans.push(Span::raw(" "));
            used += 1;
        }
        spans.push(Span::raw(token));
        if let Some(c) = swatch_color {
            spans.push(Span::raw(" "));
            spans.push(swatch(c));
        }
        used += len;
    }
    lines.push(Line::from(spans).style(style));
    lines
}

/// The pane's lines wrapped to `width`, and the first line of the marked part.
pub fn lines(
    tree: &RayTree,
    id: NodeId,
    at: Option<usize>,
    width: usize,
) -> (Vec<Line<'static>>, Option<usize>) {
    let (text, marked) = text_lines(tree, id, at);
    let mut out = Vec::new();
    let mut first_marked = None;
    for (i, line) in text.iter().enumerate() {
        let style = if marked.contains(&i) {
            first_marked.get_or_insert(out.len());
            Style::new()
                .fg(TermColor::Yellow)
                .add_modifier(Modifier::BOLD)
        } else if i == 0 {
            Style::new().add_modifier(Modifier::BOLD)
        } else {
            Style::new()
        };
        out.extend(wrap(line, width.max(20), style));
    }
    (out, first_marked)
}

pub fn draw(frame: &mut Frame, app: &App, area: Rect) {
    let id = app.selected_node();
    let node = &app.tree.nodes[id];
    let title = format!(" Details · r{id} {} ray ", kind_name(node.kind));
    let block = pane_block(app, Pane::Details, title);
    let inside = block.inner(area);
    let (lines, marked) = lines(&app.tree, id, Some(app.current), inside.width as usize);
    let height = inside.height as usize;
    let auto = marked.map_or(0, |m| {
        if m + 4 <= height {
            0
        } else {
            m.saturating_sub(1)
        }
    });
    let most = lines.len().saturating_sub(height);
    let offset = app.details_scroll.map_or(auto, |s| s as usize).min(most);
    frame.render_widget(
        Paragraph::new(lines)
            .block(block)
            .scroll((offset as u16, 0)),
        area,
    );
}
