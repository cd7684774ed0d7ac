//! Where each pane goes: a pure function of the screen size, shared by the
//! drawing code and by mouse handling so a click lands where it was drawn.

use ratatui::layout::{Constraint, Layout, Rect};

/// The smallest terminal the debugger draws in.
pub const MIN_WIDTH: u16 = 80;
pub const MIN_HEIGHT: u16 = 24;

/// The panes, in the order Tab visits them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pane {
    Image,
    Tree,
    Steps,
    Details,
    Diagram,
}

impl Pane {
    pub const ALL: [Pane; 5] = [
        Pane::Image,
        Pane::Tree,
        Pane::Steps,
        Pane::Details,
        Pane::Diagram,
    ];

    pub fn next(self) -> Pane {
        let i = Pane::ALL.iter().position(|&p| p == self).unwrap_or(0);
        Pane::ALL[(i + 1) % Pane::ALL.len()]
    }

    pub fn previous(self) -> Pane {
        let i = Pane::ALL.iter().position(|&p| p == self).unwrap_or(0);
        Pane::ALL[(i + Pane::ALL.len() - 1) % Pane::ALL.len()]
    }
}

/// The screen, cut into its parts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Panes {
    pub header: Rect,
    pub image: Rect,
    pub diagram: Rect,
    pub tree: Rect,
    pub steps: Rect,
    pub details: Rect,
    pub banner: Rect,
    pub status: Rect,
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
    pub fn pane_at(&self, column: u16, row: u16) -> Option<Pane> {
        let position = ratatui::layout::Position::new(column, row);
        Pane::ALL
            .into_iter()
            .find(|&p| self.rect(p).contains(position))
    }
}

pub fn too_small(area: Rect) -> bool {
    area.width < MIN_WIDTH || area.height < MIN_HEIGHT
}

/// Cuts `area`: `banner_lines` of error text (0 for none), `tree_rows` rows
/// wanted by the ray tree.
pub fn panes(area: Rect, banner_lines: u16, tree_rows: u16) -> Panes {
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
