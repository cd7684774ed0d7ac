//! What each action does to the app: cursor, zoom, stepping, the tree, and
//! the teaching toggles. Split from `app/mod.rs` only to keep files short.

use ratatui::layout::Position;

use crate::terms::Term;

use super::{App, MAX_DEPTH, View};
use crate::scene::Switch;
use crate::tui::view::image_grid::{ImageGrid, max_zoom};
use crate::tui::view::layout::{Pane, inner};
use crate::tui::view::stepper::{self, Breakpoint, Step};
use crate::tui::view::steps;
use crate::tui::view::tree::{self, RowKind};

impl App {
    /// The image pane's mapping, for drawing and for clicks.
    pub fn image_grid(&self) -> Option<ImageGrid> {
        let size = self.image.as_ref().map(|i| (i.width(), i.height()))?;
        Some(ImageGrid::new(
            inner(self.panes().image),
            size,
            self.zoom,
            self.cursor,
        ))
    }

    pub(super) fn move_cursor(&mut self, dx: i32, dy: i32) {
        let clamp =
            |v: u32, d: i32, size: u32| (v as i64 + d as i64).clamp(0, size as i64 - 1) as u32;
        let (x, y) = (
            clamp(self.cursor.0, dx, self.scene.width),
            clamp(self.cursor.1, dy, self.scene.height),
        );
        if (x, y) != self.cursor {
            self.pick(x, y);
        }
    }

    pub(super) fn click(&mut self, column: u16, row: u16) {
        let panes = self.panes();
        let Some(pane) = panes.pane_at(column, row) else {
            return;
        };
        self.focus = pane;
        let inside = inner(panes.rect(pane));
        if !inside.contains(Position::new(column, row)) {
            return;
        }
        let line = (row - inside.y) as usize;
        match pane {
            Pane::Image => {
                if let Some((x, y)) = self.image_grid().and_then(|v| v.pixel_at_cell(column, row)) {
                    self.pick(x.min(self.scene.width - 1), y.min(self.scene.height - 1));
                }
            }
            Pane::Tree => {
                let rows = tree::rows(&self.tree, &self.collapsed);
                let selected = tree::selected_row(&self.tree, &rows, self.current).unwrap_or(0);
                let first = tree::scroll_offset(selected, inside.height as usize);
                if let Some(row) = rows.get(first + line) {
                    self.select(row.kind);
                }
            }
            Pane::Steps => {
                let first =
                    steps::first_line(self.current, self.tree.events.len(), inside.height as usize);
                if first + line < self.tree.events.len() {
                    self.set_current(first + line);
                }
            }
            Pane::Details | Pane::Diagram => {}
        }
    }

    pub(super) fn zoom_in(&mut self) {
        let Some(size) = self.image.as_ref().map(|i| (i.width(), i.height())) else {
            return;
        };
        if self.zoom < max_zoom(inner(self.panes().image), size) {
            self.zoom *= 2;
        } else {
            self.message = Some("zoomed in all the way: one image pixel per half cell".into());
        }
    }

    pub(super) fn set_current(&mut self, event: usize) {
        self.current = event.min(self.tree.events.len().saturating_sub(1));
        self.details_scroll = None;
    }

    pub(super) fn step(&mut self, step: Step) {
        self.set_current(stepper::step(&self.tree, self.current, step));
    }

    pub(super) fn run_to(&mut self, breakpoint: Breakpoint) {
        match stepper::run_to(&self.tree, self.current, breakpoint) {
            Some(event) => self.set_current(event),
            None => {
                let what = match breakpoint {
                    Breakpoint::BlockedShadow => "blocked shadow ray".to_string(),
                    Breakpoint::HitObject(object) => {
                        format!("hit on {}", self.scene.object_name(object))
                    }
                    Breakpoint::Tir => "total internal reflection".to_string(),
                };
                self.message = Some(format!(
                    "no {what} after event {} in this pixel",
                    self.current + 1
                ));
            }
        }
    }

    /// The object breakpoint: the chosen one, else the selected ray's object.
    pub fn break_target(&self) -> Option<usize> {
        self.break_object.or_else(|| {
            self.tree.nodes[self.selected_node()]
                .hit
                .as_ref()
                .map(|h| h.object_index)
        })
    }

    pub(super) fn run_to_object(&mut self) {
        match self.break_target() {
            Some(object) => {
                self.break_object = Some(object);
                self.run_to(Breakpoint::HitObject(object));
            }
            None => {
                self.message =
                    Some("the selected ray hits nothing: press X to choose an object".into())
            }
        }
    }

    pub(super) fn cycle_break_object(&mut self) {
        let count = self.scene.objects.len();
        self.break_object = match self.break_target() {
            _ if count == 0 => None,
            Some(object) if self.break_object.is_some() => Some((object + 1) % count),
            Some(object) => Some(object),
            None => Some(0),
        };
        if let Some(object) = self.break_object {
            self.message = Some(format!(
                "x runs to the next hit on {}",
                self.scene.object_name(object)
            ));
        }
    }

    /// Makes a tree row's ray or light the current event.
    fn select(&mut self, kind: RowKind) {
        let event = match kind {
            RowKind::Ray(node) => stepper::cast_event(&self.tree, node),
            RowKind::Light { node, light } => stepper::light_event(
                &self.tree,
                node,
                self.tree.nodes[node].lights[light].light_index,
            ),
        };
        if let Some(event) = event {
            self.set_current(event);
        }
    }

    pub(super) fn select_row(&mut self, delta: i32) {
        let rows = tree::rows(&self.tree, &self.collapsed);
        let Some(selected) = tree::selected_row(&self.tree, &rows, self.current) else {
            return;
        };
        let row = (selected as i64 + delta as i64).clamp(0, rows.len() as i64 - 1) as usize;
        self.select(rows[row].kind);
    }

    pub(super) fn toggle_collapse(&mut self) {
        let node = self.selected_node();
        if !self.collapsed.remove(&node) {
            self.collapsed.insert(node);
        }
    }

    pub(super) fn scroll_details(&mut self, delta: i32) {
        let from = self.details_scroll.unwrap_or(0) as i32;
        self.details_scroll = Some((from + delta).max(0) as u16);
    }

    pub(super) fn toggle(&mut self, switch: Switch) {
        let mut settings = self.settings;
        let state = if settings.switches.flip(switch) {
            "on"
        } else {
            "off"
        };
        self.apply_settings(settings);
        self.message = Some(format!("{} {state}", switch.name()));
    }

    pub(super) fn toggle_specular(&mut self) {
        use crate::scene::SpecularModel::{Blinn, Phong};
        let mut settings = self.settings;
        settings.specular = if settings.specular == Blinn {
            Phong
        } else {
            Blinn
        };
        self.apply_settings(settings);
        self.message = Some(
            if self.phong() {
                "specular: Phong's R·V"
            } else {
                "specular: Blinn's N·H"
            }
            .into(),
        );
    }

    pub(super) fn change_depth(&mut self, delta: i32) {
        let depth = self.settings.max_depth as i64 + delta as i64;
        if !(1..=MAX_DEPTH as i64).contains(&depth) {
            self.message = Some(format!(
                "max depth stays {}: it goes from 1 to {MAX_DEPTH}",
                self.settings.max_depth
            ));
            return;
        }
        let mut settings = self.settings;
        settings.max_depth = depth as u32;
        self.apply_settings(settings);
        self.message = Some(format!("max depth {depth}"));
    }

    /// The render, each term, then (when comparing) yours and the error map.
    pub(super) fn cycle_view(&mut self) {
        let after_terms = if self.compared.is_some() {
            View::Yours
        } else {
            View::Image
        };
        self.view = match self.view {
            View::Image => View::Term(Term::ALL[0]),
            View::Term(term) => match Term::ALL.iter().position(|&t| t == term) {
                Some(i) if i + 1 < Term::ALL.len() => View::Term(Term::ALL[i + 1]),
                _ => after_terms,
            },
            View::Yours => View::ErrorMap,
            View::ErrorMap => View::Image,
        };
        if matches!(self.view, View::Term(_)) && self.terms_generation != Some(self.generation) {
            self.request_current();
        }
        self.message = Some(match self.view {
            View::Image => "view: the render".to_string(),
            View::Term(term) => format!("view {}: {}", term.name(), term.legend()),
            View::Yours => "view yours: the image you compare".to_string(),
            View::ErrorMap => {
                "view error map: FLIP's error, black where the images agree, bright where they part"
                    .to_string()
            }
        });
    }
}
