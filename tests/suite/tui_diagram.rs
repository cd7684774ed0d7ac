//! Issue 16, sections 2 and 3: the debugger's diagram pane, its labels
//! never written over one another, and panned and zoomed with the keys
//! while it has the focus.

use std::path::PathBuf;

use crossterm::event::KeyCode;
use ratatui::layout::Rect;
use raystep::tui::{Action, App, Pane};
use raystep_tools::diagram::{Diagram, Progress};

use crate::support::debugger::*;

/// Seven-rays with its two lights replaced by two a hair apart, so that
/// in the top view they land on one cell.
fn two_lamps() -> PathBuf {
    let path = scene_file("two-lamps.toml");
    edit(
        &path,
        "name = \"key\"\nposition = [-4, 6, 6]",
        "name = \"lamp A\"\nposition = [3, 3, 4]",
    );
    edit(
        &path,
        "name = \"fill\"\nposition = [5, 3, 4]",
        "name = \"lamp B\"\nposition = [3.02, 3, 4]",
    );
    path
}

/// The diagram pane's rows, inside its border.
fn diagram_rows(app: &mut App) -> Vec<String> {
    let terminal = screen(app, 120, 40);
    let buffer = terminal.backend().buffer();
    let Rect {
        x,
        y,
        width,
        height,
    } = app.panes().diagram;
    (y + 1..y + height - 1)
        .map(|row| {
            (x + 1..x + width - 1)
                .map(|col| buffer[(col, row)].symbol())
                .collect()
        })
        .collect()
}

/// The diagram pane's top border, with its title.
fn diagram_title(app: &mut App) -> String {
    let terminal = screen(app, 120, 40);
    let buffer = terminal.backend().buffer();
    let Rect { x, y, width, .. } = app.panes().diagram;
    (x..x + width)
        .map(|col| buffer[(col, y)].symbol())
        .collect()
}

/// The (column, row) of the first cell holding `symbol`.
fn find(rows: &[String], symbol: char) -> Option<(usize, usize)> {
    rows.iter()
        .enumerate()
        .find_map(|(r, line)| line.chars().position(|c| c == symbol).map(|c| (c, r)))
}

fn focus_diagram(app: &mut App) {
    while app.screen().focus() != Pane::Diagram {
        app.update(Action::FocusNext);
    }
}

#[test]
fn two_lights_on_one_cell_keep_both_names_readable() {
    // Before: "☼ lamp B" was printed over "☼ lamp A" on the same cell, and
    // only "lamp B" could be read. Now one ☼ marks the cell and each name
    // has its own place.
    let mut app = App::open(Some(two_lamps()), true).unwrap();
    let rows = diagram_rows(&mut app);
    let text = rows.join("\n");
    assert!(text.contains("lamp A"), "{text}");
    assert!(text.contains("lamp B"), "{text}");
    assert!(text.contains("eye"), "{text}");
    assert_eq!(text.matches('☼').count(), 1, "{text}");
}

#[test]
fn with_the_diagram_focused_arrows_pan_it_and_keep_the_pixel() {
    let mut app = app();
    focus_diagram(&mut app);
    let pixel = app.pixel().cursor();
    // The status line says what the arrows do here.
    let status = {
        let terminal = screen(&mut app, 120, 40);
        let buffer = terminal.backend().buffer();
        (0..120)
            .map(|x| buffer[(x, 39)].symbol())
            .collect::<String>()
    };
    assert!(
        status.contains("arrows pan diagram  +/- zoom  0 fit"),
        "{status}"
    );
    let (eye_col, eye_row) = find(&diagram_rows(&mut app), '◉').expect("the eye is drawn");
    press(&mut app, &[key(KeyCode::Right)]);
    assert_eq!(app.pixel().cursor(), pixel, "the pixel stays");
    // The window moved right by a quarter of its width: the eye a quarter
    // of the pane's width left (within a cell of rounding).
    let width = app.panes().diagram.width as usize - 2;
    let (col, row) = find(&diagram_rows(&mut app), '◉').expect("still in view");
    assert_eq!(row, eye_row);
    assert!(
        (eye_col - col).abs_diff(width / 4) <= 1,
        "{eye_col} -> {col} in {width}"
    );
    // Back left, and the eye is where it was.
    press(&mut app, &[key(KeyCode::Left)]);
    assert_eq!(find(&diagram_rows(&mut app), '◉'), Some((eye_col, eye_row)));
}

#[test]
fn plus_zooms_the_diagram_and_zero_or_a_new_pixel_fits_it_again() {
    let mut app = app();
    focus_diagram(&mut app);
    let fitted = diagram_rows(&mut app);
    let image_zoom = app.screen().zoom();
    chars(&mut app, "+");
    assert_eq!(app.screen().diagram_pan_zoom().zoom(), 1);
    assert_eq!(app.screen().zoom(), image_zoom, "the image keeps its zoom");
    // Zoomed about the primary ray's first hit, not the window's centre
    // (as `raystep diagram --zoom`); the title says by how much (1.5).
    assert!(
        diagram_title(&mut app).contains("· zoom 1.5× ·"),
        "{}",
        diagram_title(&mut app)
    );
    chars(&mut app, "0");
    assert!(app.screen().diagram_pan_zoom().is_fit());
    assert!(!diagram_title(&mut app).contains("zoom"), "none at 1");
    chars(&mut app, "+");
    press(&mut app, &[key(KeyCode::Home)]);
    assert!(app.screen().diagram_pan_zoom().is_fit(), "Home fits it too");
    assert_eq!(diagram_rows(&mut app), fitted);
    // A pan, then another pixel: the diagram fits the new pixel's rays.
    press(&mut app, &[key(KeyCode::Right)]);
    chars(&mut app, "-");
    assert!(!app.screen().diagram_pan_zoom().is_fit());
    let (x, y) = app.pixel().cursor();
    app.update(Action::Pick(x + 1, y));
    assert!(app.screen().diagram_pan_zoom().is_fit());
    // So does another plane.
    chars(&mut app, "+");
    chars(&mut app, "d");
    assert!(app.screen().diagram_pan_zoom().is_fit());
}

#[test]
fn zooming_the_diagram_keeps_the_hit_object_in_view() {
    // prism.toml's middle pixel hits the prism, far from the middle of the
    // fitted window (which also holds the eye, the lamp and the green
    // wall behind them). Zoomed about the window's centre, three steps
    // (3.375×) pushed the prism out; zoomed about the hit, its outline
    // and its name stay.
    let mut app = App::open(Some(PathBuf::from("scenes/prism.toml")), true).unwrap();
    focus_diagram(&mut app);
    assert!(diagram_rows(&mut app).join("\n").contains("prism"));
    chars(&mut app, "+++");
    assert!(diagram_title(&mut app).contains("zoom 3.375×"));
    let text = diagram_rows(&mut app).join("\n");
    assert!(text.contains("prism"), "{text}");
}

#[test]
fn a_plane_hit_by_a_ray_is_named() {
    // polygons.toml's pixel (40, 54): the primary ray ends on the back
    // wall, a plane, which had no name in the pane.
    let mut app = App::open(Some(PathBuf::from("scenes/polygons.toml")), true).unwrap();
    app.update(Action::Pick(40, 54));
    let text = diagram_rows(&mut app).join("\n");
    assert!(text.contains("back wall"), "{text}");
}

/// The diagram pane's bottom-right corner rows, where the key to its
/// marks goes.
fn key_rows(app: &mut App) -> String {
    let rows = diagram_rows(app);
    rows[rows.len() - 2..].join("\n")
}

#[test]
fn a_polygon_passed_by_is_ringed_in_the_pane_as_in_the_figure() {
    // polygons.toml's pixel (40, 54): the primary ray passes the star by
    // (tests/suite/figure.rs: the SVG rings it). The pane showed no ring: now a
    // ○ where the ray crosses the star's plane, "passed by" beside it (the
    // star, which blocks a shadow ray, is named at its outline already)
    // and in the key; no light faces away from the back wall's hit, so
    // no dotted line's key.
    let mut app = App::open(Some(PathBuf::from("scenes/polygons.toml")), true).unwrap();
    app.update(Action::Pick(40, 54));
    let text = diagram_rows(&mut app).join("\n");
    assert_eq!(text.matches('○').count(), 1 + 1, "ring and key: {text}");
    assert!(key_rows(&mut app).contains("○ passed by"), "{text}");
    assert_eq!(text.matches("passed by").count(), 2, "{text}");
    assert!(!text.contains("faces away"), "{text}");
    // The same marks as `raystep diagram` draws from the same assembly.
    let scene = raystep_engine::scene::load(std::path::Path::new("scenes/polygons.toml")).unwrap();
    let tree = raystep_engine::record::record_pixel(&scene, &scene.settings, 40, 54);
    let diagram = Diagram::new(&scene, &tree, app.screen().plane(), Progress::done(&tree));
    let svg = raystep_tools::diagram::svg::figure(&diagram, 1.0);
    assert_eq!(diagram.passed.len(), 1);
    assert_eq!(svg.matches("class=\"passed-by\"").count(), 1);
    assert!(!svg.contains("light facing away"));
}

#[test]
fn a_light_facing_away_is_dotted_and_keyed_in_the_pane() {
    // glass.toml's pixel (135, 58): two lights face away from hits (the
    // figure's test counts them); the pane's key says what the grey
    // dotted lines are, as the SVG's legend does. No ray passes anything
    // by: no ring in either.
    let mut app = App::open(Some(PathBuf::from("scenes/glass.toml")), true).unwrap();
    app.update(Action::Pick(135, 58));
    let text = diagram_rows(&mut app).join("\n");
    assert!(key_rows(&mut app).contains("┈ light faces away"), "{text}");
    assert!(!text.contains('○'), "{text}");
    let scene = raystep_engine::scene::load(std::path::Path::new("scenes/glass.toml")).unwrap();
    let tree = raystep_engine::record::record_pixel(&scene, &scene.settings, 135, 58);
    let diagram = Diagram::new(&scene, &tree, app.screen().plane(), Progress::done(&tree));
    assert_eq!(diagram.faces_away.len(), 2);
    assert!(diagram.passed.is_empty());
    let svg = raystep_tools::diagram::svg::figure(&diagram, 1.0);
    assert!(svg.contains(">light facing away (no shadow ray)<"));
    assert!(!svg.contains("class=\"passed-by\""));
}
