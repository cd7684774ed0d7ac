//! Drawing: `draw(frame, &app)` reads the app and paints every pane. It
//! never changes state; where the panes go comes from `layout.rs`.

use ratatui::Frame;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style, Stylize};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use crate::record::kind_name;

use super::app::{App, View};
use super::controls::inner;
use super::layout::{MIN_HEIGHT, MIN_WIDTH, Pane, too_small};
use super::tree_view;
use super::{details, diagram, help, image_view, steps_view};

pub fn draw(frame: &mut Frame, app: &App) {
    let area = frame.area();
    if too_small(area) {
        draw_too_small(frame, area);
        return;
    }
    let panes = app.panes();
    frame.render_widget(header(app), panes.header);
    draw_image(frame, app, panes.image);
    draw_tree(frame, app, panes.tree);
    draw_steps(frame, app, panes.steps);
    draw_details(frame, app, panes.details);
    let block = pane_block(app, Pane::Diagram, format!(" Ray diagram: {} (d) ", app.plane.name()));
    let block = block.title_bottom(diagram::legend());
    diagram::render(panes.diagram, frame.buffer_mut(), block, &app.scene, &app.tree, app.current, app.plane);
    if let Some(error) = &app.error {
        let block = Block::bordered()
            .border_style(Style::new().fg(Color::Red))
            .title(" Scene error: the last good scene stays; fix the file and save ".bold().red());
        frame.render_widget(Paragraph::new(error.as_str()).red().block(block), panes.banner);
    }
    frame.render_widget(status(app), panes.status);
    if app.help {
        help::draw(frame, area);
    }
}

fn draw_too_small(frame: &mut Frame, area: Rect) {
    let text = format!(
        "The terminal is {}x{}; raystep needs at least {MIN_WIDTH}x{MIN_HEIGHT}.\nEnlarge the window, or press q to quit.",
        area.width, area.height
    );
    let y = area.height / 2;
    let rect = Rect::new(area.x, area.y + y.saturating_sub(1), area.width, 2.min(area.height));
    frame.render_widget(Paragraph::new(text).alignment(Alignment::Center).wrap(Wrap { trim: true }), rect);
}

fn on_off(name: &str, on: bool) -> Span<'static> {
    if on { Span::raw(format!("{name} on")).green() } else { Span::raw(format!("{name} OFF")).red().bold() }
}

fn header(app: &App) -> Line<'static> {
    let settings = &app.scene.settings;
    let s = settings.switches;
    let view = match app.view {
        View::Image => "render".to_string(),
        View::Term(term) => term.name().to_string(),
    };
    let sep = || Span::raw(" · ").dark_gray();
    Line::from(vec![
        Span::raw(" raystep ").bold().reversed(),
        Span::raw(format!(" {} {}x{}", app.source.name(), app.scene.width, app.scene.height)),
        sep(),
        on_off("shadows", s.shadows),
        Span::raw(" "),
        on_off("reflection", s.reflection),
        Span::raw(" "),
        on_off("transmission", s.transmission),
        Span::raw(" "),
        on_off("ambient", s.ambient),
        sep(),
        Span::raw(if app.phong() { "Phong R·V" } else { "Blinn N·H" }),
        sep(),
        Span::raw(format!("depth {}", settings.max_depth)),
        sep(),
        Span::raw(format!("view {view}")),
    ])
}

/// A bordered pane, its border bright when it has the focus.
fn pane_block(app: &App, pane: Pane, title: String) -> Block<'static> {
    let focused = app.focus == pane;
    let style = if focused { Style::new().fg(Color::Cyan).add_modifier(Modifier::BOLD) } else { Style::new() };
    Block::bordered().border_style(style).title(Span::styled(title, style))
}

fn rgb_swatch([r, g, b]: [u8; 3]) -> Span<'static> {
    Span::styled("██", Style::new().fg(Color::Rgb(r, g, b)))
}

fn draw_image(frame: &mut Frame, app: &App, area: Rect) {
    let (x, y) = app.cursor;
    let mut title = vec![Span::raw(format!(" Image · pixel ({x}, {y}) "))];
    if let Some(rgb) = app.shown_pixel(x, y) {
        title.push(Span::raw(format!("rgb ({}, {}, {}) ", rgb[0], rgb[1], rgb[2])));
        title.push(rgb_swatch(rgb));
    }
    title.push(Span::raw(format!(" · zoom {}x ", app.zoom)));
    let mut block = pane_block(app, Pane::Image, String::new()).title(Line::from(title));
    if let View::Term(term) = app.view {
        block = block.title_bottom(term_legend(app, term));
    }
    frame.render_widget(block, area);
    let (Some(view), Some(_)) = (app.image_view(), app.shown_pixel(0, 0)) else {
        let text = match app.progress() {
            Some(p) => format!("rendering… {}/{} rows", p.rows_done, p.rows),
            None => "rendering…".into(),
        };
        frame.render_widget(Paragraph::new(text).alignment(Alignment::Center), inner(area));
        return;
    };
    let pixel = |x: u32, y: u32| app.shown_pixel(x, y).unwrap_or([0, 0, 0]);
    frame.render_widget(image_view::ImageWidget { view, pixel: &pixel, cursor: app.cursor }, area);
    if let Some((column, row, _)) = view.cursor_cell(app.cursor) {
        let marks = [((column, area.y + area.height - 1), "▲"), ((area.x, row), "▶")];
        for (position, mark) in marks {
            if let Some(cell) = frame.buffer_mut().cell_mut(position) {
                cell.set_symbol(mark).set_fg(Color::LightMagenta);
            }
        }
    }
}

/// The term view's legend: what it shows, and the scale of a count view.
fn term_legend(app: &App, term: crate::terms::Term) -> Line<'static> {
    let mut spans = vec![Span::raw(format!(" {}: {} ", term.name(), term.legend()))];
    if let (Some(terms), crate::terms::Term::Rays | crate::terms::Term::Cost) = (&app.terms, term) {
        let max = terms.max_count(term);
        spans.push(Span::raw("0 "));
        for i in 0..8 {
            spans.push(rgb_swatch(crate::terms::false_color(i as f64 / 7.0)));
        }
        spans.push(Span::raw(format!(" {max} ")));
    }
    Line::from(spans)
}

fn draw_tree(frame: &mut Frame, app: &App, area: Rect) {
    let tree = &app.tree;
    let rays = tree.nodes.len();
    let title = format!(" Ray tree · pixel ({}, {}) · {rays} ray{} ", tree.pixel.0, tree.pixel.1, if rays == 1 { "" } else { "s" });
    let block = pane_block(app, Pane::Tree, title);
    let inside = block.inner(area);
    let rows = tree_view::rows(tree, &app.collapsed);
    let selected = tree_view::selected_row(tree, &rows, app.current);
    let first = tree_view::scroll_offset(selected.unwrap_or(0), inside.height as usize);
    let lines: Vec<Line> = rows
        .iter()
        .enumerate()
        .skip(first)
        .take(inside.height as usize)
        .map(|(i, row)| {
            let line = tree_view::row_line(tree, &app.collapsed, row, inside.width as usize);
            if Some(i) == selected { line.patch_style(tree_view::selected_style(app.focus == Pane::Tree)) } else { line }
        })
        .collect();
    frame.render_widget(Paragraph::new(lines).block(block), area);
}

fn draw_steps(frame: &mut Frame, app: &App, area: Rect) {
    let count = app.tree.events.len();
    let mut title = format!(" Step-through · event {} of {count} ", app.current + 1);
    if let Some(object) = app.break_object.and_then(|o| app.scene.objects.get(o)) {
        title.push_str(&format!("· x stops at hits on {} ", object.name));
    }
    let block = pane_block(app, Pane::Steps, title);
    let height = block.inner(area).height as usize;
    let lines = steps_view::lines(&app.tree, &app.scene, app.current, height);
    frame.render_widget(Paragraph::new(lines).block(block), area);
}

fn draw_details(frame: &mut Frame, app: &App, area: Rect) {
    let id = app.selected_node();
    let node = &app.tree.nodes[id];
    let title = format!(" Details · r{id} {} ray ", kind_name(node.kind));
    let block = pane_block(app, Pane::Details, title);
    let inside = block.inner(area);
    let (lines, marked) = details::lines(&app.tree, id, Some(app.current), app.phong(), inside.width as usize);
    let height = inside.height as usize;
    let auto = marked.map_or(0, |m| if m + 4 <= height { 0 } else { m.saturating_sub(1) });
    let most = lines.len().saturating_sub(height);
    let offset = app.details_scroll.map_or(auto, |s| s as usize).min(most);
    frame.render_widget(Paragraph::new(lines).block(block).scroll((offset as u16, 0)), area);
}

fn status(app: &App) -> Line<'static> {
    let mut spans = Vec::new();
    if let Some(p) = app.progress() {
        spans.push(Span::raw(format!(" rendering {}/{} rows ", p.rows_done, p.rows)).black().on_yellow());
    }
    if let Some(message) = &app.message {
        spans.push(Span::raw(format!(" {message} ")).yellow().bold());
    } else if app.show_timings {
        let render = app.render_time.map_or(String::new(), |t| format!(", image in {:.0} ms", t.as_secs_f64() * 1e3));
        spans.push(Span::raw(format!(" pixel traced in {} µs{render} ", app.pick_time.as_micros())).dark_gray());
    }
    spans.push(Span::raw(" ?").bold().cyan());
    spans.push(Span::raw(" help  "));
    for (keys, what) in [("arrows", "pixel"), ("Tab", "pane"), ("n/p", "step"), ("b", "blocked shadow"), ("s r t a", "toggles"), ("v", "view"), ("q", "quit")] {
        spans.push(Span::raw(keys).bold().cyan());
        spans.push(Span::raw(format!(" {what}  ")));
    }
    Line::from(spans)
}
