//! Whole debugger screens drawn on ratatui's `TestBackend`, pinned with insta
//! in `snapshots/` (as `tui_screens__<name>.snap`). Every one was read against
//! `raystep inspect` before it was accepted.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use raystep::tui::keymap::{self, Input};
use raystep::tui::{self, Action, App, Mode, Pane, Picture};
use raystep_engine::terms::Term;

use crate::support::debugger::*;

#[test]
fn snapshot_start_screen() {
    let mut app = app();
    snapshot!("start_screen", screen(&mut app, 120, 40).backend());
}

#[test]
fn snapshot_shadowed_pixel() {
    let mut app = app();
    app.update(Action::Pick(80, 82));
    chars(&mut app, "b");
    snapshot!("shadowed_pixel", screen(&mut app, 120, 40).backend());
}

#[test]
fn snapshot_step_through() {
    let mut app = app();
    chars(&mut app, "ioi");
    snapshot!("step_through", screen(&mut app, 120, 40).backend());
}

#[test]
fn snapshot_help_overlay() {
    let mut app = app();
    chars(&mut app, "?");
    snapshot!("help_overlay", screen(&mut app, 120, 40).backend());
}

#[test]
fn snapshot_term_view() {
    let mut app = app();
    chars(&mut app, "vvvvvvv");
    assert_eq!(app.screen().picture(), Picture::Term(Term::Rays));
    snapshot!("term_view_rays", screen(&mut app, 120, 40).backend());
}

#[test]
fn snapshot_error_banner() {
    let path = scene_file("broken.toml");
    let mut app = App::open(Some(path.clone()), true).unwrap();
    edit(&path, "kt = 0.7", "kt = 0.7.5");
    app.update(Action::Reload);
    snapshot!("error_banner", screen(&mut app, 120, 40).backend());
}

#[test]
fn snapshot_too_small() {
    let mut app = app();
    snapshot!("too_small", screen(&mut app, 60, 20).backend());
}

#[test]
fn snapshot_wide_side_view() {
    let mut app = app();
    app.update(Action::Pick(80, 82));
    chars(&mut app, "d");
    snapshot!("wide_side_view", screen(&mut app, 200, 60).backend());
}

/// Timings for the report:
/// `cargo test --release --test suite tui_screens:: -- --ignored --nocapture`.
#[test]
#[ignore = "a measurement, not a check"]
fn measure_pick_and_render_on_the_teapot() {
    let path = PathBuf::from("scenes/spd/teapot.nff");
    if !path.exists() {
        return;
    }
    let mut app = App::open(Some(path), true).unwrap();
    println!(
        "teapot {}x{}, {} objects",
        app.session().scene().width,
        app.session().scene().height,
        app.session().scene().objects.len()
    );
    let mut picks = Vec::new();
    for i in 0..200u32 {
        app.update(Action::Pick(
            (i * 37) % app.session().scene().width,
            (i * 91) % app.session().scene().height,
        ));
        picks.push(app.pixel().pick_time());
    }
    picks.sort();
    println!(
        "pixel pick: median {:?}, max {:?}",
        picks[picks.len() / 2],
        picks[picks.len() - 1]
    );
    for _ in 0..3 {
        let started = Instant::now();
        app.update(Action::Toggle(tui::Switch::Shadows));
        println!(
            "toggle shadows: re-render {:?} (update returned after {:?})",
            app.renders().render_time().unwrap(),
            started.elapsed()
        );
    }
}

#[test]
fn snapshot_mistakes_menu() {
    // no-ambient (row 9) turned on: [x] in the menu, red in the header,
    // the pixel retraced without its ambient term behind the menu.
    let mut app = app();
    chars(&mut app, "Mjjjjjjjjj ");
    snapshot!("mistakes_menu", screen(&mut app, 120, 40).backend());
}

#[test]
fn a_narrow_header_shortens_the_switches_before_the_scene_name() {
    // The scene is named as given: here "scenes/glass.toml", relative to the
    // crate. At 80 columns the long header (" raystep " 9 + " scenes/glass.toml
    // 160x120" 26 + " · shadows reflection transmission ambient · Blinn ·
    // depth 5" 59) needs 94; with the short names (" · shad refl trans amb ·
    // Blinn · depth 5", 38) it needs 73, so the scene's name stays whole.
    let mut app = App::open(Some(PathBuf::from("scenes/glass.toml")), true).unwrap();
    let header = header_row(&mut app, 80);
    assert!(
        header.starts_with(" raystep  scenes/glass.toml 160x120 · shad refl trans amb · Blinn"),
        "{header}"
    );
    // Wide enough, the names are whole.
    let header = header_row(&mut app, 120);
    assert!(
        header.contains("scenes/glass.toml 160x120 · shadows reflection transmission ambient"),
        "{header}"
    );
}

/// The screen's top line at `width` columns.
fn header_row(app: &mut App, width: u16) -> String {
    let terminal = screen(app, width, 24);
    let buffer = terminal.backend().buffer();
    (0..width)
        .map(|x| buffer[(x, 0)].symbol().to_string())
        .collect()
}

/// The key table as the debugger carries it out: for every mode, each row
/// that applies (its help text), and each of its inputs with the action it
/// gives in each pane (the focused one for keys, the one under the mouse
/// for the mouse). It pins `keymap.rs` and `event.rs` together: a key that changes
/// what it does changes this snapshot.
#[test]
fn snapshot_key_table() {
    let openers = [
        (Mode::Browsing, None),
        (Mode::Help, Some(Action::ToggleHelp)),
        (Mode::Menu, Some(Action::ToggleMistakeMenu)),
        (Mode::Prompt, Some(Action::OpenPrompt)),
        (Mode::Find, Some(Action::StartFind)),
    ];
    let mut table = String::new();
    for (mode, opener) in openers {
        let mut app = app();
        if let Some(action) = opener {
            app.update(action);
        }
        assert_eq!(app.overlay().mode(), mode);
        writeln!(table, "{mode:?}").unwrap();
        for row in keymap::rows().filter(|row| row.context.applies(mode)) {
            writeln!(table, "  {}", row.what).unwrap();
            for &(input, _) in row.inputs {
                let actions = in_each_pane(&mut app, input);
                writeln!(table, "    {:<15} {actions}", label(input)).unwrap();
            }
        }
    }
    snapshot!("key_table", table);
}

/// An input's name, each modifier spelled out (`H` is the key, `Shift+h`
/// the key with Shift held); any other key is shown by a `7`.
fn label(input: Input) -> String {
    match input {
        Input::Shift(KeyCode::Char(c)) => format!("Shift+{c}"),
        Input::Ctrl(KeyCode::Char(c)) => format!("Ctrl+{c}"),
        Input::AnyKey => "any other (7)".into(),
        Input::WheelUp => "wheel up".into(),
        Input::WheelDown => "wheel down".into(),
        input => input.name(),
    }
}

/// What `input` does with each pane focused (keys) or under the mouse: one
/// action when every pane gives the same, else each pane's.
fn in_each_pane(app: &mut App, input: Input) -> String {
    let key = |code, modifiers| Event::Key(KeyEvent::new(code, modifiers));
    let panes = app.panes();
    let mut actions: Vec<(Pane, Option<Action>)> = Vec::new();
    for pane in Pane::ALL {
        while app.screen().focus() != pane {
            app.update(Action::FocusNext);
        }
        let area = panes.rect(pane);
        let (column, row) = (area.x + area.width / 2, area.y + area.height / 2);
        let mouse = |kind| {
            Event::Mouse(MouseEvent {
                kind,
                column,
                row,
                modifiers: KeyModifiers::NONE,
            })
        };
        let event = match input {
            Input::Key(code) => key(code, KeyModifiers::NONE),
            Input::Shift(code) => key(code, KeyModifiers::SHIFT),
            Input::Ctrl(code) => key(code, KeyModifiers::CONTROL),
            Input::AnyKey => key(KeyCode::Char('7'), KeyModifiers::NONE),
            Input::Click => mouse(MouseEventKind::Down(MouseButton::Left)),
            Input::WheelUp => mouse(MouseEventKind::ScrollUp),
            Input::WheelDown => mouse(MouseEventKind::ScrollDown),
        };
        actions.push((pane, tui::event::action(&event, app)));
    }
    let said = |action: Option<Action>| action.map_or("nothing".into(), |a| format!("{a:?}"));
    if actions.iter().all(|&(_, action)| action == actions[0].1) {
        return said(actions[0].1);
    }
    let each: Vec<String> = actions
        .iter()
        .map(|&(pane, action)| format!("{pane:?}: {}", said(action)))
        .collect();
    each.join(" · ")
}
