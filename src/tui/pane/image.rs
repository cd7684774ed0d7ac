//! The image pane: its picture (the render, a term image, yours or the
//! error map) with the pixel cursor, the selected pixel's coordinates and
//! colour in the title, and a term image's legend at the bottom.

use ratatui::Frame;
use ratatui::buffer::Buffer;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Stylize};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};

use raystep_engine::record::{color, num};
use raystep_engine::terms::{Term, false_color};

use super::pane_block;
use crate::tui::view::image_grid::ImageGrid;
use crate::tui::view::layout::inner;
use crate::tui::view::mistakes_menu;
use crate::tui::view::tree::rgb_swatch;
use crate::tui::{App, Pane, Picture};

pub(crate) fn draw(frame: &mut Frame, app: &App, area: Rect) {
    let (x, y) = app.pixel().cursor();
    let mut title = vec![Span::raw(format!(" Pixel ({x}, {y}) "))];
    // In "yours" the colour is the student's, and says so; else ours.
    let (whose, rgb) = match app.screen().picture() {
        Picture::Yours => ("yours ", app.shown_pixel(x, y)),
        _ => ("", app.our_pixel()),
    };
    if let Some(rgb) = rgb {
        title.push(Span::raw(format!(
            "{whose}rgb({},{},{}) ",
            rgb[0], rgb[1], rgb[2]
        )));
        title.push(rgb_swatch(rgb));
    }
    title.push(Span::raw(format!(" zoom {}x ", app.screen().zoom())));
    let mut block = pane_block(app, Pane::Image, String::new()).title(Line::from(title));
    // The legend keeps its place at the right; the compare line takes the
    // room left of it, dropping whole items rather than cutting a word.
    let mut room = (area.width as usize).saturating_sub(2);
    if let Picture::Term(term) = app.screen().picture() {
        let legend = term_legend(app, term);
        room = room.saturating_sub(legend.width() + 1);
        block = block.title_bottom(legend.right_aligned());
    }
    if let Some(c) = app.comparison().map(|c| c.findings()) {
        // The ranking stays in sight while comparing, whatever the picture.
        if let Some(line) = mistakes_menu::compare_line(&c.mistakes, c.matches, room) {
            block = block.title_bottom(Line::from(line).bold().yellow());
        }
    }
    frame.render_widget(block, area);
    let (Some(grid), Some(_)) = (app.image_grid(), app.shown_pixel(0, 0)) else {
        let text = match app.renders().progress() {
            Some(p) => format!("rendering… {}/{} rows", p.rows_done, p.rows),
            None => "rendering…".into(),
        };
        frame.render_widget(
            Paragraph::new(text).alignment(Alignment::Center),
            inner(area),
        );
        return;
    };
    let pixel = |x: u32, y: u32| app.shown_pixel(x, y).unwrap_or([0, 0, 0]);
    frame.render_widget(
        ImageWidget {
            grid,
            pixel: &pixel,
            cursor: app.pixel().cursor(),
        },
        area,
    );
    if let Some((column, row, _)) = grid.cursor_cell(app.pixel().cursor()) {
        // Marks on the border point at the cursor's column and row.
        let marks = [
            ((column, area.y + area.height - 1), "▲", "─"),
            ((area.x, row), "▶", "│"),
        ];
        for (position, mark, border) in marks {
            if let Some(cell) = frame
                .buffer_mut()
                .cell_mut(position)
                .filter(|c| c.symbol() == border)
            {
                cell.set_symbol(mark).set_fg(Color::LightMagenta);
            }
        }
    }
}

/// A term image's legend: the term's name, the selected pixel's value,
/// and the scale of a count image (rays, cost).
fn term_legend(app: &App, term: Term) -> Line<'static> {
    let Some(terms) = app.renders().terms() else {
        return Line::raw(format!(" {}: rendering… ", term.name()));
    };
    let (x, y) = app.pixel().cursor();
    let index = (x < terms.width && y < terms.height).then_some((y * terms.width + x) as usize);
    let here = index
        .and_then(|i| terms.pixels.get(i))
        .map_or(String::new(), |p| match term {
            Term::Ambient => color(p.ambient),
            Term::Emission => color(p.emission),
            Term::Diffuse => color(p.diffuse),
            Term::Specular => color(p.specular),
            Term::Reflected => color(p.reflected),
            Term::Transmitted => color(p.transmitted),
            Term::Shadow => p
                .shadow
                .map_or("no light faces it".into(), |s| format!("S = {}", num(s))),
            Term::Rays => p.rays.to_string(),
            Term::Cost => p.cost.to_string(),
        });
    let mut spans = vec![Span::raw(format!(" {}: {here} ", term.name())).bold()];
    if matches!(term, Term::Rays | Term::Cost) {
        // Apart from the value here, so "2" and the scale's "0" never run together.
        spans.push(Span::raw("· scale: 0 ").dark_gray());
        for i in 0..8 {
            spans.push(rgb_swatch(false_color(i as f64 / 7.0)));
        }
        spans.push(Span::raw(format!(" {} ", app.renders().count_max(term))));
    }
    Line::from(spans)
}

/// The half-block drawing of an image through its grid, with the cursor.
pub(crate) struct ImageWidget<'a> {
    pub(crate) grid: ImageGrid,
    pub(crate) pixel: &'a dyn Fn(u32, u32) -> [u8; 3],
    pub(crate) cursor: (u32, u32),
}

/// The cursor's colour: one that stands out against the pixel under it.
fn cursor_color(under: [u8; 3]) -> Color {
    let luma = 0.3 * under[0] as f64 + 0.59 * under[1] as f64 + 0.11 * under[2] as f64;
    if luma > 140.0 {
        Color::Rgb(200, 0, 160)
    } else {
        Color::Rgb(255, 90, 255)
    }
}

impl Widget for ImageWidget<'_> {
    fn render(self, _area: Rect, buf: &mut Buffer) {
        let grid = self.grid;
        let rgb = |[r, g, b]: [u8; 3]| Color::Rgb(r, g, b);
        let cursor = grid.display_of(self.cursor);
        for dy in (0..grid.shown.1).step_by(2) {
            for dx in 0..grid.shown.0 {
                let color_at = |dy: u32| {
                    let (x, y) = grid.sample(dx, dy);
                    let color = (self.pixel)(x, y);
                    if cursor == Some((dx, dy)) {
                        cursor_color(color)
                    } else {
                        rgb(color)
                    }
                };
                let upper = color_at(dy);
                let lower = if dy + 1 < grid.shown.1 {
                    color_at(dy + 1)
                } else {
                    Color::Reset
                };
                let position = (
                    grid.area.x + grid.offset.0 + dx as u16,
                    grid.area.y + grid.offset.1 + (dy / 2) as u16,
                );
                if let Some(cell) = buf.cell_mut(position) {
                    cell.set_symbol("▀").set_fg(upper).set_bg(lower);
                }
            }
        }
    }
}
