//! Helpers shared by the debugger's test files: an app on the built-in
//! scene, keys fed through the real key mapping, and screens on `TestBackend`.

use std::path::{Path, PathBuf};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use raystep::tui::{self, App};

/// The built-in seven-rays scene, rendering synchronously.
pub fn app() -> App {
    App::open(None, true).expect("the built-in scene loads")
}

pub fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::from(code))
}

pub fn shift(c: char) -> Event {
    Event::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::SHIFT))
}

/// Feeds terminal events through the same mapping the main loop uses.
pub fn press(app: &mut App, events: &[Event]) {
    for event in events {
        if let Some(action) = tui::event::action(event, app) {
            app.update(action);
        }
    }
}

pub fn chars(app: &mut App, keys: &str) {
    let events: Vec<Event> = keys.chars().map(|c| key(KeyCode::Char(c))).collect();
    press(app, &events);
}

pub fn screen(app: &mut App, width: u16, height: u16) -> Terminal<TestBackend> {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    tui::draw(&mut terminal, app).unwrap();
    terminal
}

/// A copy of the seven-rays scene in a fixed relative place, so error
/// messages name the same path on every machine.
pub fn scene_file(name: &str) -> PathBuf {
    let dir = Path::new("target/tui-tests");
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, include_str!("../../../scenes/seven-rays.toml")).unwrap();
    path
}

pub fn edit(path: &Path, from: &str, to: &str) {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains(from), "{from} not in the scene");
    std::fs::write(path, text.replace(from, to)).unwrap();
}

/// Pumps `Action::Tick` until the app's background find has ended (its
/// result, if any, taken in), or panics after `limit`.
pub fn until_found(app: &mut App, limit: std::time::Duration) {
    let deadline = std::time::Instant::now() + limit;
    while app.finding_progress().is_some() {
        assert!(std::time::Instant::now() < deadline, "the find never ended");
        std::thread::sleep(std::time::Duration::from_millis(5));
        app.update(tui::Action::Tick);
    }
}
