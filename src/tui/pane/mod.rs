//! Drawing: `draw(frame, &app)` reads the app and paints every pane. It
//! never changes state; where the panes go comes from `view::layout`, and
//! what they say from the rest of `view/`. One file per pane.

mod bars;
pub mod details;
pub(crate) mod diagram;
pub(crate) mod help;
pub(crate) mod image;
pub(crate) mod mistakes_menu;
pub(crate) mod steps;
pub(crate) mod tree;

use ratatui::Frame;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style, Stylize};
use ratatui::text::Span;
use ratatui::widgets::{Block, Paragraph, Wrap};

use super::action::Pane;
use super::app::{App, Overlay};
use super::view::layout::{MIN_HEIGHT, MIN_WIDTH, too_small};

pub fn draw(frame: &mut Frame, app: &App) {
    let area = frame.area();
    if too_small(area) {
        draw_too_small(frame, area);
        return;
    }
    let panes = app.panes();
    frame.render_widget(bars::header(app, area.width), panes.header);
    image::draw(frame, app, panes.image);
    tree::draw(frame, app, panes.tree);
    steps::draw(frame, app, panes.steps);
    details::draw(frame, app, panes.details);
    let block = pane_block(
        app,
        Pane::Diagram,
        format!(
            " Diagram · {}{} · white: current ",
            app.screen().plane().name(),
            (app.screen().diagram_pan_zoom().label()).map_or(String::new(), |z| format!(" · {z}"))
        ),
    );
    diagram::render(panes.diagram, frame.buffer_mut(), block, app);
    if let Some(error) = app.session().error() {
        let block = Block::bordered()
            .border_style(Style::new().fg(Color::Red))
            .title(
                " Scene error: the last good scene stays; fix the file and save "
                    .bold()
                    .red(),
            );
        frame.render_widget(Paragraph::new(error).red().block(block), panes.banner);
    }
    frame.render_widget(bars::status(app), panes.status);
    // The prompt and `f` speak in the status line; these two draw over the panes.
    if let Some(selected) = app.overlay().menu_row() {
        mistakes_menu::draw(frame, app, area, selected);
    }
    if let Some(Overlay::Help { scroll }) = app.overlay().open() {
        help::draw(frame, area, *scroll);
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

/// A bordered pane, its border bright when it has the focus.
fn pane_block(app: &App, pane: Pane, title: String) -> Block<'static> {
    let focused = app.screen().focus() == pane;
    let style = if focused {
        Style::new().fg(Color::Cyan).add_modifier(Modifier::BOLD)
    } else {
        Style::new()
    };
    Block::bordered()
        .border_style(style)
        .title(Span::styled(title, style))
}
