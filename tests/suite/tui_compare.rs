//! The debugger with `--compare` and the classic mistakes as switches:
//! keys in, state out, checked against raystep's own renders and recordings.

use std::path::Path;

use crossterm::event::KeyCode;
use image::RgbImage;
use raystep::compare::student;
use raystep::mistakes::{Mistake, Mistakes};
use raystep::record::{record_pixel, text};
use raystep::render::render;
use raystep::scene::{Scene, Settings, builtin};
use raystep::terms::Term;
use raystep::trace::NoRecorder;
use raystep::tui::{Action, App, Mode, Picture};

use crate::support::debugger::*;

fn builtin_scene() -> Scene {
    builtin::load_file_or_builtin(None).expect("the built-in scene loads")
}

fn with(mistake: Mistake) -> Settings {
    let scene = builtin_scene();
    Settings {
        mistakes: Mistakes::NONE.with(mistake),
        ..scene.settings
    }
}

/// The built-in scene rendered by raystep under `mistake`, written as the
/// student's PNG.
/// Each call writes its own file: tests run in parallel, and one writing
/// a PNG while another reads it gave a truncated image.
fn students_png(mistake: Mistake) -> (tempfile::TempPath, RgbImage) {
    let scene = builtin_scene();
    let (image, _) = render::<NoRecorder>(&scene, &with(mistake), &|| {});
    let path = tempfile::Builder::new()
        .prefix(&format!("yours-{mistake}-"))
        .suffix(".png")
        .tempfile()
        .unwrap()
        .into_temp_path();
    image.save(&path).unwrap();
    (path, image)
}

/// The app as `raystep debug --compare PNG` opens it (on the built-in scene).
fn comparing(png: &Path) -> App {
    let student = student::load(png).expect("the PNG loads");
    App::open_with(None, Some(student), true).expect("the app opens")
}

/// All the screen's text, row after row.
fn screen_text(app: &mut App, width: u16, height: u16) -> String {
    let terminal = screen(app, width, height);
    let buffer = terminal.backend().buffer();
    let mut out = String::new();
    for y in 0..height {
        for x in 0..width {
            out.push_str(buffer[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

#[test]
fn a_mistake_turned_on_in_the_menu_records_as_record_pixel_with_it() {
    let mut app = app();
    let scene = builtin_scene();
    let (x, y) = app.pixel().cursor();
    let plain = text(&record_pixel(&scene, &scene.settings, x, y));
    assert_eq!(text(app.pixel().tree()), plain);
    chars(&mut app, "M");
    assert_eq!(app.overlay().mode(), Mode::Menu);
    assert_eq!(app.overlay().menu_row(), Some(0));
    // no-ambient is row 9 of the catalogue: nine rows down.
    chars(&mut app, "jjjjjjjjjj");
    chars(&mut app, "k");
    assert_eq!(app.overlay().menu_row(), Some(9));
    assert_eq!(Mistake::ALL[9], Mistake::NoAmbient);
    chars(&mut app, " ");
    assert_eq!(app.message(), Some("mistake no-ambient on"));
    assert_eq!(
        app.session().settings().mistakes,
        Mistakes::NONE.with(Mistake::NoAmbient)
    );
    let mistaken = text(&record_pixel(&scene, &with(Mistake::NoAmbient), x, y));
    assert_ne!(mistaken, plain, "the centre pixel has an ambient term");
    assert_eq!(text(app.pixel().tree()), mistaken);
    let (image, _) = render::<NoRecorder>(&scene, &with(Mistake::NoAmbient), &|| {});
    assert!(
        app.renders().image() == Some(&image),
        "the image re-rendered with it"
    );
    // The menu stays open until Esc; the keys then go to the panes again.
    assert!(screen_text(&mut app, 120, 40).contains("[x] no-ambient"));
    press(&mut app, &[key(KeyCode::Esc)]);
    assert_eq!(app.overlay().mode(), Mode::Browsing);
    assert!(!app.should_quit(), "Esc closes the menu, not the debugger");
    let header = screen_text(&mut app, 120, 40);
    assert!(
        header
            .lines()
            .next()
            .unwrap()
            .contains("mistakes: no-ambient"),
        "{header}"
    );
    // Enter toggles it off again; M closes.
    chars(&mut app, "M");
    press(&mut app, &[key(KeyCode::Enter)]);
    chars(&mut app, "M");
    assert_eq!(app.overlay().mode(), Mode::Browsing);
    assert!(app.session().settings().mistakes.is_empty());
    assert_eq!(text(app.pixel().tree()), plain);
    assert!(!screen_text(&mut app, 120, 40).contains("mistakes:"));
}

#[test]
fn the_menu_selection_stops_at_both_ends() {
    let mut app = app();
    chars(&mut app, "Mkk");
    assert_eq!(app.overlay().menu_row(), Some(0));
    for _ in 0..Mistake::ALL.len() + 5 {
        chars(&mut app, "j");
    }
    assert_eq!(
        app.overlay().menu_row(),
        Some(21),
        "fov-full-angle, the last"
    );
    chars(&mut app, " ");
    assert!(
        app.session()
            .settings()
            .mistakes
            .contains(Mistake::FovFullAngle)
    );
}

#[test]
fn a_mistake_stays_on_across_a_reload() {
    let path = scene_file("mistake-reload.toml");
    let mut app = App::open(Some(path.clone()), true).unwrap();
    app.update(Action::ToggleMistake(Mistake::ShadowAcne));
    edit(&path, "max_depth = 3", "max_depth = 2");
    app.update(Action::Reload);
    assert_eq!(app.session().error(), None);
    assert_eq!(
        app.session().settings().max_depth,
        2,
        "the edit took effect"
    );
    assert_eq!(
        app.session().settings().mistakes,
        Mistakes::NONE.with(Mistake::ShadowAcne)
    );
}

#[test]
fn comparing_shows_yours_and_the_error_map_and_ranks_the_mistake() {
    let (png, yours) = students_png(Mistake::NoAmbient);
    let mut app = comparing(&png);
    let comparison = app.comparison().unwrap().findings();
    assert_eq!(comparison.mistakes[0].mistake, Mistake::NoAmbient);
    let error_map = comparison.error_map.clone();
    let (x, y) = app.pixel().cursor();
    // The render, each term, then yours and the error map, then the render.
    for _ in 0..=Term::ALL.len() {
        chars(&mut app, "v");
    }
    assert_eq!(app.screen().picture(), Picture::Yours);
    assert_eq!(app.shown_pixel(x, y), Some(yours.get_pixel(x, y).0));
    let screen = screen_text(&mut app, 120, 40);
    assert!(screen.contains("view: yours"), "{screen}");
    chars(&mut app, "v");
    assert_eq!(app.screen().picture(), Picture::ErrorMap);
    assert_eq!(app.shown_pixel(x, y), Some(error_map.get_pixel(x, y).0));
    assert_eq!(app.shown_pixel(3, 119), Some(error_map.get_pixel(3, 119).0));
    chars(&mut app, "v");
    assert_eq!(app.screen().picture(), Picture::Render);
    // The ranking under the image, the rank in the menu.
    let screen = screen_text(&mut app, 120, 40);
    assert!(screen.contains("compare: no-ambient 100%"), "{screen}");
    chars(&mut app, "M");
    assert!(screen_text(&mut app, 120, 40).contains("no ambient term  #1 explains 100%"));
}

#[test]
fn the_details_put_your_pixel_beside_ours() {
    let (png, yours) = students_png(Mistake::NoAmbient);
    let mut app = comparing(&png);
    let scene = builtin_scene();
    let (ours, _) = render::<NoRecorder>(&scene, &scene.settings, &|| {});
    let (x, y) = app.pixel().cursor();
    let [a, b, c] = yours.get_pixel(x, y).0;
    let [r, g, bl] = ours.get_pixel(x, y).0;
    assert_ne!([a, b, c], [r, g, bl], "no-ambient darkens the centre pixel");
    let want = format!("yours ({a}, {b}, {c}) ██ · ours ({r}, {g}, {bl}) ██");
    let screen = screen_text(&mut app, 120, 40);
    assert!(screen.contains(&want), "{want} not in\n{screen}");
    // With the student's mistake on, ours is theirs.
    app.update(Action::ToggleMistake(Mistake::NoAmbient));
    let want = format!("yours ({a}, {b}, {c}) ██ · ours ({a}, {b}, {c}) ██");
    let screen = screen_text(&mut app, 120, 40);
    assert!(screen.contains(&want), "{want} not in\n{screen}");
}

#[test]
fn w_goes_to_each_regions_pixel_largest_first_and_cycles() {
    let (png, _) = students_png(Mistake::NoAmbient);
    let mut app = comparing(&png);
    let regions: Vec<([u32; 2], usize)> = app
        .comparison()
        .unwrap()
        .findings()
        .regions
        .iter()
        .map(|r| (r.pixel, r.pixels))
        .collect();
    assert!(!regions.is_empty());
    for (i, &([x, y], pixels)) in regions.iter().enumerate() {
        chars(&mut app, "w");
        assert_eq!(app.pixel().cursor(), (x, y));
        let message = app.message().unwrap();
        assert!(
            message.starts_with(&format!("region {} of", i + 1))
                && message.contains(&format!(": {pixels} pixels on ")),
            "{message}"
        );
        let scene = app.session().scene();
        assert_eq!(
            text(app.pixel().tree()),
            text(&record_pixel(scene, &scene.settings, x, y))
        );
    }
    chars(&mut app, "w");
    assert_eq!(
        app.pixel().cursor(),
        (regions[0].0[0], regions[0].0[1]),
        "back to the largest"
    );
}

#[test]
fn without_an_image_w_says_how_to_compare_and_v_skips_the_compare_views() {
    let mut app = app();
    chars(&mut app, "w");
    assert_eq!(
        app.message(),
        Some("no image to compare: open with --compare IMAGE.png")
    );
    for _ in 0..=Term::ALL.len() {
        chars(&mut app, "v");
    }
    assert_eq!(app.screen().picture(), Picture::Render);
}

#[test]
fn a_matching_image_has_no_region_and_no_mistake() {
    let scene = builtin_scene();
    let (image, _) = render::<NoRecorder>(&scene, &scene.settings, &|| {});
    let png = Path::new("target/tui-tests/yours-correct.png");
    std::fs::create_dir_all(png.parent().unwrap()).unwrap();
    image.save(png).unwrap();
    let mut app = comparing(png);
    let before = app.pixel().cursor();
    chars(&mut app, "w");
    assert_eq!(app.message(), Some("your image matches: no region differs"));
    assert_eq!(app.pixel().cursor(), before);
    assert!(screen_text(&mut app, 120, 40).contains("compare: your image matches"));
}

#[test]
fn the_scene_takes_the_images_size_also_after_a_reload() {
    let scene = builtin_scene();
    let small = scene.clone().with_size(40, 30).unwrap();
    let (image, _) = render::<NoRecorder>(&small, &small.settings, &|| {});
    let png = Path::new("target/tui-tests/yours-40x30.png");
    std::fs::create_dir_all(png.parent().unwrap()).unwrap();
    image.save(png).unwrap();
    let path = scene_file("compare-reload.toml");
    let student = student::load(png).unwrap();
    let mut app = App::open_with(Some(path), Some(student), true).unwrap();
    assert_eq!(
        (app.session().scene().width, app.session().scene().height),
        (40, 30)
    );
    assert!(app.comparison().unwrap().findings().matches);
    app.update(Action::Reload);
    assert_eq!(
        (app.session().scene().width, app.session().scene().height),
        (40, 30)
    );
}
