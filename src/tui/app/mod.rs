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
//! - `ray_log.rs`: `--rays`' log, and the pixel traced set beside it (in
//!   the background: `compare_job.rs`);
//! - `screen.rs`: focus, zoom, the image pane's picture, the diagram's
//!   plane, pan and zoom;
//! - `search.rs`: a find across the image under way.
//!
//! `App` ties them together: an action that concerns several parts (a
//! pick, a toggle, a reload, a find) is carried out here. Drawing and tests
//! read each part as it is (`app.pixel().cursor()`,
//! `app.session().scene()`), and from `App` only what is made of several
//! (the panes' layout, the colour shown at a pixel, whether work is under
//! way); a part's readers are public, its changes private to this folder.
//! Keys become `Action`s in `event.rs` first, and background work
//! (finished renders, a changed scene file, a pixel compared with the
//! log) is looked at on `Action::Tick`.

use std::path::PathBuf;

use image::RgbImage;
use ratatui::layout::Position;

use raystep_engine::scene::{Scene, SceneError, Settings};
use raystep_engine::terms::Term;
use raystep_model::mistakes::Mistakes;
use raystep_tools::compare::{self, Ranked, StudentImage};

use super::action::{Action, Find, Pane, Picture};
use super::source::SceneSource;
use super::view::find;
use super::view::image_grid::{ImageGrid, max_zoom};
use super::view::layout::{self, Panes, inner};
use super::view::mistakes_menu;
use super::view::your_rays;

mod comparing;
mod overlay;
mod pixel;
mod ray_log;
mod renders;
mod screen;
mod search;
mod session;

pub(crate) use comparing::StudentComparison;
pub(crate) use overlay::{Overlay, Overlays};
pub(crate) use pixel::TracedPixel;
pub use ray_log::RayLog;
pub(crate) use renders::Renders;
pub(crate) use screen::Screen;
use search::Search;
use session::Reloaded;
pub(crate) use session::Session;

/// The deepest max_depth the depth keys go to.
pub const MAX_DEPTH: u32 = raystep_engine::scene::DEEPEST_TOGGLED_DEPTH;
/// What `y` and `D` say without a log.
const NO_LOG: &str = "no ray log: open with --rays LOG.jsonl (docs/RAYLOG.md)";
/// What `w`, `c` and `E` say without an image to compare.
const NO_IMAGE: &str = "no image to compare: open with --compare IMAGE.png";
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
    /// The student's ray log, with `--rays`.
    ray_log: Option<RayLog>,
    /// The find scanning the image in the background, if one runs.
    search: Option<Search>,
    /// The status line's message.
    message: Option<String>,
    /// The message shown while the pixel is compared with the log, and
    /// what it becomes once the comparison is back (if it is still shown).
    log_words: Option<(String, LogWords)>,
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
        App::open_sized(path, None, sync)
    }

    /// Opens a scene as `open` does, traced at `size` (`--size WxH`, the
    /// field of view kept) from then on, reloads too.
    pub(crate) fn open_sized(
        path: Option<PathBuf>,
        size: Option<(u32, u32)>,
        sync: bool,
    ) -> Result<App, SceneError> {
        let source = SceneSource { path, size };
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
        let comparison = compare::compare(&scene, student)?;
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
        let ranked = comparison
            .as_ref()
            .map_or(&[][..], |c| &c.findings().mistakes[..]);
        let profile = scene.settings.profile;
        let overlay = Overlays::with_menu(mistakes_menu::order(ranked, profile));
        let session = Session::new(source, scene);
        let pixel = TracedPixel::new(session.scene(), session.settings(), cursor);
        let mut app = App {
            session,
            pixel,
            renders: Renders::new(sync),
            overlay,
            screen: Screen::default(),
            comparison,
            ray_log: None,
            search: None,
            message: Some(WELCOME.into()),
            log_words: None,
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
        let scene = self.session.scene();
        let size = (scene.width, scene.height);
        if pixel.0 >= size.0 || pixel.1 >= size.1 {
            return Err(find::outside(pixel, size));
        }
        self.pick(pixel.0, pixel.1);
        self.say_of_log(LogWords::Opening);
        Ok(self)
    }

    /// The app with the student's ray log (`--rays`, read against this
    /// app's scene), on the log's first pixel.
    pub fn with_ray_log(mut self, log: RayLog) -> App {
        let mut log = log.comparing_in(self.sync);
        let first = log.first_pixel();
        if let (Some(comparison), Some((traced, words))) = (&mut self.comparison, log.verdict()) {
            comparison.supersede_by_log(traced, words);
        }
        self.ray_log = Some(log);
        if let Some((x, y)) = first {
            self.pick(x, y);
        }
        self.say_of_log(LogWords::Opening);
        self
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
            // The main loop suspends the process itself (`tui::run_loop`);
            // the state stays as it is (a test's keys may still bring it here).
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
                // An emitting scene has an emission view after the ambient.
                let views = Term::written_for(self.session.scene());
                self.message = Some(self.screen.next_picture(self.comparison.is_some(), &views));
                let terms = matches!(self.screen.picture(), Picture::Term(_));
                if terms && !self.renders.terms_are_current() {
                    let (scene, settings) = (self.session.shared_scene(), *self.session.settings());
                    self.renders.request_again(scene, settings, true);
                }
            }
            Action::TogglePicture(picture) => {
                self.message = Some(match self.comparison {
                    Some(_) => self.screen.toggle_picture(picture),
                    None => NO_IMAGE.into(),
                });
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
            Action::NextLoggedPixel(delta) => self.next_logged_pixel(delta),
            Action::FirstDivergence => self.first_divergence(),
            Action::PromptSubmit => self.prompt_submit(),
            Action::Find(what) => {
                self.overlay.update(action, height);
                self.find(what);
            }
            Action::Reload => self.reload(),
            Action::ToggleMistakeMenu if self.overlay.menu_row().is_none() => {
                // With --rays, M opens on the mistake the pixel's rays are
                // named with (or consistent with), as --compare opens on
                // the ranking's first.
                if let Some(mistake) = self.ray_log.as_ref().and_then(RayLog::mistake_shown) {
                    self.overlay.select(mistake);
                }
                self.message = self.overlay.update(action, height);
            }
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
        self.collect_reload();
        self.collect_renders();
        self.collect_find();
        self.collect_log();
    }

    /// Selects a pixel: only that pixel is traced again.
    fn pick(&mut self, x: u32, y: u32) {
        self.search = None;
        self.screen.fit_diagram();
        let session = &self.session;
        self.pixel.pick((x, y), session.scene(), session.settings());
        self.follow_log();
    }

    /// Sets the pixel traced, as it is now, beside the student's rays of it.
    fn follow_log(&mut self) {
        if let Some(log) = &mut self.ray_log {
            log.follow(self.pixel.tree(), self.session.shared_scene());
        }
    }

    /// The status line's words on the log's pixel, once it is compared:
    /// until then what they are meanwhile, replaced when it is back.
    fn say_of_log(&mut self, words: LogWords) {
        let Some(log) = &self.ray_log else {
            return;
        };
        let message = words.say(log, self.pixel.cursor());
        self.log_words = log.comparing().then(|| (message.clone(), words));
        self.message = Some(message);
    }

    /// Takes in the comparison of the pixel with the log once it is back;
    /// the words said meanwhile, if still shown, become the final ones.
    fn collect_log(&mut self) {
        let Some(log) = &mut self.ray_log else {
            return;
        };
        if !log.collect() && log.comparing() {
            return;
        }
        if let Some((shown, words)) = self.log_words.take()
            && self.message.as_deref() == Some(shown.as_str())
        {
            self.message = Some(words.say(log, self.pixel.cursor()));
        }
    }

    fn move_cursor(&mut self, dx: i32, dy: i32) {
        let clamp =
            |v: u32, d: i32, size: u32| (v as i64 + d as i64).clamp(0, size as i64 - 1) as u32;
        let (cursor, scene) = (self.pixel.cursor(), self.session.scene());
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
                    let scene = self.session.scene();
                    let (width, height) = (scene.width, scene.height);
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
        match self.ray_log {
            None => self.message = Some(message),
            Some(_) => self.say_of_log(LogWords::Toggled(message)),
        }
    }

    /// Traces the scene with new settings: the pixel, then the image.
    fn apply_settings(&mut self, settings: Settings) {
        self.search = None;
        self.session.set_settings(settings);
        let session = &self.session;
        self.pixel.retrace_with(session.scene(), session.settings());
        self.follow_log();
        self.request_render();
    }

    /// Reloads the scene file beside the keys (`Session::start_reload`).
    fn reload(&mut self) {
        self.session.start_reload(self.sync);
        if !self.sync {
            self.message = Some(format!("reloading {}…", self.session.source().name()));
        }
    }

    /// Takes in the reloaded scene once it has come; a broken file keeps
    /// the last good scene.
    fn collect_reload(&mut self) {
        match self.session.finished_reload() {
            None => {}
            Some(Reloaded::Scene(settings)) => {
                // The file's profile may have changed: the menu follows it
                // (merge_settings has switched off what it does not offer).
                let before = self.session.settings().mistakes;
                self.overlay
                    .set_menu(mistakes_menu::order(self.ranked(), settings.profile));
                self.apply_settings(settings);
                let mut message = format!("reloaded {}", self.session.source().name());
                let gone: Mistakes = before
                    .iter()
                    .filter(|&m| !settings.mistakes.contains(m))
                    .collect();
                if !gone.is_empty() {
                    message += &format!(
                        "; switched off {gone}: no meaning under the {} profile",
                        settings.profile.name()
                    );
                }
                self.message = Some(message);
            }
            Some(Reloaded::Broken) => {
                self.message =
                    Some("the scene file has an error: the last good scene stays".into());
            }
        }
    }

    /// The mistakes the comparison ranks, best first (none without one).
    fn ranked(&self) -> &[Ranked] {
        (self.comparison.as_ref()).map_or(&[][..], |c| &c.findings().mistakes[..])
    }

    /// The cursor to the next region's pixel (the largest first, cycling).
    fn next_region(&mut self) {
        let Some(comparison) = &mut self.comparison else {
            self.message = Some(NO_IMAGE.into());
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

    /// `y` / `Y`: the cursor to the next or previous pixel of the log.
    fn next_logged_pixel(&mut self, delta: i32) {
        let Some(log) = &mut self.ray_log else {
            self.message = Some(NO_LOG.into());
            return;
        };
        let (x, y) = log.step(self.pixel.cursor(), delta);
        self.pick(x, y);
        self.say_of_log(LogWords::Pixel);
    }

    /// `D`: the current event to where the pixel's first divergence from
    /// the log is made, its ray selected, the details at their top (yours
    /// beside ours, and what the divergence is).
    fn first_divergence(&mut self) {
        let Some(log) = &self.ray_log else {
            self.message = Some(NO_LOG.into());
            return;
        };
        let (x, y) = self.pixel.cursor();
        if log.comparing() {
            self.message = Some(format!(
                "still comparing your rays of pixel ({x}, {y}) with ours: D once it is done"
            ));
            return;
        }
        let Some(report) = log.report() else {
            self.message = Some(format!(
                "pixel ({x}, {y}) is not in your log: y goes to a logged pixel"
            ));
            return;
        };
        let Some(first) = &report.first_divergence else {
            self.message = Some(format!(
                "your rays of pixel ({x}, {y}) match ours: no divergence"
            ));
            return;
        };
        let message = format!(
            "first divergence: {} {}, {}: yours beside ours in the details",
            first.path,
            first.field,
            first.kind.name()
        );
        match your_rays::divergence_event(self.pixel.tree(), first) {
            Some(event) => {
                self.pixel.go_to(event);
                self.message = Some(message);
            }
            None => self.message = Some(format!("{message} (no event of ours for it)")),
        }
    }

    /// Enter: go to the pixel typed, or say why not and keep the prompt
    /// open so the text can be corrected.
    fn prompt_submit(&mut self) {
        let Some(text) = self.overlay.prompt() else {
            return;
        };
        let scene = self.session.scene();
        match find::parse_goto(text, (scene.width, scene.height)) {
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
            self.follow_log();
        }
    }

    /// Renders the scene as it is now, as a new generation.
    fn request_render(&mut self) {
        let terms = matches!(self.screen.picture(), Picture::Term(_));
        let (scene, settings) = (self.session.shared_scene(), *self.session.settings());
        self.renders.request(scene, settings, terms);
    }

    /// Takes in the previews and renders that came back.
    fn collect_renders(&mut self) {
        if let Some(failed) = self.renders.collect() {
            self.message = Some(failed);
        }
    }

    // What the panes and tests read: each part as it is, and what is made
    // of several parts.

    /// The scene, its source, the settings traced, the reload's error.
    pub fn session(&self) -> &Session {
        &self.session
    }

    /// The pixel traced: cursor, recording, current event, folded rows.
    pub fn pixel(&self) -> &TracedPixel {
        &self.pixel
    }

    /// The whole image's renders.
    pub fn renders(&self) -> &Renders {
        &self.renders
    }

    /// What is open over the panes, and so what has the keys.
    pub fn overlay(&self) -> &Overlays {
        &self.overlay
    }

    /// The terminal's size, focus, zoom, the picture, the diagram's view.
    pub fn screen(&self) -> &Screen {
        &self.screen
    }

    /// The student's image and what `compare` found, with `--compare`.
    pub fn comparison(&self) -> Option<&StudentComparison> {
        self.comparison.as_ref()
    }

    /// The student's ray log, with `--rays`.
    pub fn ray_log(&self) -> Option<&RayLog> {
        self.ray_log.as_ref()
    }

    pub fn panes(&self) -> Panes {
        let banner = self.session.error().map_or(0, |e| e.lines().count() as u16);
        let only_yours =
            (self.ray_log.as_ref().and_then(RayLog::report)).map_or(0, |r| r.only_yours.len());
        let rows = (self.pixel.rows().len() + only_yours) as u16;
        layout::panes(self.screen.size(), banner, rows)
    }

    /// The image pane's mapping, for drawing and for clicks.
    pub fn image_grid(&self) -> Option<ImageGrid> {
        let size = self.renders.image().map(|i| (i.width(), i.height()))?;
        Some(ImageGrid::new(
            inner(self.panes().image),
            size,
            self.screen.zoom(),
            self.pixel.cursor(),
        ))
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
    pub(crate) fn busy(&self) -> bool {
        self.renders.busy()
            || self.session.reload_waits()
            || self.search.is_some()
            || self.ray_log.as_ref().is_some_and(RayLog::comparing)
    }

    /// What the running find looks for and the row it is on (from 1), of
    /// the image's rows: "finding {what}… (row N of H)".
    pub fn finding_progress(&self) -> Option<(&str, u32, u32)> {
        let (what, row) = self.search.as_ref()?.progress();
        Some((what, row + 1, self.session.scene().height))
    }

    /// Whether the status line shows timings (off in tests, for stable screens).
    pub(crate) fn show_timings(&self) -> bool {
        self.show_timings
    }

    /// The colour of a pixel as the image pane shows it.
    pub fn shown_pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        let renders = &self.renders;
        let comparison = self.comparison.as_ref();
        match self.screen.picture() {
            Picture::Render => renders.image().and_then(|i| pixel(i, x, y)),
            Picture::Term(term) => renders
                .terms()
                .filter(|t| x < t.width && y < t.height)
                .map(|t| t.rgb(term, (y * t.width + x) as usize, renders.count_max(term))),
            Picture::Yours => comparison.and_then(|c| pixel(c.yours(), x, y)),
            Picture::ErrorMap => {
                comparison.and_then(|c| pixel(c.findings().error_map.as_ref()?, x, y))
            }
        }
    }

    /// Our pixel at the cursor, as the render (with the toggles) has it.
    pub(crate) fn our_pixel(&self) -> Option<[u8; 3]> {
        let (x, y) = self.pixel.cursor();
        self.renders.image().and_then(|i| pixel(i, x, y))
    }
}

/// What the status line says of the log's pixel: words that change when
/// its comparison comes back.
enum LogWords {
    /// Which logged pixel it is and how it compares (`y`).
    Pixel,
    /// The log's name and counts too (at open).
    Opening,
    /// What a toggle did (its message), and how the pixel compares now.
    Toggled(String),
}

impl LogWords {
    fn say(&self, log: &RayLog, cursor: (u32, u32)) -> String {
        match self {
            LogWords::Pixel => log.pixel_words(cursor),
            LogWords::Opening => log.opening_words(cursor),
            LogWords::Toggled(message) => {
                let against = match log.report().map(|r| &r.first_divergence) {
                    _ if log.comparing() => format!(" · {}", ray_log::COMPARING),
                    None => String::new(),
                    Some(None) => " · your rays of this pixel match ours".to_string(),
                    Some(Some(d)) => format!(" · your rays first differ at {} {}", d.path, d.field),
                };
                format!("{message}{against}")
            }
        }
    }
}

/// An image's pixel, `None` outside it.
fn pixel(image: &RgbImage, x: u32, y: u32) -> Option<[u8; 3]> {
    (x < image.width() && y < image.height()).then(|| image.get_pixel(x, y).0)
}
