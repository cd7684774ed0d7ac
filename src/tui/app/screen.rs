//! How the panes are looked at: the terminal's size, the focused pane, the
//! image pane's zoom and picture, the diagram's plane, pan and zoom.

use ratatui::layout::Rect;

use crate::tui::action::{Action, Pane, Picture};
use crate::tui::view::pan_zoom::PanZoom;
use raystep_engine::terms::Term;
use raystep_tools::diagram::DiagramPlane;

pub struct Screen {
    /// The terminal's size, as the last `Action::Resize` gave it.
    size: Rect,
    focus: Pane,
    /// 1 shows the whole image; each doubling halves the pixels per cell.
    zoom: u32,
    picture: Picture,
    plane: DiagramPlane,
    /// The diagram's pan and zoom; fitted again for another pixel or plane.
    diagram: PanZoom,
}

impl Default for Screen {
    fn default() -> Screen {
        Screen {
            size: Rect::new(0, 0, 120, 40),
            focus: Pane::Image,
            zoom: 1,
            picture: Picture::Render,
            plane: DiagramPlane::Top,
            diagram: PanZoom::fit(),
        }
    }
}

impl Screen {
    /// Focus, zoom out, the diagram's plane, pan and zoom, the size.
    pub(super) fn update(&mut self, action: Action) {
        match action {
            Action::FocusNext => self.focus = self.focus.next(),
            Action::FocusPrevious => self.focus = self.focus.previous(),
            Action::ZoomOut => self.zoom = (self.zoom / 2).max(1),
            Action::CyclePlane => {
                self.plane = self.plane.next();
                self.diagram = PanZoom::fit();
            }
            Action::PanDiagram(dx, dy) => self.diagram.pan(dx, dy),
            Action::ZoomDiagram(steps) => self.diagram.zoom_by(steps),
            Action::FitDiagram => self.diagram = PanZoom::fit(),
            Action::Resize(width, height) => self.size = Rect::new(0, 0, width, height),
            _ => {}
        }
    }

    /// The terminal's size, as the last `Action::Resize` gave it.
    pub(crate) fn size(&self) -> Rect {
        self.size
    }

    /// The pane that has the keys.
    pub fn focus(&self) -> Pane {
        self.focus
    }

    pub(super) fn set_focus(&mut self, pane: Pane) {
        self.focus = pane;
    }

    /// 1 shows the whole image; each doubling halves the pixels per cell.
    pub fn zoom(&self) -> u32 {
        self.zoom
    }

    /// Doubles the zoom up to `most`; the message when it is there already.
    pub(super) fn zoom_in(&mut self, most: u32) -> Option<String> {
        if self.zoom < most {
            self.zoom *= 2;
            return None;
        }
        Some("zoomed in all the way: one image pixel per half cell".into())
    }

    /// What the image pane shows.
    pub fn picture(&self) -> Picture {
        self.picture
    }

    /// The render, each of `terms` (the scene's: `Term::written_for`), then
    /// (`comparing`) yours and the error map; the message that names the
    /// picture.
    pub(super) fn next_picture(&mut self, comparing: bool, terms: &[Term]) -> String {
        let after_terms = if comparing {
            Picture::Yours
        } else {
            Picture::Render
        };
        self.picture = match self.picture {
            Picture::Render => Picture::Term(terms[0]),
            Picture::Term(term) => match terms.iter().position(|&t| t == term) {
                Some(i) if i + 1 < terms.len() => Picture::Term(terms[i + 1]),
                _ => after_terms,
            },
            Picture::Yours => Picture::ErrorMap,
            Picture::ErrorMap => Picture::Render,
        };
        words(self.picture)
    }

    /// `c` and `E`: straight to yours or the error map, and back to the
    /// render from there; the message that names the picture.
    pub(super) fn toggle_picture(&mut self, picture: Picture) -> String {
        self.picture = if self.picture == picture {
            Picture::Render
        } else {
            picture
        };
        words(self.picture)
    }

    /// The plane the diagram is drawn on.
    pub fn plane(&self) -> DiagramPlane {
        self.plane
    }

    /// How the diagram is panned and zoomed.
    pub fn diagram_pan_zoom(&self) -> PanZoom {
        self.diagram
    }

    /// The whole diagram again (another pixel).
    pub(super) fn fit_diagram(&mut self) {
        self.diagram = PanZoom::fit();
    }
}

/// What the status line says of a picture shown.
fn words(picture: Picture) -> String {
    match picture {
        Picture::Render => "view: the render".to_string(),
        Picture::Term(term) => format!("view {}: {}", term.name(), term.legend()),
        Picture::Yours => "view yours: the image you compare".to_string(),
        Picture::ErrorMap => {
            "view error map: FLIP's error, black where the images agree, bright where they part"
                .to_string()
        }
    }
}
