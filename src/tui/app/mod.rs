//! The debugger's state and the one place it changes: `App::update(Action)`.
//! The state is in parts, each owning its fields and changed by its own
//! `update` or methods:
//!
//! - `overlay.rs`: what is open over the panes (help, mistakes menu, go-to
//!   prompt, `f`'s second key), one at a time;
//! - `pixel.rs`: the pixel being traced (cursor, recording, current event,
//!   folded rows, breakpoint object, what-if);
//! - `renders.rs`: the whole image's renders;
//! - `session.rs`: the scene, its source and watcher, the settings traced;
//! - `comparing.rs`: `--compare`'s image, findings and regions;
//! - `screen.rs`: focus, zoom, the image pane's picture, the diagram's
//!   plane, pan and zoom;
//! - `search.rs`: a find across the image under way.
//!
//! `App` ties them together: an action that concerns several parts (a
//! pick, a toggle, a reload, a find) is carried out here. Drawing and tests
//! read through the accessors below; keys become `Action`s in `event.rs`
//! first, and background work (finished renders, a changed scene file) is
//! looked at on `Action::Tick`.

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::time::Duration;

use image::RgbImage;
use ratatui::layout::{Position, Rect};

use crate::compare::{self, Comparison, StudentImage};
use crate::diagram::DiagramPlane;
use crate::record::{NodeId, RayTree};
use crate::scene::{Scene, SceneError, Settings, SpecularModel};
use crate::terms::{Term, TermImages};

use super::action::{Action, Find, Pane, Picture};
use super::keymap::Mode;
use super::render_job::Progress;
use super::source::SceneSource;
use super::view::find;
use super::view::image_grid::{ImageGrid, max_zoom};
use super::view::layout::{self, Panes, inner};
use super::view::pan_zoom::PanZoom;
use super::view::tree;

mod comparing;
mod overlay;
mod pixel;
mod renders;
mod screen;
mod search;
mod session;

pub use comparing::StudentComparison;
pub use overlay::Overlay;
use overlay::Overlays;
use pixel::TracedPixel;
use renders::Renders;
use screen::Screen;
use search::Search;
use session::Session;

/// The deepest max_depth the depth keys go to (a glass scene's tree doubles
/// with every level).
pub const MAX_DEPTH: u32 = 16;
/// The first status message, for someone who has never seen the debugger.
pub const WELCOME: &str =
    "arrows pick a pixel, n steps through its trace, Tab changes pane, ? lists every key";

pub struct App {
    session: Session,
    pixel: TracedPixel,
    renders: Renders,
    overlay: Overlays,
    screen: Screen,
    /// The student's image and what `compare` found, with `--compare`.
    comparison: Option<StudentComparison>,
    /// The find scanning the image in the background, if one runs.
    search: Option<Search>,
    /// The status line's message.
    message: Option<String>,
    quit: bool,
    /// Background work runs on the caller's thread (tests).
    sync: bool,
    /// Show timings in the status line (off in tests, for stable screens).
    show_timings: bool,
}

impl App {
    /// Opens a scene (`None`: the built-in one). With `sync`, renders finish
    /// before `update` returns, so tests see deterministic screens.
    pub fn open(path: Option<PathBuf>, sync: bool) -> Result<App, SceneError> {
        let source = SceneSource { path, size: None };
        let scene = source.load()?;
        Ok(App::new(source, scene, None, sync))
    }

    /// Opens a scene as `open` does, and with a student's image compares
    /// them once, here: the scene is traced at the image's size from then on
    /// (reloads too). `raystep debug SCENE --compare IMAGE.png` opens here.
    pub fn open_with(
        path: Option<PathBuf>,
        student: Option<StudentImage>,
        sync: bool,
    ) -> anyhow::Result<App> {
        let Some(student) = student else {
            return Ok(App::open(path, sync)?);
        };
        let source = SceneSource {
            path,
            size: Some(student.image.dimensions()),
        };
        let scene = source.load()?;
        let yours = student.image.clone();
        let comparison = compare::compare(&scene, student);
        let comparison = StudentComparison::new(yours, comparison);
        Ok(App::new(source, scene, Some(comparison), sync))
    }

    /// The app on a loaded scene: its centre pixel picked, its render asked for.
    fn new(
        source: SceneSource,
        scene: Scene,
        comparison: Option<StudentComparison>,
        sync: bool,
    ) -> App {
        let cursor = (scene.width / 2, scene.height / 2);
        let session = Session::new(source, scene);
        let pixel = TracedPixel::new(session.scene(), session.settings(), cursor);
        let mut app = App {
            session,
            pixel,
            renders: Renders::new(sync),
            overlay: Overlays::default(),
            screen: Screen::default(),
            comparison,
            search: None,
            message: Some(WELCOME.into()),
            quit: false,
            sync,
            show_timings: !sync,
        };
        app.request_render();
        app.collect_renders();
        app
    }

    /// The app watching its scene file for changes, which it reloads on a
    /// later `Action::Tick` (the built-in scene has no file).
    pub fn watching(mut self) -> App {
        if let Some(why) = self.session.watch() {
            self.message = Some(why);
        }
        self
    }

    /// The app on `pixel` instead of the centre (`--pixel X,Y`); refused
    /// when the pixel is outside the image.
    pub fn at_pixel(mut self, pixel: (u32, u32)) -> Result<App, String> {
        let size = (self.scene().width, self.scene().height);
        if pixel.0 >= size.0 || pixel.1 >= size.1 {
            return Err(find::outside(pixel, size));
        }
        self.pick(pixel.0, pixel.1);
        Ok(self)
    }

    /// Carries out an action: the only way the state changes.
    pub fn update(&mut self, action: Action) {
        if !matches!(action, Action::Tick | Action::Resize(..)) {
            // Time passing and the terminal's size are not the user's
            // doing: the message (the welcome, at first) stays.
            self.message = None;
        }
        let height = self.screen.size().height;
        match action {
            Action::Tick => {
                if self.session.reload_is_due() {
                    self.reload();
                }
            }
            Action::Quit => {
                self.quit = true;
                self.search = None;
                self.renders.cancel();
            }
            Action::Suspend => {}
            Action::Move(dx, dy) => self.move_cursor(dx, dy),
            Action::Pick(x, y) => self.pick(x, y),
            Action::Click(column, row) => self.click(column, row),
            Action::ZoomIn => {
                if let Some(size) = self.renders.image().map(|i| (i.width(), i.height())) {
                    let most = max_zoom(inner(self.panes().image), size);
                    self.message = self.screen.zoom_in(most);
                }
            }
            Action::CyclePicture => {
                self.message = Some(self.screen.next_picture(self.comparison.is_some()));
                let terms = matches!(self.screen.picture(), Picture::Term(_));
                if terms && !self.renders.terms_are_current() {
                    let (scene, settings) = (self.session.shared_scene(), *self.settings());
                    self.renders.request_again(scene, settings, true);
                }
            }
            Action::Step(_)
            | Action::RunTo(_)
            | Action::RunToObject
            | Action::CycleBreakObject
            | Action::SelectRow(_)
            | Action::ToggleCollapse
            | Action::ScrollDetails(_) => {
                self.message = self.pixel.update(action, self.session.scene());
            }
            Action::Toggle(_)
            | Action::ToggleSpecular
            | Action::Depth(_)
            | Action::ToggleMistake(_) => self.toggle(action),
            Action::MenuToggle => self.toggle(Action::ToggleMistake(self.overlay.menu_mistake())),
            Action::NextRegion => self.next_region(),
            Action::PromptSubmit => self.prompt_submit(),
            Action::Find(what) => {
                self.overlay.update(action, height);
                self.find(what);
            }
            Action::Reload => self.reload(),
            Action::ToggleHelp
            | Action::CloseHelp
            | Action::ScrollHelp(_)
            | Action::ToggleMistakeMenu
            | Action::CloseMistakeMenu
            | Action::MenuMove(_)
            | Action::OpenPrompt
            | Action::PromptChar(_)
            | Action::PromptBackspace
            | Action::PromptCancel
            | Action::StartFind
            | Action::CancelFind => self.message = self.overlay.update(action, height),
            Action::FocusNext
            | Action::FocusPrevious
            | Action::ZoomOut
            | Action::CyclePlane
            | Action::PanDiagram(..)
            | Action::ZoomDiagram(_)
            | Action::FitDiagram
            | Action::Resize(..) => self.screen.update(action),
        }
        self.collect_renders();
        self.collect_find();
    }

    /// Selects a pixel: only that pixel is traced again.
    fn pick(&mut self, x: u32, y: u32) {
        self.search = None;
        self.screen.fit_diagram();
        let session = &self.session;
        self.pixel.pick((x, y), session.scene(), session.settings());
    }

    fn move_cursor(&mut self, dx: i32, dy: i32) {
        let clamp =
            |v: u32, d: i32, size: u32| (v as i64 + d as i64).clamp(0, size as i64 - 1) as u32;
        let (cursor, scene) = (self.cursor(), self.scene());
        let (x, y) = (
            clamp(cursor.0, dx, scene.width),
            clamp(cursor.1, dy, scene.height),
        );
        if (x, y) != cursor {
            self.pick(x, y);
        }
    }

    fn click(&mut self, column: u16, row: u16) {
        let panes = self.panes();
        let Some(pane) = panes.pane_at(column, row) else {
            return;
        };
        self.screen.set_focus(pane);
        let inside = inner(panes.rect(pane));
        if !inside.contains(Position::new(column, row)) {
            return;
        }
        let (line, height) = ((row - inside.y) as usize, inside.height as usize);
        match pane {
            Pane::Image => {
                if let Some((x, y)) = self.image_grid().and_then(|v| v.pixel_at_cell(column, row)) {
                    let (width, height) = (self.scene().width, self.scene().height);
                    self.pick(x.min(width - 1), y.min(height - 1));
                }
            }
            Pane::Tree => self.pixel.click_tree(line, height),
            Pane::Steps => self.pixel.click_steps(line, height),
            Pane::Details | Pane::Diagram => {}
        }
    }

    /// A teaching toggle: the new settings traced, and what it did said.
    fn toggle(&mut self, action: Action) {
        let Some((settings, message)) = self.session.toggled(action) else {
            return;
        };
        if let Some(settings) = settings {
            self.apply_settings(settings);
        }
        self.message = Some(message);
    }

    /// Traces the scene with new settings: the pixel, then the image.
    fn apply_settings(&mut self, settings: Settings) {
        self.search = None;
        self.session.set_settings(settings);
        let session = &self.session;
        self.pixel.retrace_with(session.scene(), session.settings());
        self.request_render();
    }

    /// Reloads the scene file; a broken file keeps the last good scene.
    fn reload(&mut self) {
        match self.session.reload() {
            Some(settings) => {
                self.apply_settings(settings);
                self.message = Some(format!("reloaded {}", self.session.source().name()));
            }
            None => {
                self.message =
                    Some("the scene file has an error: the last good scene stays".into());
            }
        }
    }

    /// The cursor to the next region's pixel (the largest first, cycling).
    fn next_region(&mut self) {
        let Some(comparison) = &mut self.comparison else {
            self.message = Some("no image to compare: open with --compare IMAGE.png".into());
            return;
        };
        match comparison.next_region() {
            Ok(((x, y), message)) => {
                self.pick(x, y);
                self.message = Some(message);
            }
            Err(why) => self.message = Some(why),
        }
    }

    /// Enter: go to the pixel typed, or say why not and keep the prompt
    /// open so the text can be corrected.
    fn prompt_submit(&mut self) {
        let Some(text) = self.overlay.prompt() else {
            return;
        };
        match find::parse_goto(text, (self.scene().width, self.scene().height)) {
            Ok((x, y)) => {
                self.overlay.close();
                self.pick(x, y);
                self.message = Some(format!("went to pixel ({x}, {y})"));
            }
            Err(why) => self.message = Some(why),
        }
    }

    /// Starts looking for the next pixel in reading order whose recording
    /// has `what`, in the background: a pick, a toggle, another find or
    /// quitting cancels it.
    fn find(&mut self, what: Find) {
        self.search = None;
        match Search::start(what, &mut self.pixel, &self.session, self.sync) {
            Ok(search) => self.search = Some(search),
            Err(why) => self.message = Some(why),
        }
    }

    /// Takes in the running find's result once it has one.
    fn collect_find(&mut self) {
        let Some(found) = self.search.as_ref().and_then(Search::poll) else {
            return;
        };
        let Some(search) = self.search.take() else {
            return;
        };
        self.message = Some(search.result_message(found.as_ref().map(|f| f.pixel)));
        if let Some(found) = found {
            self.pixel.take_found(found, search.elapsed());
        }
    }

    /// Renders the scene as it is now, as a new generation.
    fn request_render(&mut self) {
        let terms = matches!(self.screen.picture(), Picture::Term(_));
        let (scene, settings) = (self.session.shared_scene(), *self.settings());
        self.renders.request(scene, settings, terms);
    }

    /// Takes in the previews and renders that came back.
    fn collect_renders(&mut self) {
        if let Some(failed) = self.renders.collect() {
            self.message = Some(failed);
        }
    }

    // What the panes and tests read.

    pub fn source(&self) -> &SceneSource {
        self.session.source()
    }

    /// The last good file's scene, with the file's own settings.
    pub fn scene(&self) -> &Scene {
        self.session.scene()
    }

    /// The settings traced: the file's, with the user's toggles.
    pub fn settings(&self) -> &Settings {
        self.session.settings()
    }

    pub fn phong(&self) -> bool {
        self.settings().specular == SpecularModel::Phong
    }

    /// The banner: why the last reload failed.
    pub fn error(&self) -> Option<&str> {
        self.session.error()
    }

    /// The selected pixel, in the scene image's coordinates.
    pub fn cursor(&self) -> (u32, u32) {
        self.pixel.cursor()
    }

    /// The selected pixel's recording.
    pub fn tree(&self) -> &RayTree {
        self.pixel.tree()
    }

    /// The current event, an index into `tree().events`.
    pub fn current(&self) -> usize {
        self.pixel.current()
    }

    /// The rays whose rows the tree pane folds away.
    pub fn collapsed(&self) -> &BTreeSet<NodeId> {
        self.pixel.collapsed()
    }

    /// The node the tree and details show: the current event's ray.
    pub fn selected_node(&self) -> NodeId {
        self.pixel.selected_node()
    }

    /// The object the `x` breakpoint stops at, once chosen.
    pub fn break_object(&self) -> Option<usize> {
        self.pixel.break_object()
    }

    /// Manual scroll of the details; `None` follows the current event.
    pub fn details_scroll(&self) -> Option<u16> {
        self.pixel.details_scroll()
    }

    /// How the selected pixel changed with the last toggle, when it did.
    pub fn what_if(&self) -> Option<&str> {
        self.pixel.what_if()
    }

    /// How long the last pixel pick took.
    pub fn pick_time(&self) -> Duration {
        self.pixel.pick_time()
    }

    /// What is open over the panes, if anything.
    pub fn overlay(&self) -> Option<&Overlay> {
        self.overlay.open()
    }

    /// What has the keys: the overlay open, else the panes.
    pub fn mode(&self) -> Mode {
        self.overlay.mode()
    }

    /// Whether the help is open.
    pub fn help(&self) -> bool {
        matches!(self.overlay(), Some(Overlay::Help { .. }))
    }

    /// The mistakes menu's selected row (an index into `Mistake::ALL`)
    /// when the menu is open.
    pub fn mistake_menu(&self) -> Option<usize> {
        self.overlay.menu_row()
    }

    /// The go-to prompt's text while it is open.
    pub fn prompt(&self) -> Option<&str> {
        self.overlay.prompt()
    }

    pub fn focus(&self) -> Pane {
        self.screen.focus()
    }

    /// 1 shows the whole image; each doubling halves the pixels per cell.
    pub fn zoom(&self) -> u32 {
        self.screen.zoom()
    }

    /// What the image pane shows.
    pub fn picture(&self) -> Picture {
        self.screen.picture()
    }

    pub fn plane(&self) -> DiagramPlane {
        self.screen.plane()
    }

    /// How the diagram is panned and zoomed.
    pub fn diagram_pan_zoom(&self) -> PanZoom {
        self.screen.diagram()
    }

    /// The terminal's size, as the last `Action::Resize` gave it.
    pub fn screen(&self) -> Rect {
        self.screen.size()
    }

    pub fn panes(&self) -> Panes {
        let banner = self.error().map_or(0, |e| e.lines().count() as u16);
        let rows = tree::rows(self.tree(), self.collapsed()).len() as u16;
        layout::panes(self.screen(), banner, rows)
    }

    /// The image pane's mapping, for drawing and for clicks.
    pub fn image_grid(&self) -> Option<ImageGrid> {
        let size = self.image().map(|i| (i.width(), i.height()))?;
        Some(ImageGrid::new(
            inner(self.panes().image),
            size,
            self.zoom(),
            self.cursor(),
        ))
    }

    /// The student's image, with `--compare`.
    pub fn yours(&self) -> Option<&RgbImage> {
        self.comparison.as_ref().map(StudentComparison::yours)
    }

    /// The comparison's findings, with `--compare`.
    pub fn comparison(&self) -> Option<&Comparison> {
        self.comparison.as_ref().map(StudentComparison::comparison)
    }

    /// The status line's message.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// Whether the user asked to quit.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// Whether background work is under way (the loop then polls more often).
    pub fn busy(&self) -> bool {
        self.renders.busy() || self.session.reload_waits() || self.search.is_some()
    }

    /// How far the running render is.
    pub fn progress(&self) -> Option<Progress> {
        self.renders.progress()
    }

    /// What the running find looks for and the row it is on (from 1), of
    /// the image's rows: "finding {what}… (row N of H)".
    pub fn finding_progress(&self) -> Option<(&str, u32, u32)> {
        let (what, row) = self.search.as_ref()?.progress();
        Some((what, row + 1, self.scene().height))
    }

    /// The latest render (or preview) of the current settings.
    pub fn image(&self) -> Option<&RgbImage> {
        self.renders.image()
    }

    /// The term images, once a term picture asked for them.
    pub fn terms(&self) -> Option<&TermImages> {
        self.renders.terms()
    }

    /// The scale of a count picture (rays or cost): its largest count.
    pub fn count_max(&self, term: Term) -> u32 {
        self.renders.count_max(term)
    }

    /// How long the last finished render took.
    pub fn render_time(&self) -> Option<Duration> {
        self.renders.render_time()
    }

    /// Whether the status line shows timings (off in tests, for stable screens).
    pub fn show_timings(&self) -> bool {
        self.show_timings
    }

    /// The colour of a pixel as the image pane shows it.
    pub fn shown_pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        match self.picture() {
            Picture::Render => self.image().and_then(|i| pixel(i, x, y)),
            Picture::Term(term) => self
                .terms()
                .filter(|t| x < t.width && y < t.height)
                .map(|t| t.rgb(term, (y * t.width + x) as usize, self.count_max(term))),
            Picture::Yours => self.yours().and_then(|i| pixel(i, x, y)),
            Picture::ErrorMap => self.comparison().and_then(|c| pixel(&c.error_map, x, y)),
        }
    }

    /// Our pixel at the cursor, as the render (with the toggles) has it.
    pub fn our_pixel(&self) -> Option<[u8; 3]> {
        let (x, y) = self.cursor();
        self.image().and_then(|i| pixel(i, x, y))
    }
}

/// An image's pixel, `None` outside it.
fn pixel(image: &RgbImage, x: u32, y: u32) -> Option<[u8; 3]> {
    (x < image.width() && y < image.height()).then(|| image.get_pixel(x, y).0)
}
