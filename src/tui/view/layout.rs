//! Where each pane goes: a pure function of the screen size, shared by the
//! drawing code and by mouse handling so a click lands where it was drawn.

use ratatui::layout::{Constraint, Layout, Margin, Rect};

use crate::tui::action::Pane;

/// The smallest terminal the debugger draws in.
pub(crate) const MIN_WIDTH: u16 = 80;
pub(crate) const MIN_HEIGHT: u16 = 24;

/// The screen, cut into its parts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Panes {
    pub(crate) header: Rect,
    pub(crate) image: Rect,
    pub diagram: Rect,
    pub tree: Rect,
    pub(crate) steps: Rect,
    pub(crate) details: Rect,
    pub(crate) banner: Rect,
    pub(crate) status: Rect,
}

impl Panes {
    pub fn rect(&self, pane: Pane) -> Rect {
        match pane {
            Pane::Image => self.image,
            Pane::Tree => self.tree,
            Pane::Steps => self.steps,
            Pane::Details => self.details,
            Pane::Diagram => self.diagram,
        }
    }

    /// The pane under a screen cell.
    pub(crate) fn pane_at(&self, column: u16, row: u16) -> Option<Pane> {
        let position = ratatui::layout::Position::new(column, row);
        Pane::ALL
            .into_iter()
            .find(|&p| self.rect(p).contains(position))
    }
}

/// The inside of a bordered pane.
pub(crate) fn inner(area: Rect) -> Rect {
    area.inner(Margin::new(1, 1))
}

pub(crate) fn too_small(area: Rect) -> bool {
    area.width < MIN_WIDTH || area.height < MIN_HEIGHT
}

/// Cuts `area`: `banner_lines` of error text (0 for none), `tree_rows` rows
/// wanted by the ray tree.
pub(crate) fn panes(area: Rect, banner_lines: u16, tree_rows: u16) -> Panes {
    let banner = if banner_lines == 0 {
        0
    } else {
        (banner_lines + 2).min(area.height / 3)
    };
    let [header, main, banner, status] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Fill(1),
        Constraint::Length(banner),
        Constraint::Length(1),
    ])
    .areas(area);
    let [left, right] =
        Layout::horizontal([Constraint::Percentage(42), Constraint::Fill(1)]).areas(main);
    let [image, diagram] =
        Layout::vertical([Constraint::Percentage(55), Constraint::Fill(1)]).areas(left);
    let tree_height = (tree_rows + 2).clamp(5, (main.height / 3).max(5));
    let steps_height = (main.height / 4).max(7);
    let [tree, steps, details] = Layout::vertical([
        Constraint::Length(tree_height),
        Constraint::Length(steps_height),
        Constraint::Fill(1),
    ])
    .areas(right);
    Panes {
        header,
        image,
        diagram,
        tree,
        steps,
        details,
        banner,
        status,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tab_order_goes_round_both_ways() {
        for pane in Pane::ALL {
            assert_eq!(pane.next().previous(), pane);
        }
        assert_eq!(Pane::Diagram.next(), Pane::Image);
        assert_eq!(Pane::Image.previous(), Pane::Diagram);
    }

    #[test]
    fn the_right_column_stacks_tree_steps_and_details() {
        // 120 x 40: header row 0, status row 39, 38 rows between. The tree
        // wants 3 rows + 2 borders = 5; the steps get max(38 / 4, 7) = 9;
        // the details the other 38 - 5 - 9 = 24.
        let p = panes(Rect::new(0, 0, 120, 40), 0, 3);
        assert_eq!((p.header.y, p.status.y, p.banner.height), (0, 39, 0));
        assert_eq!((p.tree.y, p.tree.height), (1, 5));
        assert_eq!((p.steps.y, p.steps.height), (6, 9));
        assert_eq!((p.details.y, p.details.height), (15, 24));
        // The left column (42% of 120 = 50.4) holds image and diagram.
        assert_eq!((p.image.x, p.image.width, p.tree.x), (0, 50, 50));
        assert_eq!(p.diagram.y, p.image.y + p.image.height);
        assert_eq!(p.pane_at(p.tree.x, p.tree.y), Some(Pane::Tree));
        assert_eq!(p.pane_at(0, 0), None, "the header is no pane");
    }

    #[test]
    fn a_banner_takes_its_lines_and_borders_from_the_middle() {
        // 2 lines + 2 borders = 4 rows (at most 40 / 3), above the status.
        let p = panes(Rect::new(0, 0, 120, 40), 2, 3);
        assert_eq!((p.banner.y, p.banner.height), (35, 4));
        // A long tree is held to a third of the 34 rows left: 11.
        let p = panes(Rect::new(0, 0, 120, 40), 2, 50);
        assert_eq!(p.tree.height, 11);
    }

    #[test]
    fn sizes_and_borders() {
        assert_eq!(inner(Rect::new(2, 3, 10, 5)), Rect::new(3, 4, 8, 3));
        assert!(too_small(Rect::new(0, 0, 79, 24)));
        assert!(too_small(Rect::new(0, 0, 80, 23)));
        assert!(!too_small(Rect::new(0, 0, 80, 24)));
    }
}
