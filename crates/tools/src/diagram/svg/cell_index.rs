//! A uniform grid of cells over a figure, listing the boxes and segments
//! that reach each cell: the label placer tests a place's box against what
//! lies in the cells it covers, not against everything reserved, so that a
//! figure of thousands of marks and rays (2,000 near misses along one ray,
//! a tree of 65,536 rays) is labelled in time linear in them, not in their
//! product with the labels.
//!
//! It answers "which items may meet this box": every item that has a
//! point in the box is listed (some more than once, some that do not meet
//! it); the caller tests each exactly. Cells at the edges reach out to
//! infinity, so an item or a box outside the grid is still found.

use glam::DVec2;

/// How far each item and query is widened, in figure units, so that
/// rounding never leaves out a cell an item touches.
const SLACK: f64 = 1e-3;

pub(super) struct CellIndex {
    origin: DVec2,
    cell: f64,
    columns: usize,
    rows: usize,
    /// The items reaching each cell, row by row.
    cells: Vec<Vec<u32>>,
}

impl CellIndex {
    /// A grid of `cell`-sized cells over the box from `lo` to `hi`.
    pub(super) fn new((lo, hi): (DVec2, DVec2), cell: f64) -> CellIndex {
        let count = |extent: f64| ((extent / cell).ceil() as usize).clamp(1, 1024);
        let (columns, rows) = (count(hi.x - lo.x), count(hi.y - lo.y));
        CellIndex {
            origin: lo,
            cell,
            columns,
            rows,
            cells: vec![Vec::new(); columns * rows],
        }
    }

    /// The column holding `x` (an edge column past the grid's edge).
    fn column(&self, x: f64) -> usize {
        let i = ((x - self.origin.x) / self.cell).floor() as i64;
        i.clamp(0, self.columns as i64 - 1) as usize
    }

    fn row(&self, y: f64) -> usize {
        let i = ((y - self.origin.y) / self.cell).floor() as i64;
        i.clamp(0, self.rows as i64 - 1) as usize
    }

    /// Lists `item` in every cell the box from `lo` to `hi` covers.
    pub(super) fn insert_box(&mut self, (lo, hi): (DVec2, DVec2), item: u32) {
        let columns = self.column(lo.x - SLACK)..=self.column(hi.x + SLACK);
        for row in self.row(lo.y - SLACK)..=self.row(hi.y + SLACK) {
            for column in columns.clone() {
                self.cells[row * self.columns + column].push(item);
            }
        }
    }

    /// Lists `item` in every cell the segment from `a` to `b` crosses: row
    /// by row, the columns between where it enters and leaves the row.
    pub(super) fn insert_segment(&mut self, a: DVec2, b: DVec2, item: u32) {
        let d = b - a;
        let (top, bottom) = (a.y.min(b.y), a.y.max(b.y));
        for row in self.row(top - SLACK)..=self.row(bottom + SLACK) {
            // The row's band, open-ended at the grid's top and bottom.
            let y0 = match row {
                0 => f64::NEG_INFINITY,
                _ => self.origin.y + row as f64 * self.cell - SLACK,
            };
            let y1 = match row + 1 == self.rows {
                true => f64::INFINITY,
                false => self.origin.y + (row + 1) as f64 * self.cell + SLACK,
            };
            let (t0, t1) = if d.y == 0.0 {
                (0.0, 1.0)
            } else {
                let (s0, s1) = ((y0 - a.y) / d.y, (y1 - a.y) / d.y);
                (s0.min(s1).max(0.0), s0.max(s1).min(1.0))
            };
            if t0 > t1 {
                continue;
            }
            let (x0, x1) = (a.x + d.x * t0, a.x + d.x * t1);
            let columns = self.column(x0.min(x1) - SLACK)..=self.column(x0.max(x1) + SLACK);
            for column in columns {
                self.cells[row * self.columns + column].push(item);
            }
        }
    }

    /// The items listed in the cells the box from `lo` to `hi` covers,
    /// each as often as it is listed there.
    pub(super) fn near(&self, (lo, hi): (DVec2, DVec2)) -> impl Iterator<Item = usize> + '_ {
        let columns = self.column(lo.x - SLACK)..=self.column(hi.x + SLACK);
        (self.row(lo.y - SLACK)..=self.row(hi.y + SLACK)).flat_map(move |row| {
            let cells = &self.cells[row * self.columns..(row + 1) * self.columns];
            cells[columns.clone()]
                .iter()
                .flat_map(|items| items.iter().map(|&i| i as usize))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn listed(index: &CellIndex, b: (DVec2, DVec2)) -> Vec<usize> {
        let mut items: Vec<usize> = index.near(b).collect();
        items.sort_unstable();
        items.dedup();
        items
    }

    #[test]
    fn a_box_finds_what_reaches_its_cells_only() {
        // Cells of 10 over 0..100: a box in cell (6, 2) and a diagonal
        // from (0, 0) to (100, 100), which crosses cells (i, i) (and, by
        // the slack, touches their neighbours (i ± 1, i)).
        let mut index = CellIndex::new((DVec2::ZERO, DVec2::splat(100.0)), 10.0);
        index.insert_box((DVec2::new(62.0, 23.0), DVec2::new(68.0, 27.0)), 0);
        index.insert_segment(DVec2::ZERO, DVec2::splat(100.0), 1);
        let at = |x: f64, y: f64| (DVec2::new(x, y), DVec2::new(x + 1.0, y + 1.0));
        assert_eq!(listed(&index, at(64.0, 24.0)), [0]);
        assert_eq!(listed(&index, at(55.0, 55.0)), [1]);
        assert_eq!(listed(&index, at(75.0, 15.0)), Vec::<usize>::new());
        // A vertical segment at x = 50 (on a cell edge) and a horizontal
        // one: both found from either side.
        index.insert_segment(DVec2::new(50.0, 0.0), DVec2::new(50.0, 100.0), 2);
        index.insert_segment(DVec2::new(0.0, 80.0), DVec2::new(100.0, 80.0), 3);
        assert_eq!(listed(&index, at(48.5, 5.0)), [2]);
        assert_eq!(listed(&index, at(50.5, 5.0)), [2]);
        assert_eq!(listed(&index, at(5.0, 79.5)), [3]);
    }

    #[test]
    fn what_lies_past_the_grid_is_found_at_its_edge() {
        // A segment above the grid (y = -50) and a box right of it: both
        // found by a box out there, as the exact test would meet them.
        let mut index = CellIndex::new((DVec2::ZERO, DVec2::splat(100.0)), 10.0);
        index.insert_segment(DVec2::new(20.0, -50.0), DVec2::new(40.0, -50.0), 0);
        index.insert_box((DVec2::new(500.0, 50.0), DVec2::new(510.0, 60.0)), 1);
        let above = (DVec2::new(25.0, -55.0), DVec2::new(30.0, -45.0));
        assert_eq!(listed(&index, above), [0]);
        let right = (DVec2::new(505.0, 55.0), DVec2::new(506.0, 56.0));
        assert_eq!(listed(&index, right), [1]);
    }
}
