//! The image pane: the render drawn with half-block cells (▀: the foreground
//! is the upper display pixel, the background the lower one), scaled to fit
//! or zoomed around the cursor down to one image pixel per half cell.
//!
//! Coordinates are always the scene image's own pixels (those `raystep
//! inspect --pixel X,Y` takes); display pixels only sample them.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::Widget;

/// How the image maps onto a pane's inner area at one zoom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageView {
    pub area: Rect,
    /// Image pixels per display pixel, at least 1.
    pub scale: f64,
    /// The image point at the top-left corner of the shown part.
    pub origin: (f64, f64),
    /// Display pixels shown (width, height); a cell holds two rows.
    pub shown: (u32, u32),
    /// Cells left empty before the image, to centre it.
    pub offset: (u16, u16),
    pub image: (u32, u32),
}

/// Image pixels per display pixel when the whole image fits the area.
pub fn fit_scale(area: Rect, image: (u32, u32)) -> f64 {
    let (cols, rows) = (area.width.max(1) as f64, 2.0 * area.height.max(1) as f64);
    (image.0 as f64 / cols).max(image.1 as f64 / rows)
}

/// The largest useful zoom: one image pixel per display pixel.
pub fn max_zoom(area: Rect, image: (u32, u32)) -> u32 {
    let mut zoom = 1;
    while fit_scale(area, image) / zoom as f64 > 1.0 && zoom < 1 << 16 {
        zoom *= 2;
    }
    zoom
}

impl ImageView {
    pub fn new(area: Rect, image: (u32, u32), zoom: u32, cursor: (u32, u32)) -> Self {
        let scale = (fit_scale(area, image) / zoom.max(1) as f64).max(1.0);
        let (cols, rows) = (area.width as u32, 2 * area.height as u32);
        let shown_w = cols.min((image.0 as f64 / scale).ceil() as u32);
        let shown_h = rows.min((image.1 as f64 / scale).ceil() as u32);
        let axis = |size: u32, shown: u32, cursor: u32| {
            let span = shown as f64 * scale;
            if span >= size as f64 {
                0.0
            } else {
                (cursor as f64 + 0.5 - span / 2.0)
                    .clamp(0.0, size as f64 - span)
                    .floor()
            }
        };
        let origin = (
            axis(image.0, shown_w, cursor.0),
            axis(image.1, shown_h, cursor.1),
        );
        let offset = (
            ((cols - shown_w) / 2) as u16,
            ((area.height as u32 - shown_h.div_ceil(2)) / 2) as u16,
        );
        Self {
            area,
            scale,
            origin,
            shown: (shown_w, shown_h),
            offset,
            image,
        }
    }

    /// The image pixel a display pixel shows.
    pub fn sample(&self, dx: u32, dy: u32) -> (u32, u32) {
        let x = (self.origin.0 + (dx as f64 + 0.5) * self.scale).floor() as u32;
        let y = (self.origin.1 + (dy as f64 + 0.5) * self.scale).floor() as u32;
        (x.min(self.image.0 - 1), y.min(self.image.1 - 1))
    }

    /// The display pixel that holds an image pixel, if it is shown.
    pub fn display_of(&self, pixel: (u32, u32)) -> Option<(u32, u32)> {
        let dx = (pixel.0 as f64 + 0.5 - self.origin.0) / self.scale;
        let dy = (pixel.1 as f64 + 0.5 - self.origin.1) / self.scale;
        let inside = dx >= 0.0 && dy >= 0.0 && dx < self.shown.0 as f64 && dy < self.shown.1 as f64;
        inside.then_some((dx as u32, dy as u32))
    }

    /// The image pixel under a screen cell (its upper half), if any.
    pub fn pixel_at_cell(&self, column: u16, row: u16) -> Option<(u32, u32)> {
        let left = self.area.x + self.offset.0;
        let top = self.area.y + self.offset.1;
        if column < left || row < top {
            return None;
        }
        let (dx, dy) = ((column - left) as u32, 2 * (row - top) as u32);
        (dx < self.shown.0 && dy < self.shown.1).then(|| self.sample(dx, dy))
    }

    /// The screen cell that holds the cursor, and whether it is the upper half.
    pub fn cursor_cell(&self, cursor: (u32, u32)) -> Option<(u16, u16, bool)> {
        let (dx, dy) = self.display_of(cursor)?;
        Some((
            self.area.x + self.offset.0 + dx as u16,
            self.area.y + self.offset.1 + (dy / 2) as u16,
            dy % 2 == 0,
        ))
    }
}

/// The half-block drawing of an image through a view, with the cursor.
pub struct ImageWidget<'a> {
    pub view: ImageView,
    pub pixel: &'a dyn Fn(u32, u32) -> [u8; 3],
    pub cursor: (u32, u32),
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
        let view = self.view;
        let rgb = |[r, g, b]: [u8; 3]| Color::Rgb(r, g, b);
        let cursor = view.display_of(self.cursor);
        for dy in (0..view.shown.1).step_by(2) {
            for dx in 0..view.shown.0 {
                let color_at = |dy: u32| {
                    let (x, y) = view.sample(dx, dy);
                    let color = (self.pixel)(x, y);
                    if cursor == Some((dx, dy)) {
                        cursor_color(color)
                    } else {
                        rgb(color)
                    }
                };
                let upper = color_at(dy);
                let lower = if dy + 1 < view.shown.1 {
                    color_at(dy + 1)
                } else {
                    Color::Reset
                };
                let position = (
                    view.area.x + view.offset.0 + dx as u16,
                    view.area.y + view.offset.1 + (dy / 2) as u16,
                );
                if let Some(cell) = buf.cell_mut(position) {
                    cell.set_symbol("▀").set_fg(upper).set_bg(lower);
                }
            }
        }
    }
}
