//! Drawing: `draw(frame, &app)` reads the app and paints every pane. It
//! never changes state; where the panes go comes from `layout.rs`.

use ratatui::Frame;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style, Stylize};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use super::app::{App, View};
use super::layout::{MIN_HEIGHT, MIN_WIDTH, Pane, too_small};
use super::{details, diagram, help, image_pane, keymap, steps_view, tree_view};

pub fn draw(frame: &mut Frame, app: &App) {
    let area = frame.area();
    if too_small(area) {
        draw_too_small(frame, area);
        return;
    }
    let panes = app.panes();
    frame.render_widget(header(app, area.width), panes.header);
    image_pane::draw(frame, app, panes.image);
    tree_view::draw(frame, app, panes.tree);
    steps_view::draw(frame, app, panes.steps);
    details::draw(frame, app, panes.details);
    let block = pane_block(
        app,
        Pane::Diagram,
        format!(" Diagram · {} · white: current ", app.plane().name()),
    );
    let block = block.title_bottom(diagram::legend());
    diagram::render(
        panes.diagram,
        frame.buffer_mut(),
        block,
        app.scene(),
        app.tree(),
        app.current(),
        app.plane(),
    );
    if let Some(error) = app.error() {
        let block = Block::bordered()
            .border_style(Style::new().fg(Color::Red))
            .title(
                " Scene error: the last good scene stays; fix the file and save "
                    .bold()
                    .red(),
            );
        frame.render_widget(Paragraph::new(error).red().block(block), panes.banner);
    }
    frame.render_widget(status(app), panes.status);
    if app.help() {
        help::draw(frame, area, app.help_scroll());
    }
}

fn draw_too_small(frame: &mut Frame, area: Rect) {
    let text = format!(
        "The terminal is {}x{}; raystep needs at least {MIN_WIDTH}x{MIN_HEIGHT}.\nEnlarge the window, or press q to quit.",
        area.width, area.height
    );
    let y = area.height / 2;
    let rect = Rect::new(
        area.x,
        area.y + y.saturating_sub(1),
        area.width,
        2.min(area.height),
    );
    frame.render_widget(
        Paragraph::new(text)
            .alignment(Alignment::Center)
            .wrap(Wrap { trim: true }),
        rect,
    );
}

/// A switch's name: plain green when on, "no ..." in red when off.
fn on_off(name: &str, on: bool) -> Span<'static> {
    if on {
        Span::raw(name.to_string()).green()
    } else {
        Span::raw(format!("no {name}")).red().bold()
    }
}

/// The top line: the scene (shortened first when space is short) and the
/// model's settings as the toggles left them.
fn header(app: &App, width: u16) -> Line<'static> {
    let settings = app.settings();
    let s = settings.switches;
    let sep = || Span::raw(" · ").dark_gray();
    let mut right = vec![
        sep(),
        on_off("shadows", s.shadows),
        Span::raw(" "),
        on_off("reflection", s.reflection),
        Span::raw(" "),
        on_off("transmission", s.transmission),
        Span::raw(" "),
        on_off("ambient", s.ambient),
        sep(),
        Span::raw(if app.phong() { "Phong" } else { "Blinn" }),
        sep(),
        Span::raw(format!("depth {}", settings.max_depth)),
    ];
    if let View::Term(term) = app.view() {
        right.extend([
            sep(),
            Span::raw(format!("view: {}", term.name())).bold().yellow(),
        ]);
    }
    let used: usize = 9 + right.iter().map(|s| s.width()).sum::<usize>();
    let scene = format!(
        " {} {}x{}",
        app.source().name(),
        app.scene().width,
        app.scene().height
    );
    let room = (width as usize).saturating_sub(used);
    let scene = if scene.chars().count() <= room {
        scene
    } else {
        let tail: String = scene
            .chars()
            .rev()
            .take(room.saturating_sub(2))
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        format!(" …{tail}")
    };
    let mut spans = vec![Span::raw(" raystep ").bold().reversed(), Span::raw(scene)];
    spans.extend(right);
    Line::from(spans)
}

/// A bordered pane, its border bright when it has the focus.
pub(super) fn pane_block(app: &App, pane: Pane, title: String) -> Block<'static> {
    let focused = app.focus() == pane;
    let style = if focused {
        Style::new().fg(Color::Cyan).add_modifier(Modifier::BOLD)
    } else {
        Style::new()
    };
    Block::bordered()
        .border_style(style)
        .title(Span::styled(title, style))
}

fn status(app: &App) -> Line<'static> {
    let mut spans = Vec::new();
    if let Some(p) = app.progress() {
        spans.push(
            Span::raw(format!(" rendering {}/{} rows ", p.rows_done, p.rows))
                .black()
                .on_yellow(),
        );
    }
    if let Some(message) = app.message() {
        spans.push(Span::raw(format!(" {message} ")).yellow().bold());
    } else if app.show_timings() {
        let render = app.render_time().map_or(String::new(), |t| {
            format!(", image in {:.0} ms", t.as_secs_f64() * 1e3)
        });
        spans.push(
            Span::raw(format!(
                " pixel traced in {} µs{render} ",
                app.pick_time().as_micros()
            ))
            .dark_gray(),
        );
    }
    spans.push(Span::raw(" "));
    for hint in keymap::hints() {
        spans.push(Span::raw(hint.keys).bold().cyan());
        spans.push(Span::raw(format!(" {}  ", hint.what)));
    }
    Line::from(spans)
}
