//! The debugger's state and the one place it changes: `App::update(Action)`.
//! Every field is private: drawing and tests read through the accessors
//! below; keys become `Action`s in `event.rs` first, and background work
//! (finished renders, a changed scene file) is looked at on `Action::Tick`.
//! `controls.rs` and `renders.rs` carry out the actions; they are child
//! modules only so they can reach the fields.

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use image::RgbImage;
use ratatui::layout::Rect;

use crate::compare::{self, Comparison, StudentImage};
use crate::mistakes::Mistake;
use crate::record::{NodeId, RayTree, record_pixel};
use crate::scene::{Scene, SceneError, Settings, SpecularModel};
use crate::terms::{Term, TermImages};

pub use super::action::{Action, View};
use super::job::Renderer;
use super::keymap::Mode;
use super::source::{FileWatcher, SceneSource, merge_settings};
use super::view::layout::{self, Pane, Panes};
use super::view::pan_zoom::PanZoom;
use super::view::{help, tree};
use crate::diagram::DiagramPlane;

mod comparing;
mod controls;
mod mistakes;
mod reach;
mod renders;

pub use comparing::Compared;

/// The deepest max_depth the depth keys go to (a glass scene's tree doubles
/// with every level).
pub const MAX_DEPTH: u32 = 16;
/// The first status message, for someone who has never seen the debugger.
pub const WELCOME: &str =
    "arrows pick a pixel, n steps through its trace, Tab changes pane, ? lists every key";
/// How long the file must be quiet before a reload (editors write in bursts).
const RELOAD_DELAY: Duration = Duration::from_millis(150);

pub struct App {
    source: SceneSource,
    /// The last good file's scene, with the file's own settings; shared with
    /// the render thread, never copied.
    scene: Arc<Scene>,
    /// The settings traced: the file's, with the user's toggles.
    settings: Settings,
    /// The selected pixel, in the scene image's coordinates.
    cursor: (u32, u32),
    tree: RayTree,
    /// What-if: how the pixel's tree changed with the last toggle (or
    /// reload), in `record::diff`'s words; cleared when another pixel is picked.
    what_if: Option<String>,
    /// The current event of `tree.events`.
    current: usize,
    collapsed: BTreeSet<NodeId>,
    focus: Pane,
    /// 1 shows the whole image; each doubling halves the pixels per cell.
    zoom: u32,
    view: View,
    plane: DiagramPlane,
    /// The diagram's pan and zoom; fitted again for another pixel or plane.
    diagram_view: PanZoom,
    help: bool,
    help_scroll: u16,
    /// Whether the mistakes menu is open, and its selected row.
    menu: bool,
    menu_row: usize,
    /// The go-to prompt's text while it is open (`:`).
    prompt: Option<String>,
    /// `f` was pressed: the next key says what to find across the image.
    finding: bool,
    /// The find scanning the image in the background, if one runs.
    searching: Option<reach::Searching>,
    /// Background work runs on the caller's thread (tests).
    sync: bool,
    /// The student's image and what `compare` found, with `--compare`.
    compared: Option<Compared>,
    /// The region `w` went to last.
    region: Option<usize>,
    /// The banner: why the last reload failed.
    error: Option<String>,
    /// The status line's message.
    message: Option<String>,
    break_object: Option<usize>,
    /// Manual scroll of the details; `None` follows the current event.
    details_scroll: Option<u16>,
    screen: Rect,
    quit: bool,
    /// The latest finished render, and the term images when a term view asked for them.
    image: Option<RgbImage>,
    terms: Option<TermImages>,
    /// The term images' largest ray and cost counts, worked out once when
    /// they arrive: a redraw then costs the cells shown, not the image.
    count_max: (u32, u32),
    generation: u64,
    terms_generation: Option<u64>,
    renderer: Renderer,
    watcher: Option<FileWatcher>,
    reload_due: Option<Instant>,
    /// How long the last pixel pick and the last render took.
    pick_time: Duration,
    render_time: Option<Duration>,
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
        let compared = Compared { yours, comparison };
        Ok(App::new(source, scene, Some(compared), sync))
    }

    /// The app on a loaded scene: its centre pixel picked, its render asked for.
    fn new(source: SceneSource, scene: Scene, compared: Option<Compared>, sync: bool) -> App {
        let scene = Arc::new(scene);
        let settings = scene.settings;
        let cursor = (scene.width / 2, scene.height / 2);
        let started = Instant::now();
        let tree = record_pixel(&scene, &settings, cursor.0, cursor.1);
        let pick_time = started.elapsed();
        let mut app = App {
            source,
            scene,
            settings,
            cursor,
            tree,
            what_if: None,
            current: 0,
            collapsed: BTreeSet::new(),
            focus: Pane::Image,
            zoom: 1,
            view: View::Image,
            plane: DiagramPlane::Top,
            diagram_view: PanZoom::fit(),
            help: false,
            help_scroll: 0,
            menu: false,
            menu_row: 0,
            prompt: None,
            finding: false,
            searching: None,
            sync,
            compared,
            region: None,
            error: None,
            message: Some(WELCOME.into()),
            break_object: None,
            details_scroll: None,
            screen: Rect::new(0, 0, 120, 40),
            quit: false,
            image: None,
            terms: None,
            count_max: (0, 0),
            generation: 0,
            terms_generation: None,
            renderer: Renderer::new(sync),
            watcher: None,
            reload_due: None,
            pick_time,
            render_time: None,
            show_timings: !sync,
        };
        app.request_render();
        app.collect_renders();
        app
    }

    /// The app watching its scene file for changes, which it reloads on a
    /// later `Action::Tick` (the built-in scene has no file).
    pub fn watching(mut self) -> App {
        let Some(path) = &self.source.path else {
            return self;
        };
        match FileWatcher::new(path) {
            Ok(watcher) => self.watcher = Some(watcher),
            Err(e) => {
                self.message = Some(format!(
                    "cannot watch {} ({e}): press R to reload",
                    path.display()
                ))
            }
        }
        self
    }

    /// Carries out an action: the only way the state changes.
    pub fn update(&mut self, action: Action) {
        if !matches!(action, Action::Tick | Action::Resize(..)) {
            // Time passing and the terminal's size are not the user's
            // doing: the message (the welcome, at first) stays.
            self.message = None;
        }
        match action {
            Action::Tick => self.tick(),
            Action::Quit => {
                self.quit = true;
                self.searching = None;
                self.cancel_renders();
            }
            Action::Suspend => {}
            Action::ToggleHelp => (self.help, self.help_scroll) = (!self.help, 0),
            Action::CloseHelp => self.help = false,
            Action::ScrollHelp(delta) => {
                let most = help::hidden_lines(self.screen.height) as i32;
                self.help_scroll = (self.help_scroll as i32 + delta).clamp(0, most) as u16;
            }
            Action::FocusNext => self.focus = self.focus.next(),
            Action::FocusPrevious => self.focus = self.focus.previous(),
            Action::Move(dx, dy) => self.move_cursor(dx, dy),
            Action::Pick(x, y) => self.pick(x, y),
            Action::Click(column, row) => self.click(column, row),
            Action::ZoomIn => self.zoom_in(),
            Action::ZoomOut => self.zoom = (self.zoom / 2).max(1),
            Action::Step(step) => self.step(step),
            Action::RunTo(breakpoint) => self.run_to(breakpoint),
            Action::RunToObject => self.run_to_object(),
            Action::CycleBreakObject => self.cycle_break_object(),
            Action::SelectRow(delta) => self.select_row(delta),
            Action::ToggleCollapse => self.toggle_collapse(),
            Action::ScrollDetails(delta) => self.scroll_details(delta),
            Action::Toggle(switch) => self.toggle(switch),
            Action::ToggleSpecular => self.toggle_specular(),
            Action::Depth(delta) => self.change_depth(delta),
            Action::CycleView => self.cycle_view(),
            Action::ToggleMistakeMenu => self.menu = !self.menu,
            Action::CloseMistakeMenu => self.menu = false,
            Action::MenuMove(delta) => self.menu_move(delta),
            Action::MenuToggle => self.toggle_mistake(Mistake::ALL[self.menu_row]),
            Action::ToggleMistake(mistake) => self.toggle_mistake(mistake),
            Action::NextRegion => self.next_region(),
            Action::CyclePlane => {
                self.plane = self.plane.next();
                self.diagram_view = PanZoom::fit();
            }
            Action::PanDiagram(dx, dy) => self.diagram_view.pan(dx, dy),
            Action::ZoomDiagram(steps) => self.diagram_view.zoom_by(steps),
            Action::FitDiagram => self.diagram_view = PanZoom::fit(),
            Action::OpenPrompt => self.prompt = Some(String::new()),
            Action::PromptChar(c) => self.prompt_char(c),
            Action::PromptBackspace => self.prompt_backspace(),
            Action::PromptSubmit => self.prompt_submit(),
            Action::PromptCancel => self.prompt = None,
            Action::StartFind => {
                self.finding = true;
                self.message = Some(
                    "find the next pixel with: b blocked shadow, p partly blocked, t TIR, D depth limit, x object X, n near miss"
                        .into(),
                );
            }
            Action::CancelFind => self.finding = false,
            Action::Find(what) => self.find(what),
            Action::Reload => self.reload(),
            Action::Resize(width, height) => self.screen = Rect::new(0, 0, width, height),
        }
        self.collect_renders();
        self.collect_find();
    }

    /// Background work: finished renders, and a reload once the file has
    /// been quiet for `RELOAD_DELAY` after a change.
    fn tick(&mut self) {
        if self.watcher.as_ref().is_some_and(|w| w.changed()) {
            self.reload_due = Some(Instant::now() + RELOAD_DELAY);
        }
        if self.reload_due.is_some_and(|due| Instant::now() >= due) {
            self.reload_due = None;
            self.reload();
        }
    }

    pub fn source(&self) -> &SceneSource {
        &self.source
    }

    /// The last good file's scene, with the file's own settings.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The settings traced: the file's, with the user's toggles.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The selected pixel, in the scene image's coordinates.
    pub fn cursor(&self) -> (u32, u32) {
        self.cursor
    }

    /// The selected pixel's recording.
    pub fn tree(&self) -> &RayTree {
        &self.tree
    }

    /// The current event, an index into `tree().events`.
    pub fn current(&self) -> usize {
        self.current
    }

    /// The rays whose rows the tree pane folds away.
    pub fn collapsed(&self) -> &BTreeSet<NodeId> {
        &self.collapsed
    }

    pub fn focus(&self) -> Pane {
        self.focus
    }

    /// 1 shows the whole image; each doubling halves the pixels per cell.
    pub fn zoom(&self) -> u32 {
        self.zoom
    }

    pub fn view(&self) -> View {
        self.view
    }

    pub fn plane(&self) -> DiagramPlane {
        self.plane
    }

    /// How the diagram is panned and zoomed.
    pub fn diagram_view(&self) -> PanZoom {
        self.diagram_view
    }

    /// Whether the help overlay is open, and how far it is scrolled.
    pub fn help(&self) -> bool {
        self.help
    }

    pub fn help_scroll(&self) -> u16 {
        self.help_scroll
    }

    /// The mistakes menu's selected row (an index into `Mistake::ALL`)
    /// when the menu is open.
    pub fn mistake_menu(&self) -> Option<usize> {
        self.menu.then_some(self.menu_row)
    }

    /// What has the keys: the help, the mistakes menu, or the panes.
    pub fn mode(&self) -> Mode {
        if self.help {
            Mode::Help
        } else if self.menu {
            Mode::Menu
        } else if self.prompt.is_some() {
            Mode::Prompt
        } else if self.finding {
            Mode::Find
        } else {
            Mode::Browsing
        }
    }

    /// The student's image and the comparison, with `--compare`.
    pub fn compared(&self) -> Option<&Compared> {
        self.compared.as_ref()
    }

    /// The comparison's findings, with `--compare`.
    pub fn comparison(&self) -> Option<&Comparison> {
        self.compared.as_ref().map(|c| &c.comparison)
    }

    /// The banner: why the last reload failed.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// The status line's message.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// The object the `x` breakpoint stops at, once chosen.
    pub fn break_object(&self) -> Option<usize> {
        self.break_object
    }

    /// Manual scroll of the details; `None` follows the current event.
    pub fn details_scroll(&self) -> Option<u16> {
        self.details_scroll
    }

    /// The terminal's size, as the last `Action::Resize` gave it.
    pub fn screen(&self) -> Rect {
        self.screen
    }

    /// Whether the user asked to quit.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// The latest render (or preview) of the current settings.
    pub fn image(&self) -> Option<&RgbImage> {
        self.image.as_ref()
    }

    /// The term images, once a term view asked for them.
    pub fn terms(&self) -> Option<&TermImages> {
        self.terms.as_ref()
    }

    /// The scale of a count view (rays or cost): its largest count, as
    /// `TermImages::max_count` has it, but without a scan of the image.
    pub fn count_max(&self, term: Term) -> u32 {
        match term {
            Term::Rays => self.count_max.0,
            _ => self.count_max.1,
        }
    }

    /// How long the last pixel pick took.
    pub fn pick_time(&self) -> Duration {
        self.pick_time
    }

    /// How long the last finished render took.
    pub fn render_time(&self) -> Option<Duration> {
        self.render_time
    }

    /// Whether the status line shows timings (off in tests, for stable screens).
    pub fn show_timings(&self) -> bool {
        self.show_timings
    }

    pub fn panes(&self) -> Panes {
        let banner = self.error.as_ref().map_or(0, |e| e.lines().count() as u16);
        let rows = tree::rows(&self.tree, &self.collapsed).len() as u16;
        layout::panes(self.screen, banner, rows)
    }

    pub fn phong(&self) -> bool {
        self.settings.specular == SpecularModel::Phong
    }

    /// The node the tree and details show: the current event's ray.
    pub fn selected_node(&self) -> NodeId {
        self.tree.events.get(self.current).map_or(0, |e| e.node)
    }

    /// The colour of a pixel as the image pane shows it (render or term view).
    pub fn shown_pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        match self.view {
            View::Image => self.image.as_ref().and_then(|i| pixel(i, x, y)),
            View::Term(term) => self
                .terms
                .as_ref()
                .filter(|t| x < t.width && y < t.height)
                .map(|t| t.rgb(term, (y * t.width + x) as usize, self.count_max(term))),
            View::Yours => self.compared.as_ref().and_then(|c| pixel(&c.yours, x, y)),
            View::ErrorMap => self
                .compared
                .as_ref()
                .and_then(|c| pixel(&c.comparison.error_map, x, y)),
        }
    }

    /// Our pixel at the cursor, as the render (with the toggles) has it.
    pub fn our_pixel(&self) -> Option<[u8; 3]> {
        let (x, y) = self.cursor;
        self.image.as_ref().and_then(|i| pixel(i, x, y))
    }

    /// Re-records the selected pixel in the current scene, keeping the step.
    fn retrace(&mut self) {
        self.cursor = (
            self.cursor.0.min(self.scene.width - 1),
            self.cursor.1.min(self.scene.height - 1),
        );
        let started = Instant::now();
        self.tree = record_pixel(&self.scene, &self.settings, self.cursor.0, self.cursor.1);
        self.pick_time = started.elapsed();
        self.current = self.current.min(self.tree.events.len().saturating_sub(1));
        self.collapsed.clear();
        self.details_scroll = None;
    }

    /// Selects a pixel: only that pixel is traced again.
    fn pick(&mut self, x: u32, y: u32) {
        self.cancel_find();
        self.cursor = (x, y);
        self.current = 0;
        self.what_if = None;
        self.diagram_view = PanZoom::fit();
        self.retrace();
    }

    /// Traces the scene with new settings: the pixel, then the image. The
    /// pixel's tree before and after give the what-if.
    fn apply_settings(&mut self, settings: Settings) {
        self.cancel_find();
        let before = self.tree.clone();
        self.settings = settings;
        self.retrace();
        self.what_if =
            (before.pixel == self.tree.pixel).then(|| crate::record::diff(&before, &self.tree));
        // The details open at the top, on what changed.
        self.details_scroll = self.what_if.as_ref().map(|_| 0);
        self.request_render();
    }

    /// How the selected pixel changed with the last toggle, when it did.
    pub fn what_if(&self) -> Option<&str> {
        self.what_if.as_deref()
    }

    /// Reloads the scene file; a broken file keeps the last good scene.
    fn reload(&mut self) {
        match self.source.load() {
            Ok(file_scene) => {
                let settings =
                    merge_settings(&self.scene.settings, &file_scene.settings, &self.settings);
                self.scene = Arc::new(file_scene);
                self.error = None;
                self.apply_settings(settings);
                self.message = Some(format!("reloaded {}", self.source.name()));
            }
            Err(error) => {
                self.error = Some(error.to_string());
                self.message =
                    Some("the scene file has an error: the last good scene stays".into());
            }
        }
    }
}

/// An image's pixel, `None` outside it.
fn pixel(image: &RgbImage, x: u32, y: u32) -> Option<[u8; 3]> {
    (x < image.width() && y < image.height()).then(|| image.get_pixel(x, y).0)
}
