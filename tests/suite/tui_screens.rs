//! Whole debugger screens drawn on ratatui's `TestBackend`, pinned with insta
//! in `snapshots/` (as `tui_screens__<name>.snap`). Every one was read against
//! `raystep inspect` before it was accepted.

use std::path::PathBuf;
use std::time::Instant;

use raystep::terms::Term;
use raystep::tui::{self, Action, App, View};

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
    assert_eq!(app.view(), View::Term(Term::Rays));
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

/// Timings for the report: `cargo test --release --test tui -- --ignored --nocapture`.
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
        app.scene().width,
        app.scene().height,
        app.scene().objects.len()
    );
    let mut picks = Vec::new();
    for i in 0..200u32 {
        app.update(Action::Pick(
            (i * 37) % app.scene().width,
            (i * 91) % app.scene().height,
        ));
        picks.push(app.pick_time());
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
            app.render_time().unwrap(),
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
