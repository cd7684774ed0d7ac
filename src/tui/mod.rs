//! The interactive debugger: pick a pixel, walk its ray tree, step through
//! the trace event by event, and flip the model's terms on and off.
//!
//! The structure follows ratatui's event-driven template:
//!
//! - `app/`: the state, in parts that own their fields (the overlay, the
//!   pixel traced, the renders, the session, the comparison, the ray log);
//!   `App::update(Action)` is the only place it changes, and the rest reads
//!   it through accessors.
//! - `action.rs`: what can be asked for, and the words it is said in
//!   (panes, steps, breakpoints, finds). Terminal events become `Action`s in
//!   `event.rs` by the one key table in `keymap.rs` (which the help and the
//!   status line also read); the main loop below adds `Action::Tick`, on
//!   which the app takes in finished renders and reloads a changed file.
//! - `view/`: what the panes show, worked out without drawing (tree rows,
//!   the step list, stepping, the image grid,
//!   layout). Pure and unit tested; the state uses it, it knows no pane.
//! - `pane/`: the drawing, one file per pane; `pane::draw` only reads an `App`.
//! - `render_job.rs` renders whole images on a background thread, and
//!   `find_job.rs` scans them for `f`; picking a pixel retraces that pixel
//!   alone, and `compare_job.rs` compares it with `--rays`' log. `source.rs` loads and watches the scene file,
//!   `terminal.rs` sets the terminal up and restores it.
//!
//! The main loop is generic over the ratatui `Backend`, so tests drive the
//! real app on a `TestBackend`.

pub(crate) mod action;
pub mod app;
pub(crate) mod compare_job;
pub mod event;
pub(crate) mod find_job;
pub mod keymap;
pub mod pane;
pub(crate) mod render_job;
pub(crate) mod source;
mod terminal;

pub use terminal::give_back_unlocked;
pub mod view;

use std::collections::VecDeque;
use std::io::{self, IsTerminal};
use std::path::Path;
use std::process::ExitCode;
use std::time::Duration;

use anyhow::{Result, bail};
use crossterm::event::Event;
use ratatui::Terminal;
use ratatui::backend::Backend;

pub use action::{Action, Find, Pane, Picture};
pub use app::App;
pub use keymap::Mode;
pub use raystep_engine::scene::Switch;

/// Where terminal events come from: the real terminal, or a script in tests.
pub trait Input {
    /// The next event, waiting at most `timeout`; `None` when none came.
    fn next(&mut self, timeout: Duration) -> io::Result<Option<Event>>;

    /// Ctrl+Z: give the terminal back and stop until continued. A script
    /// has no terminal to give back: nothing happens.
    fn suspend(&mut self) {}

    /// Whether the process was stopped and continued since the last call,
    /// so that the screen must be cleared and drawn whole.
    fn continued(&mut self) -> bool {
        false
    }
}

/// crossterm's event queue.
pub(crate) struct TerminalInput;

impl Input for TerminalInput {
    fn next(&mut self, timeout: Duration) -> io::Result<Option<Event>> {
        if crossterm::event::poll(timeout)? {
            crossterm::event::read().map(Some)
        } else {
            Ok(None)
        }
    }

    fn suspend(&mut self) {
        terminal::suspend();
    }

    fn continued(&mut self) -> bool {
        terminal::continued()
    }
}

/// Scripted events; when they run out, the app is asked to quit.
impl Input for VecDeque<Event> {
    fn next(&mut self, _timeout: Duration) -> io::Result<Option<Event>> {
        Ok(Some(self.pop_front().unwrap_or_else(|| {
            Event::Key(crossterm::event::KeyEvent::from(
                crossterm::event::KeyCode::Char('q'),
            ))
        })))
    }
}

/// Draws one frame, first telling the app the terminal's size.
pub fn draw<B: Backend>(terminal: &mut Terminal<B>, app: &mut App) -> Result<()>
where
    B::Error: Send + Sync + 'static,
{
    let size = terminal.size()?;
    let known = app.screen().size();
    if (size.width, size.height) != (known.width, known.height) {
        app.update(Action::Resize(size.width, size.height));
    }
    terminal.draw(|frame| {
        pane::draw(frame, app);
        // Names are data: ratatui drops control characters from text, but
        // keeps U+FFFE and U+FFFF; a cell holding one shows U+FFFD instead.
        for cell in &mut frame.buffer_mut().content {
            if cell
                .symbol()
                .contains(raystep_engine::printable::unprintable)
            {
                cell.set_symbol("\u{fffd}");
            }
        }
    })?;
    Ok(())
}

/// Clears the screen, which after a stop may hold anything (the shell's
/// prompt), so that the next frame is drawn whole. Not `Terminal::clear`:
/// it asks the terminal where the cursor is, a round trip that fails the
/// debugger when nothing answers.
fn clear<B: Backend>(terminal: &mut Terminal<B>) -> Result<()>
where
    B::Error: Send + Sync + 'static,
{
    terminal.backend_mut().clear()?;
    // An empty frame: the next one then differs from it in every cell it fills.
    terminal.draw(|_| {})?;
    Ok(())
}

/// The main loop: draw, wait for an event or for background work, and turn
/// both into actions. It redraws after an event, and after a tick while
/// background work is under way (or has just ended); after a stop (Ctrl+Z,
/// SIGTSTP, SIGSTOP) and continue, it clears the screen and draws it whole.
pub fn run_loop<B: Backend>(
    terminal: &mut Terminal<B>,
    app: &mut App,
    input: &mut impl Input,
) -> Result<()>
where
    B::Error: Send + Sync + 'static,
{
    let mut dirty = true;
    while !app.should_quit() {
        if input.continued() {
            clear(terminal)?;
            dirty = true;
        }
        if dirty {
            draw(terminal, app)?;
        }
        let busy = app.busy();
        let timeout = Duration::from_millis(if busy { 50 } else { 250 });
        dirty = false;
        if let Some(event) = input.next(timeout)? {
            match event::action(&event, app) {
                Some(Action::Suspend) => input.suspend(),
                Some(action) => app.update(action),
                None => {}
            }
            dirty = true;
        }
        app.update(Action::Tick);
        dirty |= busy || app.busy();
    }
    Ok(())
}

/// What the debugger opens on: the scene file (`None`: the built-in
/// scene), the student's image, the pixel and the ray log asked for.
pub(crate) struct Opening<'a> {
    pub(crate) scene: Option<&'a Path>,
    pub(crate) compare: Option<&'a Path>,
    pub(crate) pixel: Option<(u32, u32)>,
    pub(crate) rays: Option<&'a Path>,
    /// `--size WxH`: the image size traced (and the log's pixels read at).
    pub(crate) size: Option<(u32, u32)>,
}

/// `raystep [debug] [SCENE] [--compare IMAGE.png] [--pixel X,Y] [--rays
/// LOG.jsonl]`: runs the debugger in the terminal. The student's image and
/// ray log are read and the pixel checked first: a bad one is reported
/// (exit 1) whether or not there is a terminal, and before it is taken.
pub(crate) fn run(opening: Opening) -> Result<ExitCode> {
    let Opening {
        scene: path,
        compare,
        pixel,
        rays,
        size,
    } = opening;
    let student = compare
        .map(raystep_tools::compare::student::load)
        .transpose()?;
    if let (Some(student), Some((w, h))) = (&student, size)
        && student.image.dimensions() != (w, h)
    {
        let (iw, ih) = student.image.dimensions();
        bail!(
            "--size {w}x{h} is not the size of the image compared, {iw}x{ih}: give one or the other"
        );
    }
    let size = student.as_ref().map(|s| s.image.dimensions()).or(size);
    let mut ray_log = None;
    if pixel.is_some() || rays.is_some() {
        // Traced at the image's size with --compare, and the log's pixels with it.
        let source = source::SceneSource {
            path: path.map(Path::to_path_buf),
            size,
        };
        let scene = source.load()?;
        let size = (scene.width, scene.height);
        if let Some(pixel) = pixel
            && (pixel.0 >= size.0 || pixel.1 >= size.1)
        {
            bail!("--pixel: {}", view::find::outside(pixel, size));
        }
        ray_log = rays.map(|log| app::RayLog::read(&scene, log)).transpose()?;
    }
    if !io::stdin().is_terminal() || !io::stdout().is_terminal() {
        bail!(
            "the debugger needs a terminal (stdin and stdout must be a TTY); \
             without one, use `raystep render SCENE -o image.png` for the image \
             or `raystep inspect SCENE --pixel X,Y` for one pixel's ray tree"
        );
    }
    if let Some(image) = compare {
        // Seconds on a large scene, before the screen changes: say why.
        // The path is argv's: spelt as names are (`raystep_engine::printable`).
        let shown = image.display().to_string();
        eprintln!(
            "comparing {} with the scene…",
            raystep_engine::printable::printable_text(&shown)
        );
    }
    let path = path.map(Path::to_path_buf);
    let mut app = match student {
        Some(student) => App::open_with(path, Some(student), false)?,
        None => App::open_sized(path, size, false)?,
    }
    .watching();
    if let Some(log) = ray_log {
        app = app.with_ray_log(log);
    }
    if let Some(pixel) = pixel {
        app = app.at_pixel(pixel).map_err(anyhow::Error::msg)?;
    }
    let result = terminal::take()
        .and_then(|mut terminal| run_loop(&mut terminal, &mut app, &mut TerminalInput));
    terminal::restore();
    result.map(|()| ExitCode::SUCCESS)
}
