//! Issue 16, sections 2 and 5: reaching any pixel in a few keys, and term
//! views that redraw in the time of the cells shown.

use std::path::Path;
use std::time::Duration;

use crossterm::event::KeyCode;
use raystep::tui::{Action, App, Mode, Picture};
use raystep_engine::record::{EventKind, record_pixel};
use raystep_engine::terms::Term;
use raystep_model::mistakes::{Mistake, Mistakes};

use crate::support::debugger::*;
use crate::support::{raystep, stderr};

/// A term view's pixels, scaled as the image files scale them: each
/// rescanning the whole image for its maximum (the slow way the pane
/// used to take, once per shown pixel).
fn slow_pixel(app: &App, term: Term, x: u32, y: u32) -> [u8; 3] {
    let terms = app.renders().terms().unwrap();
    terms.rgb(term, (y * terms.width + x) as usize, terms.max_count(term))
}

#[test]
fn count_views_show_the_pixels_scaled_by_the_whole_image() {
    let mut app = app();
    while app.screen().picture() != Picture::Term(Term::Rays) {
        app.update(Action::CyclePicture);
    }
    let (width, height) = (app.session().scene().width, app.session().scene().height);
    for term in [Term::Rays, Term::Cost] {
        // The scale matters only when counts differ: a miss casts 1 ray,
        // the glass in the middle many more.
        assert!(
            app.renders().terms().unwrap().max_count(term) > 1,
            "{term:?}"
        );
        assert_eq!(
            app.renders().count_max(term),
            app.renders().terms().unwrap().max_count(term),
            "{term:?}"
        );
        for y in 0..height {
            for x in 0..width {
                assert_eq!(
                    app.shown_pixel(x, y),
                    Some(slow_pixel(&app, term, x, y)),
                    "{term:?} at ({x}, {y})"
                );
            }
        }
        app.update(Action::CyclePicture);
    }
}

/// The recording the app shows is the one `record_pixel` makes of the
/// cursor's pixel, with the same settings.
fn assert_shows_pixel(app: &App, pixel: (u32, u32)) {
    assert_eq!(app.pixel().cursor(), pixel);
    let expected = record_pixel(
        app.session().scene(),
        app.session().settings(),
        pixel.0,
        pixel.1,
    );
    assert_eq!(
        serde_json::to_value(&app.pixel().tree().nodes).unwrap(),
        serde_json::to_value(&expected.nodes).unwrap()
    );
}

#[test]
fn colon_then_x_comma_y_and_enter_goes_to_that_pixel() {
    let mut app = app();
    assert_eq!(app.pixel().cursor(), (80, 60), "the centre of 161x121");
    chars(&mut app, ":120,40");
    assert_eq!(app.overlay().mode(), Mode::Prompt);
    assert_eq!(app.overlay().prompt(), Some("120,40"));
    assert_eq!(app.pixel().cursor(), (80, 60), "nothing moves while typing");
    press(&mut app, &[key(KeyCode::Enter)]);
    assert_eq!(app.overlay().mode(), Mode::Browsing);
    assert_shows_pixel(&app, (120, 40));
    assert_eq!(app.pixel().current(), 0);
}

#[test]
fn the_prompt_says_why_bad_input_is_refused_and_esc_cancels() {
    let mut app = app();
    chars(&mut app, ":161,3");
    press(&mut app, &[key(KeyCode::Enter)]);
    // x runs 0..161 in the 161x121 image: 161 is one past the edge.
    let message = app.message().unwrap();
    assert!(message.contains("outside the 161x121 image"), "{message}");
    assert_eq!(
        app.overlay().prompt(),
        Some("161,3"),
        "kept, to be corrected"
    );
    let mut terminal = screen(&mut app, 120, 40);
    let status = row_text(&mut terminal, 39);
    assert!(status.contains("go to X,Y: 161,3"), "{status}");
    assert!(status.contains("outside the 161x121 image"), "{status}");
    press(
        &mut app,
        &[key(KeyCode::Backspace), key(KeyCode::Backspace)],
    );
    chars(&mut app, "x");
    press(&mut app, &[key(KeyCode::Enter)]);
    assert!(app.message().unwrap().contains("expected X,Y"));
    press(&mut app, &[key(KeyCode::Esc)]);
    assert_eq!(app.overlay().mode(), Mode::Browsing);
    assert_eq!(app.pixel().cursor(), (80, 60));
    assert!(
        !app.should_quit(),
        "Esc closed the prompt, not the debugger"
    );
}

fn row_text(terminal: &mut ratatui::Terminal<ratatui::backend::TestBackend>, y: u16) -> String {
    let buffer = terminal.backend().buffer();
    (0..buffer.area.width)
        .map(|x| buffer[(x, y)].symbol().to_string())
        .collect()
}

fn glass() -> App {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/glass.toml");
    App::open(Some(path), true).unwrap()
}

#[test]
fn f_t_finds_the_next_pixel_with_total_internal_reflection() {
    let mut app = glass();
    let start = app.pixel().cursor();
    let (width, height) = (app.session().scene().width, app.session().scene().height);
    // Independently: the pixels in reading order after the cursor (then
    // from the top), the first whose tree has a node that refracted with TIR.
    let (scene, settings) = (app.session().scene().clone(), *app.session().settings());
    let has_tir = |x, y| {
        record_pixel(&scene, &settings, x, y)
            .nodes
            .iter()
            .any(|n| n.refraction.is_some_and(|r| r.tir))
    };
    let after = (start.1 * width + start.0 + 1..width * height)
        .chain(0..=start.1 * width + start.0)
        .map(|i| (i % width, i / width));
    let expected = after
        .clone()
        .find(|&(x, y)| has_tir(x, y))
        .expect("glass has TIR");
    chars(&mut app, "ft");
    assert_shows_pixel(&app, expected);
    assert!(
        matches!(
            app.pixel().tree().events[app.pixel().current()].kind,
            EventKind::Refraction { tir: true }
        ),
        "the TIR is the current event"
    );
    assert!(app.message().unwrap().contains("total internal reflection"));
    // Once more: the next one after that.
    let next = after
        .skip_while(|&p| p != expected)
        .skip(1)
        .chain([expected])
        .find(|&(x, y)| has_tir(x, y))
        .unwrap();
    chars(&mut app, "ft");
    assert_eq!(app.pixel().cursor(), next);
}

#[test]
fn f_d_finds_the_depth_limit_where_the_mistake_puts_it() {
    // mirrors.toml (max_depth 5) with depth-off-by-one, turned on in the
    // mistakes menu (row 8 of the catalogue): rays of depth 5 - 1 = 4
    // spawn nothing, so no ray reaches depth 5 and the rays the limit cuts
    // are those that hit a mirror (k_s = 0.85) at depth 4.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/mirrors.toml");
    let mut app = App::open(Some(path), true).unwrap();
    let start = app.pixel().cursor();
    chars(&mut app, "Mjjjjjjjj ");
    assert_eq!(
        app.session().settings().mistakes,
        Mistakes::NONE.with(Mistake::DepthOffByOne)
    );
    chars(&mut app, "M");
    // Independently: the first pixel in reading order after the cursor with
    // a ray that hit a reflective or transparent material at depth 4.
    let (scene, settings) = (app.session().scene().clone(), *app.session().settings());
    let (width, height) = (scene.width, scene.height);
    let cut = |x, y| {
        record_pixel(&scene, &settings, x, y).nodes.iter().any(|n| {
            n.hit.as_ref().is_some_and(|h| {
                n.depth == settings.max_depth - 1 && (h.factors.ks > 0.0 || h.factors.kt > 0.0)
            })
        })
    };
    let expected = (start.1 * width + start.0 + 1..width * height)
        .chain(0..=start.1 * width + start.0)
        .map(|i| (i % width, i / width))
        .find(|&(x, y)| cut(x, y))
        .expect("mirrors.toml has rays that reach depth 4 on a mirror");
    chars(&mut app, "fD");
    let message = app.message().unwrap_or_default().to_string();
    assert_shows_pixel(&app, expected);
    assert!(message.contains("depth limit"), "{message}");
    // The current event is the cast of the ray the limit stopped, at depth 4.
    assert!(
        matches!(
            app.pixel().tree().events[app.pixel().current()].kind,
            EventKind::RayCast { depth: 4, .. }
        ),
        "{message}"
    );
}

#[test]
fn a_find_with_nothing_to_find_says_none_in_the_image() {
    // With shadows off (s) no shadow ray is cast, so none is blocked.
    let mut app = app();
    chars(&mut app, "s");
    assert!(!app.session().settings().switches.shadows);
    chars(&mut app, "fb");
    assert_eq!(app.pixel().cursor(), (80, 60));
    let message = app.message().unwrap();
    assert!(message.contains("none in the image"), "{message}");
    // Any other key after f cancels it and does nothing else.
    chars(&mut app, "fq");
    assert!(!app.should_quit());
    assert_eq!(app.overlay().mode(), Mode::Browsing);
}

#[test]
fn pixel_opens_the_debugger_on_that_pixel() {
    let app = glass().at_pixel((3, 4)).unwrap();
    assert_shows_pixel(&app, (3, 4));
    let opened = glass();
    let (width, height) = (
        opened.session().scene().width,
        opened.session().scene().height,
    );
    let Err(why) = glass().at_pixel((width, 0)) else {
        panic!("a pixel one past the right edge opened");
    };
    assert!(
        why.contains(&format!("outside the {width}x{height} image")),
        "{why}"
    );
}

/// `--pixel` outside the image is refused before the terminal is looked at:
/// exit 1, the message, nothing on stdout.
#[test]
fn pixel_outside_the_image_is_refused_before_the_terminal() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/seven-rays.toml");
    for args in [
        vec!["debug", scene, "--pixel", "161,0"],
        vec![scene, "--pixel", "0,121"],
    ] {
        let output = raystep(&args);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(message.contains("outside the 161x121 image"), "{message}");
        assert!(output.stdout.is_empty());
    }
    // Inside, it gets as far as the terminal check.
    let output = raystep(&["debug", scene, "--pixel", "160,120"]);
    assert!(
        stderr(&output).contains("needs a terminal"),
        "{}",
        stderr(&output)
    );
}

/// glass.toml, its find running in the background (as in the terminal).
fn glass_in_background() -> App {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/glass.toml");
    App::open(Some(path), false).unwrap()
}

/// The last pixel in reading order whose tree has a TIR: a find for TIR
/// from there scans nearly the whole image before it wraps to the first.
fn last_tir_pixel(app: &App) -> (u32, u32) {
    let (scene, settings) = (app.session().scene().clone(), *app.session().settings());
    let (width, height) = (scene.width, scene.height);
    (0..width * height)
        .rev()
        .map(|i| (i % width, i / width))
        .find(|&(x, y)| {
            record_pixel(&scene, &settings, x, y)
                .nodes
                .iter()
                .any(|n| n.refraction.is_some_and(|r| r.tir))
        })
        .unwrap()
}

#[test]
fn a_background_find_ends_where_the_synchronous_one_does() {
    let mut sync = glass();
    chars(&mut sync, "ft");
    let mut app = glass_in_background();
    chars(&mut app, "ft");
    until_found(&mut app, Duration::from_secs(60));
    assert_eq!(app.pixel().cursor(), sync.pixel().cursor());
    assert_eq!(app.pixel().current(), sync.pixel().current());
    assert_eq!(app.message(), sync.message());
}

#[test]
fn keys_are_answered_while_a_find_runs_and_a_cancelled_find_moves_nothing() {
    let mut app = glass_in_background();
    let last = last_tir_pixel(&app);
    app.update(Action::Pick(last.0, last.1));
    // From the last TIR pixel, f t wraps: all rows after it and all before
    // the first TIR pixel are recorded first (thousands of pixels).
    chars(&mut app, "ft");
    let (what, row, rows) = app.finding_progress().expect("the find runs");
    assert_eq!(what, "a total internal reflection");
    assert!(
        (1..=rows).contains(&row) && rows == 120,
        "row {row} of {rows}"
    );
    let mut terminal = screen(&mut app, 120, 40);
    let status = row_text(&mut terminal, 39);
    assert!(
        status.contains("finding a total internal reflection… (row "),
        "{status}"
    );
    // A key is answered at once, without waiting for the find, which goes on.
    chars(&mut app, "?");
    assert_eq!(app.overlay().mode(), Mode::Help);
    assert!(app.finding_progress().is_some(), "the find still runs");
    chars(&mut app, "?");
    // A pick (here j, one row down) cancels it: even once the scan would
    // have ended, the cursor stays where the key put it.
    chars(&mut app, "j");
    let moved = (last.0, last.1 + 1);
    assert_eq!(app.pixel().cursor(), moved);
    assert!(app.finding_progress().is_none());
    for _ in 0..100 {
        std::thread::sleep(Duration::from_millis(10));
        app.update(Action::Tick);
    }
    assert_eq!(app.pixel().cursor(), moved);
    assert_eq!(app.message(), None, "no find result came in");
    // q while a find runs: answered, and the find is dropped.
    chars(&mut app, "ft");
    assert!(app.finding_progress().is_some());
    chars(&mut app, "q");
    assert!(app.should_quit());
    assert!(app.finding_progress().is_none());
}

#[test]
fn f_p_finds_the_next_pixel_with_a_partly_blocked_shadow() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/two-lights.toml");
    let mut app = App::open(Some(path), true).unwrap();
    let (width, height) = (app.session().scene().width, app.session().scene().height);
    let (scene, settings) = (app.session().scene().clone(), *app.session().settings());
    // Independently: the first pixel after the centre, in reading order,
    // with a light whose S is strictly between 0 and 1 at any ray.
    let partly = |x, y| {
        record_pixel(&scene, &settings, x, y).nodes.iter().any(|n| {
            n.lights
                .iter()
                .filter_map(|l| l.shadow.as_ref())
                .any(|s| s.s > 0.0 && s.s < 1.0)
        })
    };
    let start = app.pixel().cursor();
    let expected = (start.1 * width + start.0 + 1..width * height)
        .chain(0..=start.1 * width + start.0)
        .map(|i| (i % width, i / width))
        .find(|&(x, y)| partly(x, y))
        .unwrap();
    chars(&mut app, "fp");
    assert_shows_pixel(&app, expected);
    assert!(
        matches!(
            app.pixel().tree().events[app.pixel().current()].kind,
            EventKind::Blocker { kt, .. } if kt > 0.0
        ),
        "a transparent blocker is the current event"
    );
}

#[test]
fn f_n_on_a_scene_too_big_for_near_misses_says_so() {
    // 2001 spheres: one more than NEAR_MISS_SCENE_LIMIT, so no recording has
    // near misses, and "none in the image" would claim there are none.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("many.nff");
    let mut text = String::from(
        "b 0 0 0\nv\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n\
         l 0 10 10\nf 1 0 0 1 0 0 0 0\n",
    );
    for i in 0..=raystep_engine::record::NEAR_MISS_SCENE_LIMIT {
        let (x, y) = ((i % 50) as f64 * 0.1 - 2.5, (i / 50) as f64 * 0.1 - 2.0);
        text.push_str(&format!("s {x} {y} 0 0.01\n"));
    }
    std::fs::write(&path, text).unwrap();
    let mut app = App::open(Some(path), true).unwrap();
    chars(&mut app, "fn");
    let message = app.message().unwrap();
    assert!(
        message.contains(
            "near misses are recorded only in scenes of at most 2000 objects; this one has 2001"
        ),
        "{message}"
    );
    assert!(app.finding_progress().is_none(), "no scan started");
}
