//! The diagram pane's rays, thinned before ratatui rasterises them. A tree
//! of 65,536 rays (max_rays, MODEL §5) bounces over and over along the same
//! few lines: on a 200x60 screen most of its segments paint exactly the
//! Braille dots another one paints, and rasterising each was most of a
//! frame. For a view (the window of the plane shown and the cells it fills)
//! this works out once which segments paint the same line of dots; each
//! frame then draws only the last of each, the one whose colour would win
//! anyway, and none that falls outside the window.
//!
//! Exact, not an approximation: ratatui's `canvas::Line` clips a segment to
//! the window (Cohen-Sutherland, the `line-clipping` crate), rounds both
//! ends to dots (`Painter::get_point`) and joins them by Bresenham, whose
//! dots depend only on the two ends, in either order. Done here with the
//! same crate and the same arithmetic, two segments with the same pair of
//! ends paint the same dots; a Braille cell is the union of the dots
//! painted in it, coloured by the last segment to paint one, so leaving
//! out each earlier twin changes no cell. Kept segments are drawn as they
//! are (ratatui clips them again, as before), so the dots are its own.

use std::collections::HashMap;

use glam::DVec2;
use line_clipping::cohen_sutherland::clip_line;
use line_clipping::{LineSegment, Point, Window};

/// What the canvas draws into: the window of the plane (`x`, `y`, as
/// `Canvas::x_bounds`/`y_bounds`) and the cells of the drawing area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct View {
    pub(crate) x: [f64; 2],
    pub(crate) y: [f64; 2],
    pub(crate) cells: (u16, u16),
}

/// A segment's dots: its two ends on the Braille grid, in order.
type Ends = ((usize, usize), (usize, usize));

/// The segments of one diagram, grouped for one view.
#[derive(Debug)]
pub(crate) struct CanvasLines {
    view: View,
    /// Per segment, the line of dots it paints (an index shared by its
    /// twins), or `OUTSIDE`.
    line: Vec<u32>,
    lines: usize,
}

/// A segment that paints no dot in the window.
const OUTSIDE: u32 = u32::MAX;

impl CanvasLines {
    /// Groups `segments` (their ends on the plane, in drawing order) by the
    /// dots they paint in `view`.
    pub(crate) fn new(segments: impl Iterator<Item = (DVec2, DVec2)>, view: View) -> Self {
        let mut ids: HashMap<Ends, u32> = HashMap::new();
        let line = segments
            .map(|(from, to)| match ends(from, to, view) {
                Some(ends) => {
                    let next = ids.len() as u32;
                    *ids.entry(ends).or_insert(next)
                }
                None => OUTSIDE,
            })
            .collect();
        CanvasLines {
            view,
            line,
            lines: ids.len(),
        }
    }

    /// The view these lines were grouped for.
    pub(crate) fn view(&self) -> View {
        self.view
    }

    /// How many distinct lines of dots the segments paint.
    #[cfg(test)]
    pub(crate) fn lines(&self) -> usize {
        self.lines
    }

    /// The segments to draw, in drawing order, for one layer: of those
    /// `in_layer` says belong to it, the last one painting each line of
    /// dots, none outside the window.
    pub(crate) fn kept(&self, in_layer: impl Fn(usize) -> bool) -> Vec<usize> {
        let mut last = vec![OUTSIDE; self.lines];
        let mut count = 0;
        for (i, &line) in self.line.iter().enumerate() {
            if line != OUTSIDE && in_layer(i) {
                let slot = &mut last[line as usize];
                count += usize::from(*slot == OUTSIDE);
                *slot = i as u32;
            }
        }
        let mut kept = Vec::with_capacity(count);
        kept.extend(
            (self.line.iter().enumerate())
                .filter(|&(i, &line)| line != OUTSIDE && last[line as usize] == i as u32)
                .map(|(i, _)| i),
        );
        kept
    }
}

/// The dots a segment from `a` to `b` paints in `view`, as ratatui works
/// them out (`canvas::Line::draw`): clipped to the window, each end rounded
/// to a dot; `None` when it paints none. The ends come in a fixed order:
/// Bresenham's dots do not depend on it.
fn ends(a: DVec2, b: DVec2, view: View) -> Option<Ends> {
    let ([left, right], [bottom, top]) = (view.x, view.y);
    let clipped = clip_line(
        LineSegment::new(Point::new(a.x, a.y), Point::new(b.x, b.y)),
        Window::new(left, right, bottom, top),
    )?;
    // A Braille cell is 2 dots wide and 4 tall (`PatternGrid::resolution`).
    let resolution = (f64::from(view.cells.0) * 2.0, f64::from(view.cells.1) * 4.0);
    // `Painter::get_point`, to the letter.
    let dot = |x: f64, y: f64| {
        if x < left || x > right || y < bottom || y > top {
            return None;
        }
        let (width, height) = (right - left, top - bottom);
        if width <= 0.0 || height <= 0.0 {
            return None;
        }
        let x = ((x - left) * (resolution.0 - 1.0) / width).round() as usize;
        let y = ((top - y) * (resolution.1 - 1.0) / height).round() as usize;
        Some((x, y))
    };
    let p = dot(clipped.p1.x, clipped.p1.y)?;
    let q = dot(clipped.p2.x, clipped.p2.y)?;
    Some((p.min(q), p.max(q)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const VIEW: View = View {
        x: [0.0, 10.0],
        y: [0.0, 10.0],
        cells: (10, 5),
    };

    #[test]
    fn twins_are_grouped_whatever_their_direction() {
        // A 10x5-cell view of [0, 10]²: 20x20 dots, 19/10 dot per unit.
        // (1, 1)-(9, 9) and its reverse paint one line; a segment a
        // hundredth of a unit off rounds to the same dots (0.019 of a dot);
        // (1, 2)-(9, 9) starts 1.9 dots higher: another line.
        let p = |x, y| DVec2::new(x, y);
        let segments = [
            (p(1.0, 1.0), p(9.0, 9.0)),
            (p(9.0, 9.0), p(1.0, 1.0)),
            (p(1.01, 1.0), p(9.0, 9.0)),
            (p(1.0, 2.0), p(9.0, 9.0)),
            // Wholly outside, left of the window.
            (p(-5.0, 1.0), p(-1.0, 9.0)),
        ];
        let lines = CanvasLines::new(segments.into_iter(), VIEW);
        assert_eq!(lines.lines(), 2);
        assert_eq!(lines.kept(|_| true), vec![2, 3]);
        // Another layer's segments are left to it: without 2, 1 is the last.
        assert_eq!(lines.kept(|i| i != 2), vec![1, 3]);
        assert_eq!(lines.kept(|i| i == 4), Vec::<usize>::new());
    }

    #[test]
    fn ends_are_clipped_to_the_window_first() {
        // From (-10, 5) to (20, 5): clipped to (0, 5)-(10, 5), so dots
        // x = 0 and 19, y = round((10 - 5) * 19 / 10) = round(9.5) = 10.
        let ends = ends(DVec2::new(-10.0, 5.0), DVec2::new(20.0, 5.0), VIEW);
        assert_eq!(ends, Some(((0, 10), (19, 10))));
    }
}
