//! Where the image's pixels land in the image pane: half-block cells (▀: the
//! foreground is the upper display pixel, the background the lower one),
//! scaled to fit or zoomed around the cursor down to one image pixel per
//! half cell. The same mapping draws the image and turns clicks into pixels.
//!
//! Coordinates are always the scene image's own pixels (those `raystep
//! inspect --pixel X,Y` takes); display pixels only sample them.

use ratatui::layout::Rect;

/// The grid of display pixels the image pane shows: which image pixel each
/// samples and which screen cell holds it, at one zoom around the cursor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageGrid {
    pub area: Rect,
    /// Image pixels per display pixel, at least 1.
    pub scale: f64,
    /// The image point at the top-left corner of the shown part.
    pub origin: (f64, f64),
    /// Display pixels shown (width, height); a cell holds two rows.
    pub(crate) shown: (u32, u32),
    /// Cells left empty before the image, to centre it.
    pub(crate) offset: (u16, u16),
    pub(crate) image: (u32, u32),
}

/// Image pixels per display pixel when the whole image fits the area.
pub(crate) fn fit_scale(area: Rect, image: (u32, u32)) -> f64 {
    let (cols, rows) = (area.width.max(1) as f64, 2.0 * area.height.max(1) as f64);
    (image.0 as f64 / cols).max(image.1 as f64 / rows)
}

/// The largest useful zoom: one image pixel per display pixel.
pub(crate) fn max_zoom(area: Rect, image: (u32, u32)) -> u32 {
    let mut zoom = 1;
    while fit_scale(area, image) / zoom as f64 > 1.0 && zoom < 1 << 16 {
        zoom *= 2;
    }
    zoom
}

impl ImageGrid {
    pub(crate) fn new(area: Rect, image: (u32, u32), zoom: u32, cursor: (u32, u32)) -> Self {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// 10 x 5 cells: 10 x 10 display pixels (two per cell, one above the other).
    const AREA: Rect = Rect::new(2, 3, 10, 5);

    #[test]
    fn a_square_image_fills_the_area_two_pixels_a_side() {
        // 20 x 20 pixels in 10 x 10 display pixels: 2 per display pixel.
        let grid = ImageGrid::new(AREA, (20, 20), 1, (0, 0));
        assert_eq!(fit_scale(AREA, (20, 20)), 2.0);
        assert_eq!(
            (grid.scale, grid.shown, grid.offset),
            (2.0, (10, 10), (0, 0))
        );
        // A display pixel samples the image at its centre: 0.5 x 2 = 1.
        assert_eq!(grid.sample(0, 0), (1, 1));
        assert_eq!(grid.sample(9, 9), (19, 19));
        // Cell (3, 2) inside the area holds display pixels (3, 4) and (3, 5);
        // its upper half samples (3.5 x 2, 4.5 x 2) = (7, 9).
        assert_eq!(grid.pixel_at_cell(5, 5), Some((7, 9)));
        assert_eq!(grid.cursor_cell((7, 9)), Some((5, 5, true)));
        assert_eq!(grid.cursor_cell((7, 11)), Some((5, 5, false)), "lower half");
        assert_eq!(grid.pixel_at_cell(1, 5), None, "left of the area");
    }

    #[test]
    fn zooming_in_centres_the_cursor_down_to_one_pixel_each() {
        // Scale 2 at zoom 1, so zoom 2 is one image pixel per display pixel.
        assert_eq!(max_zoom(AREA, (20, 20)), 2);
        let grid = ImageGrid::new(AREA, (20, 20), 2, (15, 15));
        assert_eq!(grid.scale, 1.0);
        // 10 of the 20 pixels show, centred on 15.5 but kept inside: 10..20.
        assert_eq!(grid.origin, (10.0, 10.0));
        assert_eq!(grid.sample(0, 0), (10, 10));
        assert_eq!(grid.display_of((9, 15)), None, "scrolled out of view");
    }

    #[test]
    fn a_wide_image_is_centred_vertically() {
        // 40 x 10: scale max(40 / 10, 10 / 10) = 4, so 10 x 3 display
        // pixels (⌈10 / 4⌉ = 3), 2 cells tall, 1 cell down from the top of 5.
        let grid = ImageGrid::new(AREA, (40, 10), 1, (0, 0));
        assert_eq!((grid.shown, grid.offset), ((10, 3), (0, 1)));
        assert_eq!(grid.pixel_at_cell(2, 3), None, "the empty row above");
        assert_eq!(grid.pixel_at_cell(2, 4), Some((2, 2)));
    }
}
