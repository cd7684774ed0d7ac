//! The debugger with `--compare` and the classic mistakes as switches:
//! keys in, state out, checked against raystep's own renders and recordings.

use std::path::Path;

use crossterm::event::KeyCode;
use image::RgbImage;
use raystep::tui::{Action, App, Mode, Picture};
use raystep_engine::record::{record_pixel, text};
use raystep_engine::render::render;
use raystep_engine::scene::{Scene, Settings, builtin};
use raystep_engine::terms::Term;
use raystep_engine::trace::NoRecorder;
use raystep_model::mistakes::{Mistake, Mistakes};
use raystep_tools::compare::student;

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
fn the_menu_selection_wraps_at_both_ends() {
    // Without a comparison the rows are the catalogue's, in its order.
    let mut app = app();
    let last = Mistake::ALL.len() - 1;
    chars(&mut app, "Mk");
    assert_eq!(app.overlay().menu_row(), Some(last), "up from the first");
    chars(&mut app, "j");
    assert_eq!(app.overlay().menu_row(), Some(0), "down from the last");
    chars(&mut app, "kk");
    assert_eq!(app.overlay().menu_row(), Some(last - 1));
    chars(&mut app, " ");
    assert!(
        app.session()
            .settings()
            .mistakes
            .contains(Mistake::ALL[last - 1])
    );
}

#[test]
fn the_menu_opens_on_the_top_ranked_mistake_the_ranked_first() {
    // pixel-corner is the catalogue's last row: on main M opened on its
    // first (shadow-acne) and it took 13 presses of j to reach it.
    let (png, _) = students_png(Mistake::PixelCorner);
    let mut app = comparing(&png);
    let ranked: Vec<Mistake> = (app.comparison().unwrap().findings().mistakes.iter())
        .map(|r| r.mistake)
        .collect();
    assert_eq!(ranked[0], Mistake::PixelCorner, "{ranked:?}");
    chars(&mut app, "M");
    assert_eq!(app.overlay().menu_row(), Some(0));
    // The menu's rows as drawn: the ranked ones first, best first, then
    // the rest of the catalogue in its order, each mistake once.
    let screen = screen_text(&mut app, 120, 40);
    let rows: Vec<Mistake> = (screen.lines())
        .filter_map(|l| {
            let name = l.split("] ").nth(1)?.split(' ').next()?;
            Mistake::ALL.into_iter().find(|m| m.name() == name)
        })
        .collect();
    let rest = Mistake::ALL.into_iter().filter(|m| !ranked.contains(m));
    let want: Vec<Mistake> = ranked.iter().copied().chain(rest).collect();
    assert_eq!(rows, want, "{screen}");
    let first = screen.lines().find(|l| l.contains("[ ] ")).unwrap();
    assert!(first.contains("#1 explains"), "{screen}");
    // Space at once turns on the mistake compare named.
    chars(&mut app, " ");
    assert_eq!(
        app.session().settings().mistakes,
        Mistakes::NONE.with(Mistake::PixelCorner)
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
    let error_map = comparison.error_map.clone().expect("the binary has FLIP");
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

/// The primary ray's object at a pixel (`None`: the background).
fn object_at(scene: &Scene, x: u32, y: u32) -> Option<usize> {
    let tree = record_pixel(scene, &scene.settings, x, y);
    tree.root().hit.as_ref().map(|h| h.object_index)
}

/// `image` written as the student's PNG, a file of its own per call.
fn save_png(image: &RgbImage, prefix: &str) -> tempfile::TempPath {
    let path = tempfile::Builder::new()
        .prefix(prefix)
        .suffix(".png")
        .tempfile()
        .unwrap()
        .into_temp_path();
    image.save(&path).unwrap();
    path
}

#[test]
fn c_and_capital_e_go_straight_to_yours_and_the_error_map() {
    let (png, yours) = students_png(Mistake::NoAmbient);
    let mut app = comparing(&png);
    let error_map = app
        .comparison()
        .unwrap()
        .findings()
        .error_map
        .clone()
        .expect("the binary has FLIP");
    let (x, y) = app.pixel().cursor();
    // On main: 9 presses of v to yours, 10 to the error map.
    chars(&mut app, "c");
    assert_eq!(app.screen().picture(), Picture::Yours);
    assert_eq!(app.message(), Some("view yours: the image you compare"));
    assert_eq!(app.shown_pixel(x, y), Some(yours.get_pixel(x, y).0));
    chars(&mut app, "E");
    assert_eq!(app.screen().picture(), Picture::ErrorMap);
    assert_eq!(app.shown_pixel(x, y), Some(error_map.get_pixel(x, y).0));
    // Again: back to the render, to flip between it and yours.
    chars(&mut app, "E");
    assert_eq!(app.screen().picture(), Picture::Render);
    chars(&mut app, "vc");
    assert_eq!(
        app.screen().picture(),
        Picture::Yours,
        "from a term view too"
    );
    chars(&mut app, "c");
    assert_eq!(app.screen().picture(), Picture::Render);
    // Without an image they say how to get one.
    let mut plain = crate::support::debugger::app();
    chars(&mut plain, "c");
    assert_eq!(plain.screen().picture(), Picture::Render);
    assert_eq!(
        plain.message(),
        Some("no image to compare: open with --compare IMAGE.png")
    );
}

#[test]
fn in_the_yours_view_the_image_title_shows_your_colour() {
    let (png, yours) = students_png(Mistake::NoAmbient);
    let mut app = comparing(&png);
    let scene = builtin_scene();
    let (ours, _) = render::<NoRecorder>(&scene, &scene.settings, &|| {});
    let (x, y) = app.pixel().cursor();
    let [a, b, c] = yours.get_pixel(x, y).0;
    let [r, g, bl] = ours.get_pixel(x, y).0;
    assert_ne!([a, b, c], [r, g, bl], "no-ambient darkens the centre pixel");
    let title = |app: &mut App| {
        screen_text(app, 120, 40)
            .lines()
            .nth(1)
            .unwrap()
            .to_string()
    };
    let on_render = title(&mut app);
    assert!(
        on_render.contains(&format!("rgb({r},{g},{bl})")),
        "{on_render}"
    );
    for _ in 0..=Term::ALL.len() {
        chars(&mut app, "v");
    }
    assert_eq!(app.screen().picture(), Picture::Yours);
    let on_yours = title(&mut app);
    assert!(
        on_yours.contains(&format!("yours rgb({a},{b},{c})")),
        "{on_yours}"
    );
    assert!(
        !on_yours.contains(&format!("rgb({r},{g},{bl})")),
        "{on_yours}"
    );
}

/// The items of the image pane's compare line on its bottom border, the
/// part left of the legend (which starts with " rays:").
fn compare_items(screen: &str) -> Option<Vec<String>> {
    let row = screen.lines().find(|l| l.contains("compare:"))?;
    let after = row.split("compare: ").nth(1)?;
    let before_legend = after.split(" rays:").next()?;
    let body = before_legend.trim_end_matches(['─', '┘', '│', ' ', '▲']);
    Some(body.split(" · ").map(str::to_string).collect())
}

#[test]
fn the_compare_line_keeps_whole_items_beside_a_legend() {
    // On main the rays view's legend, drawn over the compare line at the
    // right, cut it mid-word: "compare: no-ambi rays: 3 · scale ...".
    let (png, _) = students_png(Mistake::NoAmbient);
    let mut app = comparing(&png);
    while app.screen().picture() != Picture::Term(Term::Rays) {
        chars(&mut app, "v");
    }
    let names: Vec<&str> = Mistake::ALL.iter().map(|m| m.name()).collect();
    let whole = |item: &str| {
        let (name, share) = item.rsplit_once(' ').unwrap_or((item, ""));
        let percent = share
            .strip_suffix('%')
            .is_some_and(|n| n.parse::<u32>().is_ok());
        (names.contains(&name) && percent) || item.starts_with('+') && item.ends_with(" more")
    };
    let mut with_a_name = 0;
    for width in (100..=220).step_by(5) {
        let screen = screen_text(&mut app, width, 40);
        let Some(items) = compare_items(&screen) else {
            continue;
        };
        for item in &items {
            assert!(whole(item), "{item:?} at width {width}:\n{screen}");
        }
        with_a_name += items.iter().any(|i| i.starts_with("no-ambient ")) as usize;
    }
    assert!(with_a_name > 0, "no width showed the first mistake");
}

#[test]
fn the_status_line_shows_the_regions_diagnosis() {
    let (png, _) = students_png(Mistake::NoAmbient);
    let mut app = comparing(&png);
    // The diagnosis as `compare --json` gives it, independently of the debugger.
    let json = serde_json::to_value(app.comparison().unwrap().findings()).unwrap();
    let diagnosis = json["regions"][0]["diagnosis"]
        .as_str()
        .unwrap()
        .to_string();
    chars(&mut app, "w");
    let status = |app: &mut App| {
        screen_text(app, 220, 40)
            .lines()
            .last()
            .unwrap()
            .to_string()
    };
    let after_w = status(&mut app);
    assert!(
        after_w.contains(&diagnosis),
        "{diagnosis} not in\n{after_w}"
    );
    // Stepping through the pixel's trace clears the message; the region's
    // diagnosis stays while the cursor is in the region.
    chars(&mut app, "n");
    let stepping = status(&mut app);
    assert!(
        stepping.contains(&format!("region 1: {diagnosis}")),
        "{stepping}"
    );
}

#[test]
fn a_regions_pixel_lies_on_the_object_most_of_it_covers() {
    // A student image equal to ours but for a 12 x 12 box across an
    // object's edge: 3 columns left of the edge, 9 right of it. Every box
    // pixel is 40 steps off; those on the box's lesser object 120. On main
    // the region's pixel was the largest gap: on the lesser object.
    let scene = builtin_scene();
    let (mut image, _) = render::<NoRecorder>(&scene, &scene.settings, &|| {});
    let y = scene.height / 2;
    let x = (4..scene.width - 9)
        .find(|&x| object_at(&scene, x, y) != object_at(&scene, x - 1, y))
        .expect("an edge on the middle row");
    let box_pixels: Vec<(u32, u32)> = (y - 6..y + 6)
        .flat_map(|py| (x - 3..x + 9).map(move |px| (px, py)))
        .collect();
    let mut counts: Vec<(Option<usize>, usize)> = Vec::new();
    for &(px, py) in &box_pixels {
        let object = object_at(&scene, px, py);
        match counts.iter_mut().find(|(o, _)| *o == object) {
            Some((_, n)) => *n += 1,
            None => counts.push((object, 1)),
        }
    }
    counts.sort_by_key(|&(_, n)| std::cmp::Reverse(n));
    assert!(counts.len() > 1 && counts[0].1 > counts[1].1, "{counts:?}");
    let most = counts[0].0;
    for &(px, py) in &box_pixels {
        let off = if object_at(&scene, px, py) == most {
            40
        } else {
            120
        };
        let pixel = image.get_pixel_mut(px, py);
        for channel in &mut pixel.0 {
            *channel = if *channel < 128 {
                *channel + off
            } else {
                *channel - off
            };
        }
    }
    let png = save_png(&image, "yours-box-");
    let mut app = comparing(&png);
    let regions = &app.comparison().unwrap().findings().regions;
    assert_eq!(regions.len(), 1);
    assert_eq!(regions[0].pixels, 144);
    chars(&mut app, "w");
    let (cx, cy) = app.pixel().cursor();
    assert!(box_pixels.contains(&(cx, cy)));
    assert_eq!(object_at(&scene, cx, cy), most, "({cx}, {cy})");
}

#[test]
fn with_a_ray_log_the_footer_shows_the_logs_verdict_over_the_images() {
    // Issue 39: with --compare and --rays the footer said "compare:
    // eta-inverted 99%" while the details pane showed the log's own
    // verdict, and nothing said which to believe. Here the image is
    // raystep's render under eta-inverted and the log a pixel traced under
    // no-ambient: the log's verdict is the one shown, the image's name
    // superseded by it, in words.
    let (png, _) = students_png(Mistake::EtaInverted);
    let app = comparing(&png);
    assert_eq!(
        app.comparison().unwrap().findings().mistakes[0].mistake,
        Mistake::EtaInverted
    );
    let scene = builtin_scene();
    let (x, y) = (scene.width / 2, scene.height / 2);
    let tree = record_pixel(&scene, &with(Mistake::NoAmbient), x, y);
    let log = tempfile::Builder::new()
        .suffix(".jsonl")
        .tempfile()
        .unwrap()
        .into_temp_path();
    std::fs::write(&log, raystep_tools::raylog::raylog(&tree)).unwrap();
    let rays = raystep::tui::app::RayLog::read(app.session().scene(), &log).unwrap();
    let mut app = app.with_ray_log(rays);
    let ranked = &app.comparison().unwrap().findings().mistakes[0];
    assert_eq!(ranked.verdict, raystep_tools::compare::Verdict::Superseded);
    let by = ranked.superseded_by.as_deref().unwrap();
    assert!(
        by.starts_with(&format!(
            "your ray log: pixel ({x}, {y}) is consistent with no-ambient"
        )),
        "{by}"
    );
    let screen = screen_text(&mut app, 160, 40);
    assert!(
        screen.contains("compare: eta-inverted 100%, superseded: your ray log"),
        "{screen}"
    );
}
