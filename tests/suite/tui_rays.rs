//! The debugger with `--rays`: a student's ray log beside the tree. Each
//! log here is raystep's own log of a pixel of scenes/glass.toml with a
//! change made by hand, so what differs, and where, is known before the
//! debugger says it.

use std::io::Write;
use std::path::{Path, PathBuf};

use crossterm::event::KeyCode;
use raystep::tui::app::RayLog;
use raystep::tui::{App, Pane};
use raystep_engine::record::{EventKind, record_pixel};
use raystep_engine::scene::Scene;
use raystep_tools::raylog::raylog;

use crate::support::debugger::*;
use crate::support::{raystep, stderr, stdout};

const GLASS: &str = "scenes/glass.toml";

fn glass() -> Scene {
    raystep_engine::scene::load(Path::new(GLASS)).unwrap()
}

/// raystep's own log of `pixel` of the glass scene.
fn our_log(pixel: (u32, u32)) -> String {
    let scene = glass();
    raylog(&record_pixel(&scene, &scene.settings, pixel.0, pixel.1))
}

/// `log` with `from` replaced by `to` in the line of `path` (that line
/// must hold `from`).
fn edit_ray(log: &str, path: &str, from: &str, to: &str) -> String {
    let key = format!("\"path\": \"{path}\",");
    let mut found = false;
    let lines: Vec<String> = log
        .lines()
        .map(|line| {
            if line.contains(&key) {
                assert!(line.contains(from), "{from} not in {line}");
                found = true;
                line.replace(from, to)
            } else {
                line.to_string()
            }
        })
        .collect();
    assert!(found, "no ray {path}");
    lines.join("\n") + "\n"
}

/// `log` written to a file of its own (tests run in parallel).
fn log_file(log: &str) -> tempfile::TempPath {
    let mut file = tempfile::Builder::new()
        .prefix("yours-")
        .suffix(".jsonl")
        .tempfile()
        .unwrap();
    file.write_all(log.as_bytes()).unwrap();
    file.into_temp_path()
}

/// The debugger on the glass scene with the log at `path`, as
/// `raystep scenes/glass.toml --rays LOG` opens it.
fn debugger_with(path: &Path) -> App {
    let app = App::open(Some(PathBuf::from(GLASS)), true).unwrap();
    let log = RayLog::read(app.session().scene(), path).expect("the log reads");
    app.with_ray_log(log)
}

/// Pixel (72, 45) as logged by a student whose tracer differs from
/// raystep's in three places, each made by hand from raystep's log:
///
/// - P/T/R (r3, reflected inside the ball) hits at t = 2.5 where ours hits
///   at t = 1.9533822498587954 (printed 1.953382): the one number changed;
/// - P/T/R/S0 is a shadow ray ours never casts: light 0 (key) is behind
///   the surface there (the tree says "faces away");
/// - P/T/T/S1 is left out: ours casts it, yours does not.
///
/// In the trace's order, r3's hit comes before its shadow rays and before
/// P/T/T's, so the first divergence is P/T/R t.
fn three_changes() -> String {
    let log = edit_ray(
        &our_log((72, 45)),
        "P/T/R",
        "\"t\": 1.9533822498587954",
        "\"t\": 2.5",
    );
    let mut log: String = log
        .lines()
        .filter(|l| !l.contains("\"path\": \"P/T/T/S1\""))
        .map(|l| format!("{l}\n"))
        .collect();
    log.push_str("{\"pixel\": [72, 45], \"path\": \"P/T/R/S0\", \"S\": 1.0}\n");
    log
}

/// The text inside pane `pane`, line by line, trailing spaces dropped.
fn pane_text(app: &mut App, pane: Pane, width: u16, height: u16) -> Vec<String> {
    let terminal = screen(app, width, height);
    let buffer = terminal.backend().buffer();
    let rect = app.panes().rect(pane);
    (rect.y + 1..rect.y + rect.height - 1)
        .map(|y| {
            let line: String = (rect.x + 1..rect.x + rect.width - 1)
                .map(|x| buffer[(x, y)].symbol())
                .collect();
            line.trim_end().to_string()
        })
        .collect()
}

/// The tree pane's row that says `what`, from its mark to the description.
fn tree_row<'a>(rows: &'a [String], what: &str) -> &'a str {
    let row = rows
        .iter()
        .find(|r| r.contains(what))
        .unwrap_or_else(|| panic!("no row {what:?} in {rows:#?}"));
    // The swatch and share end each row.
    row.split("██").next().unwrap().trim_end()
}

#[test]
fn the_debugger_opens_on_the_first_logged_pixel_and_marks_each_ray() {
    let path = log_file(&three_changes());
    let mut app = debugger_with(&path);
    // The scene's centre is (80, 60); the log's only pixel is (72, 45).
    assert_eq!(app.pixel().cursor(), (72, 45));
    // raystep's 16 rays, less P/T/T/S1, plus P/T/R/S0.
    let opening = format!(
        "{} (1 pixel, 16 rays): logged pixel 1 of 1, (72, 45): first differs at P/T/R t, \
         D goes there; y: next",
        path.display()
    );
    assert_eq!(app.message(), Some(opening.as_str()));
    let rows = pane_text(&mut app, Pane::Tree, 160, 80);
    // Each ray of ours, by hand from the changes: r3 (P/T/R) differs and is
    // the first divergence; P/T/T/S1 is not in the log; the rest match. r3's
    // lights face away: ours casts no shadow ray there, so those rows have
    // no mark. The shadow ray only in yours is listed under the tree.
    let expected = [
        ("r0 P primary", "✓ ▾ r0 P primary → hit glass ball"),
        ("P/S0", "✓     ☼ P/S0 light key: lit, S = 1"),
        ("P/S1", "✓     ☼ P/S1 light fill: lit, S = 1"),
        ("r1 P/R", "✓     r1 P/R reflected → miss"),
        ("r2 P/T ", "✓   ▾ r2 P/T transmitted → hit glass ball"),
        (
            "r3 P/T/R ",
            "≠     ▾ r3 P/T/R reflected → hit glass ball ◀ first divergence",
        ),
        ("light key: faces away", "          ☼ light key: faces away"),
        ("P/T/T/S0", "✓         ☼ P/T/T/S0 light key: lit, S = 1"),
        ("P/T/T/S1", "−         ☼ P/T/T/S1 light fill: lit, S = 1"),
    ];
    for (what, row) in expected {
        assert_eq!(tree_row(&rows, what), row);
    }
    let only_yours = rows.iter().find(|r| r.starts_with('+')).expect("a + row");
    assert!(
        only_yours.starts_with("+ P/T/R/S0 only in yours: MODEL §4: light 0 is behind the surface"),
        "{only_yours}"
    );
    let report = app.ray_log().and_then(RayLog::report).expect("a report");
    let first = report.first_divergence.as_ref().expect("a divergence");
    assert_eq!(
        (first.path.to_string(), first.field.to_string()),
        ("P/T/R".into(), "t".into())
    );
}

#[test]
fn with_pixel_the_debugger_opens_there_and_says_how_it_stands_to_the_log() {
    let path = log_file(&three_changes());
    let app = debugger_with(&path).at_pixel((73, 45)).unwrap();
    assert_eq!(app.pixel().cursor(), (73, 45));
    let message = app.message().unwrap();
    assert!(
        message.ends_with("): pixel (73, 45) is not in your log: y goes to a logged pixel"),
        "{message}"
    );
}

#[test]
fn d_jumps_to_the_hit_of_the_changed_ray_and_the_details_set_yours_beside_ours() {
    let path = log_file(&three_changes());
    let mut app = debugger_with(&path);
    assert_eq!(
        app.pixel().current(),
        0,
        "the pixel opens on its first event"
    );
    chars(&mut app, "D");
    // t is found when r3 hits: the current event is r3's hit.
    let tree = app.pixel().tree();
    let event = &tree.events[app.pixel().current()];
    assert_eq!(event.node, 3);
    assert!(
        matches!(event.kind, EventKind::Hit { object: 0, .. }),
        "{event:?}"
    );
    assert_eq!(
        app.message(),
        Some("first divergence: P/T/R t, scaled: yours beside ours in the details")
    );
    let details = pane_text(&mut app, Pane::Details, 160, 80);
    assert_eq!(
        details[0],
        "≠ P/T/R, yours beside ours: 1 of 13 numbers differs"
    );
    assert_eq!(details[1], "First divergence of the pixel: here, t");
    // 2.5 / 1.9533822498587954 = 1.27983..., a scalar off by a factor.
    assert_eq!(details[2], "  scaled: yours is 1.2798 × ours");
    // The P/T/R/S0 only in yours and P/T/T/S1 only in ours come after it.
    assert!(
        details.contains(&"2 differences after it follow from the first.".to_string()),
        "{details:#?}"
    );
    // Yours and ours side by side: t is yours 2.5 (the edit), ours
    // 1.953382; the hit agrees (the ball is object 0 of glass.toml).
    let row = |field: &str| -> Vec<String> {
        let line = details
            .iter()
            .find(|l| {
                l.starts_with(&format!("✓ {field} ")) || l.starts_with(&format!("≠ {field} "))
            })
            .unwrap_or_else(|| panic!("no {field} in {details:#?}"));
        line.split("  ")
            .filter(|part| !part.is_empty())
            .map(|part| part.trim().to_string())
            .collect()
    };
    assert_eq!(row("t"), ["≠ t", "2.5", "1.953382"]);
    assert_eq!(
        row("hit"),
        ["✓ hit", "glass ball (object 0)", "glass ball (object 0)"]
    );
    assert_eq!(row("weight"), ["✓ weight", "0.09", "0.09"]);
    // r3's lights face away, yet your log casts a shadow ray from it to
    // light 0: listed under r3's numbers, with MODEL's rule.
    let at = details
        .iter()
        .position(|l| l == "Only in your log, from this ray:")
        .expect("the rays only in yours under r3");
    assert!(
        details[at + 1].starts_with("+ P/T/R/S0: MODEL §4: light 0 is behind the surface"),
        "{}",
        details[at + 1]
    );
    // The tree selects r3's row.
    let rows = pane_text(&mut app, Pane::Tree, 160, 80);
    assert!(rows.iter().any(|r| r.contains("r3 P/T/R")));
}

#[test]
fn y_steps_through_the_logged_pixels_in_the_logs_order_and_wraps() {
    // Three pixels, each raystep's own: they all match.
    let log = [(72, 45), (10, 10), (150, 100)].map(our_log).concat();
    let path = log_file(&log);
    let mut app = debugger_with(&path);
    let mut seen = vec![app.pixel().cursor()];
    for _ in 0..3 {
        chars(&mut app, "y");
        seen.push(app.pixel().cursor());
    }
    assert_eq!(seen, [(72, 45), (10, 10), (150, 100), (72, 45)]);
    assert_eq!(
        app.message(),
        Some("logged pixel 1 of 3, (72, 45): your rays match ours")
    );
    press(&mut app, &[shift('Y')]);
    assert_eq!(app.pixel().cursor(), (150, 100), "Y goes back, wrapping");
    // From a pixel outside the log, y goes on from the last one gone to.
    app.update(raystep::tui::Action::Pick(0, 0));
    assert!(app.ray_log().and_then(RayLog::report).is_none());
    chars(&mut app, "y");
    assert_eq!(app.pixel().cursor(), (72, 45));
}

#[test]
fn a_pixel_outside_the_log_shows_its_tree_as_without_one() {
    let path = log_file(&three_changes());
    let mut app = debugger_with(&path);
    app.update(raystep::tui::Action::Pick(73, 45));
    let with_log = pane_text(&mut app, Pane::Tree, 160, 80);
    let mut plain = App::open(Some(PathBuf::from(GLASS)), true).unwrap();
    plain.update(raystep::tui::Action::Pick(73, 45));
    let without = pane_text(&mut plain, Pane::Tree, 160, 80);
    assert_eq!(with_log, without);
    chars(&mut app, "D");
    assert_eq!(
        app.message(),
        Some("pixel (73, 45) is not in your log: y goes to a logged pixel")
    );
}

#[test]
fn without_a_log_y_and_d_say_how_to_open_one() {
    let mut app = app();
    let cursor = app.pixel().cursor();
    for key in ["y", "D"] {
        chars(&mut app, key);
        assert_eq!(
            app.message(),
            Some("no ray log: open with --rays LOG.jsonl (docs/RAYLOG.md)")
        );
        assert_eq!(app.pixel().cursor(), cursor);
    }
}

#[test]
fn turning_on_the_mistake_of_the_log_makes_every_ray_match() {
    // A log raystep prints under eta-inverted: P/T is the first ray where it acts.
    let scene = glass();
    let settings = raystep_engine::scene::Settings {
        mistakes: raystep_model::mistakes::Mistakes::NONE
            .with(raystep_model::mistakes::Mistake::EtaInverted),
        ..scene.settings
    };
    let path = log_file(&raylog(&record_pixel(&scene, &settings, 72, 45)));
    let mut app = debugger_with(&path);
    let report = app.ray_log().and_then(RayLog::report).unwrap();
    assert_eq!(
        report.first_divergence.as_ref().map(|d| d.path.to_string()),
        Some("P/T".into())
    );
    // M opens on eta-inverted, the mistake the log is consistent with (as
    // --compare's menu opens on the ranking's first, issue 39): space
    // turns it on.
    chars(&mut app, "M ");
    assert_eq!(
        app.message(),
        Some("mistake eta-inverted on · your rays of this pixel match ours")
    );
    let report = app.ray_log().and_then(RayLog::report).unwrap();
    assert!(report.matches, "{:?}", report.first_divergence);
}

#[test]
fn a_bad_log_exits_1_with_its_line_and_column_before_the_terminal_is_taken() {
    // Line 2 is not JSON; line 1 is a good primary ray.
    let log = "{\"pixel\": [72, 45], \"path\": \"P\"}\nnot json\n";
    let path = log_file(log);
    let name = path.to_str().unwrap();
    for args in [
        vec![GLASS, "--rays", name],
        vec!["debug", GLASS, "--rays", name],
    ] {
        let output = raystep(&args);
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        let err = stderr(&output);
        // 'n' may begin `null`: the 'o' at column 2 is where it is no JSON.
        assert!(
            err.starts_with(&format!("error: {name}:2:2: not JSON")),
            "{err}"
        );
        // Nothing was drawn: no escape sequence (alternate screen, raw
        // mode's cursor moves) anywhere, and nothing on stdout.
        assert!(!err.contains('\u{1b}'), "{err:?}");
        assert_eq!(stdout(&output), "");
    }
}

#[test]
fn with_compare_the_logs_pixels_are_at_the_images_size() {
    // A 32x24 image: the scene is traced at that size, and so is the log.
    let image = tempfile::Builder::new()
        .suffix(".png")
        .tempfile()
        .unwrap()
        .into_temp_path();
    image::RgbImage::new(32, 24).save(&image).unwrap();
    let image = image.to_str().unwrap();
    // (72, 45) is inside the scene's 160x120 but outside 32x24.
    let outside = log_file("{\"pixel\": [72, 45], \"path\": \"P\"}\n");
    let name = outside.to_str().unwrap();
    let output = raystep(&[GLASS, "--compare", image, "--rays", name]);
    assert_eq!(output.status.code(), Some(1));
    let err = stderr(&output);
    assert!(err.starts_with(&format!("error: {name}:1:")), "{err}");
    assert!(err.contains("32x24"), "{err}");
    // (10, 10) is inside it: the log is taken, and only the missing
    // terminal stops the debugger.
    let inside = log_file("{\"pixel\": [10, 10], \"path\": \"P\"}\n");
    let output = raystep(&[
        GLASS,
        "--compare",
        image,
        "--rays",
        inside.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("the debugger needs a terminal"),
        "{}",
        stderr(&output)
    );
}

/// The screen a student sees after `D` on a log raystep prints under
/// eta-inverted (the example, /tmp/x.jsonl in the guide): at
/// 120x40 the details stack yours over ours, and fields that agree take
/// one line.
#[test]
fn snapshot_first_divergence() {
    let scene = glass();
    let settings = raystep_engine::scene::Settings {
        mistakes: raystep_model::mistakes::Mistakes::NONE
            .with(raystep_model::mistakes::Mistake::EtaInverted),
        ..scene.settings
    };
    let path = log_file(&raylog(&record_pixel(&scene, &settings, 72, 45)));
    let mut app = debugger_with(&path);
    chars(&mut app, "D");
    snapshot!("first_divergence", screen(&mut app, 120, 40).backend());
}

#[test]
fn the_details_say_no_line_twice_and_the_tree_counts_rays_as_compare_does() {
    // Pixel (72, 45) logged without P/S0: the first divergence is a ray
    // only ours casts, whose rule is what ours is. Before issue 39 the
    // details printed that rule twice, and the tree's title counted 8
    // rays where compare counts 16 (it counts the shadow rays).
    let log: String = (our_log((72, 45)).lines())
        .filter(|l| !l.contains("\"path\": \"P/S0\""))
        .map(|l| format!("{l}\n"))
        .collect();
    let path = log_file(&log);
    let mut app = debugger_with(&path);
    chars(&mut app, "D");
    let report = app.ray_log().and_then(RayLog::report).unwrap();
    let first = report.first_divergence.as_ref().unwrap();
    assert_eq!(format!("{} {}", first.path, first.field), "P/S0 ray");
    let details = pane_text(&mut app, Pane::Details, 160, 80);
    // The log's part of the details, down to the blank line before the
    // ray's own story (whose formulas repeat per light, rightly).
    let mut seen = std::collections::HashSet::new();
    for line in details.iter().take_while(|l| !l.trim().is_empty()) {
        assert!(seen.insert(line), "{line:?} twice in {details:#?}");
    }
    assert!(
        details
            .iter()
            .any(|l| l.contains("a shadow ray to each light in front")),
        "{details:#?}"
    );
    let top = tree_title(&mut app);
    assert!(
        top.contains("· 16 rays (8 shadow) · your log differs"),
        "{top}"
    );
}

#[test]
fn the_debugger_takes_size_for_a_log_traced_at_another_size() {
    // A log of pixel (300, 200) is outside glass.toml's 160x120: with
    // --size 320x240 it reads, and only the missing terminal stops the
    // debugger (before issue 39 the debugger had no --size).
    let path = log_file("{\"pixel\": [300, 200], \"path\": \"P\"}\n");
    let name = path.to_str().unwrap();
    let output = raystep(&[GLASS, "--rays", name]);
    assert!(stderr(&output).contains("outside the image"), "{output:?}");
    let output = raystep(&[GLASS, "--rays", name, "--size", "320x240"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("the debugger needs a terminal"),
        "{}",
        stderr(&output)
    );
}

/// Three glass planes (tests/scenes/three-glass-planes.toml) at 8x6, with
/// no weight cutoff and the largest ray budget: our tree of pixel (3, 2)
/// has 98,326 rays, shadow rays included (hostile/memory.rs counts them).
/// Returns the scene file, a log of that pixel: raystep's own, its last
/// ray left out, and that ray's path, so that the pixel differs and the catalogue of mistakes
/// is tried against it. Compared on the UI thread, such a pixel had `q`
/// answered after 4 s (issue 41 §1).
fn planes_and_their_log(dir: &Path) -> (PathBuf, tempfile::TempPath, String) {
    let text = include_str!("../scenes/three-glass-planes.toml")
        .replace(
            "[settings]\n",
            "[settings]\nmin_weight = 0\nmax_rays = 65536\n",
        )
        .replace("width = 32\nheight = 24", "width = 8\nheight = 6");
    let scene_path = dir.join("planes.toml");
    std::fs::write(&scene_path, text).unwrap();
    let scene = raystep_engine::scene::load(&scene_path).unwrap();
    let ours = raylog(&record_pixel(&scene, &scene.settings, 3, 2));
    let lines: Vec<&str> = ours.lines().collect();
    assert!(lines.len() > 90_000, "{} rays", lines.len());
    let (last, kept) = lines.split_last().unwrap();
    let path: serde_json::Value = serde_json::from_str(last).unwrap();
    let yours = kept.join("\n") + "\n";
    (
        scene_path,
        log_file(&yours),
        path["path"].as_str().unwrap().to_string(),
    )
}

#[test]
fn keys_are_answered_while_a_pixel_of_100000_rays_is_compared() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, path, left_out) = planes_and_their_log(dir.path());
    // The debugger as `raystep SCENE --rays LOG` runs it: its comparisons
    // in the background (`false`: not on the caller's thread).
    let app = App::open(Some(scene), false).unwrap();
    let log = RayLog::read(app.session().scene(), &path).expect("the log reads");
    let mut app = app.with_ray_log(log);
    // It opens on the logged pixel and says it is being compared: the
    // comparison has not been waited for (before, the status line already
    // said where the rays first differ).
    assert_eq!(app.pixel().cursor(), (3, 2));
    let opening = app.message().unwrap().to_string();
    assert!(
        opening.ends_with("(3, 2): comparing your rays with ours…; y: next"),
        "{opening}"
    );
    let title = tree_title(&mut app);
    assert!(title.ends_with(" · comparing with your log… "), "{title}");
    // A key is answered at once: `q`, while the comparison goes on.
    chars(&mut app, "q");
    assert!(app.should_quit());
    assert!(app.ray_log().unwrap().comparing());
    // Once back, the comparison is taken in on a tick, as renders are.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(600);
    while app.ray_log().unwrap().comparing() {
        assert!(
            std::time::Instant::now() < deadline,
            "the comparison never came back"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
        app.update(raystep::tui::Action::Tick);
    }
    // It is the comparison the debugger made on its own thread before:
    // the one ray left out is the only difference, in ours alone.
    let report = app
        .ray_log()
        .unwrap()
        .report()
        .expect("(3, 2) is in the log");
    assert!(!report.matches);
    let only_ours: Vec<String> = report
        .only_ours
        .iter()
        .map(|u| u.path.to_string())
        .collect();
    assert_eq!(only_ours, [left_out]);
    assert!(report.only_yours.is_empty());
    assert_eq!(report.rays_ours, 98_326);
    let title = tree_title(&mut app);
    assert!(title.ends_with(" · your log differs "), "{title}");
    // Moved away, the pixel is not compared.
    press(&mut app, &[key(KeyCode::Right)]);
    assert_eq!(app.pixel().cursor(), (4, 2));
    let log = app.ray_log().unwrap();
    assert!(!log.comparing() && log.report().is_none());
}

/// The tree pane's title, from its top border.
fn tree_title(app: &mut App) -> String {
    let terminal = screen(app, 240, 40);
    let rect = app.panes().rect(Pane::Tree);
    let top: String = (rect.x..rect.x + rect.width)
        .map(|x| {
            terminal.backend().buffer()[(x, rect.y)]
                .symbol()
                .to_string()
        })
        .collect();
    top.trim_matches(|c| c == '─' || c == '┌' || c == '┐' || c == '╭' || c == '╮')
        .to_string()
}
