//! The debugger without a terminal: keys in, state out. Whole screens are
//! pinned in `tui_screens.rs`.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::style::Color;
use raystep::tui::{self, Action, App, Pane, Picture};
use raystep_engine::record::stepping::{Breakpoint, Step};
use raystep_engine::record::{EventKind, record_pixel};
use raystep_engine::scene::SpecularModel;
use raystep_engine::terms::Term;
use raystep_model::math::to_rgb8;
use raystep_model::mistakes::Mistake;

use crate::support::debugger::*;

#[test]
fn starts_on_the_centre_pixel_with_its_tree() {
    let app = app();
    assert_eq!(app.pixel().cursor(), (80, 60));
    assert_eq!(
        app.pixel().tree().nodes.len(),
        7,
        "the seven rays of the seven-rays scene"
    );
    assert_eq!(app.pixel().current(), 0);
    assert_eq!(app.screen().focus(), Pane::Image);
    assert!(
        app.renders().image().is_some(),
        "sync mode renders before returning"
    );
}

#[test]
fn cursor_moves_and_clamps_at_the_image_edge() {
    let mut app = app();
    press(
        &mut app,
        &[
            key(KeyCode::Right),
            key(KeyCode::Char('l')),
            key(KeyCode::Down),
        ],
    );
    assert_eq!(app.pixel().cursor(), (82, 61));
    press(&mut app, &[shift('H'), key(KeyCode::Char('k'))]);
    assert_eq!(app.pixel().cursor(), (72, 60));
    press(
        &mut app,
        &[Event::Key(KeyEvent::new(
            KeyCode::Left,
            KeyModifiers::SHIFT,
        ))],
    );
    assert_eq!(app.pixel().cursor(), (62, 60));
    app.update(Action::Move(-1000, -1000));
    assert_eq!(app.pixel().cursor(), (0, 0));
    app.update(Action::Move(1000, 1000));
    assert_eq!(app.pixel().cursor(), (160, 120));
    chars(&mut app, "lj");
    assert_eq!(
        app.pixel().cursor(),
        (160, 120),
        "the cursor stays on the last pixel"
    );
}

#[test]
fn picking_a_pixel_shows_exactly_what_inspect_records() {
    let mut app = app();
    for (x, y) in [(0, 0), (80, 82), (123, 45), (160, 120)] {
        app.update(Action::Pick(x, y));
        let expected = record_pixel(app.session().scene(), app.session().settings(), x, y);
        assert_eq!(app.pixel().tree().pixel, (x, y));
        assert_eq!(app.pixel().tree().color(), expected.color());
        assert_eq!(app.pixel().tree().events.len(), expected.events.len());
        let shown = app.renders().image().unwrap().get_pixel(x, y).0;
        assert_eq!(
            shown,
            to_rgb8(expected.color()),
            "the image pixel is the recorded colour"
        );
    }
}

#[test]
fn steps_move_like_a_debugger() {
    // Events of pixel (80, 60): r0 refracts at 7, casts r1 at 8; r1 returns at 28; the end is 54.
    let mut app = app();
    let step = |app: &mut App, step: Step| {
        app.update(Action::Step(step));
        app.pixel().current()
    };
    assert_eq!(
        step(&mut app, Step::Previous),
        0,
        "no event before the first"
    );
    assert_eq!(step(&mut app, Step::Next), 1);
    assert_eq!(step(&mut app, Step::Into), 8, "into: the next ray cast, r1");
    assert_eq!(step(&mut app, Step::Next), 9);
    assert_eq!(step(&mut app, Step::Out), 28, "out: where r1 returns to r0");
    assert!(matches!(
        app.pixel().tree().events[28].kind,
        EventKind::ChildReturned { child: 1, .. }
    ));
    app.update(Action::Step(Step::Start));
    for _ in 0..7 {
        app.update(Action::Step(Step::Over));
    }
    assert_eq!(app.pixel().current(), 7, "over: r0's own events one by one");
    assert_eq!(step(&mut app, Step::Over), 28, "over skips r1's subtree");
    assert_eq!(
        step(&mut app, Step::Out),
        54,
        "out of the primary ray: the end"
    );
    assert_eq!(step(&mut app, Step::Next), 54, "no event after the last");
    chars(&mut app, "g");
    assert_eq!(app.pixel().current(), 0);
    chars(&mut app, "e");
    assert_eq!(app.pixel().current(), 54);
    app.update(Action::Step(Step::Start));
    chars(&mut app, "nnnp");
    assert_eq!(app.pixel().current(), 2);
}

#[test]
fn over_at_the_end_of_a_child_ray_returns_to_the_parent() {
    let mut app = app();
    for _ in 0..16 {
        app.update(Action::Step(Step::Next));
    }
    assert_eq!(app.pixel().current(), 16);
    let event = &app.pixel().tree().events[16];
    assert!(
        matches!(event.kind, EventKind::RayDone { .. }) && event.node == 2,
        "r2 done"
    );
    app.update(Action::Step(Step::Over));
    assert_eq!(app.pixel().current(), 17);
    assert_eq!(app.pixel().tree().events[17].node, 1);
}

#[test]
fn blocked_shadow_breakpoint_lands_on_the_first_blocker() {
    let mut app = app();
    chars(&mut app, "b");
    let event = &app.pixel().tree().events[app.pixel().current()];
    assert_eq!(app.pixel().current(), 22);
    assert_eq!(event.node, 3, "the transmitted ray inside the green ball");
    assert!(
        matches!(
            event.kind,
            EventKind::Blocker {
                light: 0,
                object: 1,
                ..
            }
        ),
        "key light blocked by the green ball"
    );
    chars(&mut app, "b");
    assert_eq!(
        app.pixel().current(),
        33,
        "the next shadow ray, not the next blocker of the same ray"
    );
    chars(&mut app, "bb");
    assert_eq!(app.pixel().current(), 44);
    chars(&mut app, "b");
    assert_eq!(app.pixel().current(), 44, "no more: it stays");
    assert!(
        app.message()
            .unwrap_or("")
            .contains("no blocked shadow ray")
    );
}

#[test]
fn floor_pixel_in_the_balls_shadow() {
    let mut app = app();
    app.update(Action::Pick(80, 82));
    chars(&mut app, "b");
    let event = &app.pixel().tree().events[app.pixel().current()];
    assert!(
        matches!(
            event.kind,
            EventKind::Blocker {
                light: 0,
                object: 0,
                ..
            }
        ),
        "{event:?}"
    );
    let light = &app.pixel().tree().root().lights[0];
    let shadow = light.shadow.as_ref().unwrap();
    assert_eq!(shadow.blockers.len(), 2, "the glass ball is crossed twice");
    assert!((shadow.s - 0.49).abs() < 1e-12, "S = 0.7 x 0.7");
}

#[test]
fn object_breakpoint_uses_the_selected_rays_object_and_cycles() {
    let mut app = app();
    chars(&mut app, "x");
    assert_eq!(
        app.pixel().break_object(),
        Some(0),
        "r0 hits the glass ball"
    );
    assert_eq!(app.pixel().current(), 1, "r0's own hit comes first");
    chars(&mut app, "x");
    assert_eq!(
        app.pixel().current(),
        30,
        "the next hit on the glass ball: r4 from inside"
    );
    chars(&mut app, "X");
    assert_eq!(app.pixel().break_object(), Some(1));
    chars(&mut app, "gx");
    assert_eq!(
        app.pixel().current(),
        9,
        "the first hit on the green ball: r1"
    );
    chars(&mut app, "XX");
    assert_eq!(
        app.pixel().break_object(),
        Some(0),
        "cycles through the three objects"
    );
}

#[test]
fn tir_breakpoint_stops_at_total_internal_reflection() {
    // glass.toml names (135, 58) for TIR: into the glass block's top face,
    // then total internal reflection inside it. `T` runs to the first one.
    let glass = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/glass.toml");
    let mut glass = App::open(Some(glass), true).unwrap();
    glass.update(Action::Pick(135, 58));
    let is_tir = |kind: &EventKind| matches!(kind, EventKind::Refraction { tir: true });
    let first_tir = glass
        .pixel()
        .tree()
        .events
        .iter()
        .position(|e| is_tir(&e.kind));
    let first_tir = first_tir.expect("glass.toml 135,58 has a total internal reflection");
    assert!(first_tir > 0, "the primary ray's hit comes first");
    chars(&mut glass, "T");
    assert_eq!(glass.pixel().current(), first_tir);

    // The built-in scene's centre pixel has none: `T` stays and says so.
    let mut app = app();
    app.update(Action::Pick(80, 60));
    app.update(Action::RunTo(Breakpoint::Tir));
    assert_eq!(app.pixel().current(), 0, "the centre pixel has no TIR");
    assert!(
        app.message()
            .unwrap_or("")
            .contains("no total internal reflection")
    );
}

#[test]
fn toggles_change_settings_and_render_again() {
    let mut app = app();
    app.update(Action::Pick(80, 82));
    let before = app.renders().image().unwrap().get_pixel(80, 82).0;
    chars(&mut app, "s");
    assert!(!app.session().settings().switches.shadows);
    assert!(
        app.pixel().tree().root().lights[0].shadow.is_none(),
        "no shadow rays when shadows are off"
    );
    let after = app.renders().image().unwrap().get_pixel(80, 82).0;
    assert!(
        after[0] > before[0],
        "the floor is lit without the ball's shadow: {before:?} -> {after:?}"
    );
    assert_eq!(after, to_rgb8(app.pixel().tree().color()));
    chars(&mut app, "s");
    assert!(app.session().settings().switches.shadows);
    assert_eq!(app.renders().image().unwrap().get_pixel(80, 82).0, before);

    app.update(Action::Pick(80, 60));
    chars(&mut app, "r");
    assert!(!app.session().settings().switches.reflection);
    assert!(app.pixel().tree().root().reflected.is_none());
    chars(&mut app, "t");
    assert!(!app.session().settings().switches.transmission);
    assert_eq!(app.pixel().tree().nodes.len(), 1);
    chars(&mut app, "a");
    assert!(!app.session().settings().switches.ambient);
    assert_eq!(app.pixel().tree().root().ambient, glam::DVec3::ZERO);
    chars(&mut app, "m");
    assert_eq!(app.session().settings().specular, SpecularModel::Phong);
    chars(&mut app, "m");
    assert_eq!(app.session().settings().specular, SpecularModel::Blinn);
}

#[test]
fn max_depth_stays_within_its_bounds() {
    let mut app = app();
    assert_eq!(app.session().settings().max_depth, 3);
    chars(&mut app, "[[[[");
    assert_eq!(app.session().settings().max_depth, 1);
    assert_eq!(
        app.pixel().tree().nodes.len(),
        1,
        "depth 1: the primary ray only"
    );
    assert!(app.message().unwrap_or("").contains("stays 1"));
    for _ in 0..40 {
        chars(&mut app, "]");
    }
    assert_eq!(app.session().settings().max_depth, tui::app::MAX_DEPTH);
    assert!(
        app.pixel()
            .tree()
            .nodes
            .iter()
            .all(|n| n.depth <= tui::app::MAX_DEPTH)
    );
}

#[test]
fn term_views_cycle_and_render_the_terms() {
    let mut app = app();
    chars(&mut app, "v");
    assert_eq!(app.screen().picture(), Picture::Term(Term::Ambient));
    assert!(app.renders().terms().is_some());
    for _ in 0..5 {
        chars(&mut app, "v");
    }
    assert_eq!(app.screen().picture(), Picture::Term(Term::Shadow));
    app.update(Action::Pick(80, 82));
    let shadow = app.shown_pixel(80, 82).unwrap();
    assert_eq!(
        shadow,
        to_rgb8(glam::DVec3::splat((0.49 + 1.0) / 2.0)),
        "mean S over the two lights"
    );
    chars(&mut app, "vvv");
    assert_eq!(app.screen().picture(), Picture::Render);
}

#[test]
fn an_emitting_scene_has_an_emission_view_after_the_ambient() {
    // scenes/cse167/ambient-emission.test: its right ball emits E = (0.9,
    // 0.5, 0.1) and nothing else, so the emission view shows it at the
    // ball's centre, floor(255 E + 0.5) = (230, 128, 26), as emission.png
    // does (tests/suite/term_images.rs). The lecture's built-in scene has
    // no emission view (above: ambient, then diffuse).
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/cse167/ambient-emission.test");
    let mut app = tui::App::open(Some(scene), true).unwrap();
    chars(&mut app, "v");
    assert_eq!(app.screen().picture(), Picture::Term(Term::Ambient));
    chars(&mut app, "v");
    assert_eq!(app.screen().picture(), Picture::Term(Term::Emission));
    assert_eq!(app.shown_pixel(118, 60), Some([230, 128, 26]));
    chars(&mut app, "v");
    assert_eq!(app.screen().picture(), Picture::Term(Term::Diffuse));
}

#[test]
fn tree_selection_and_collapse_follow_the_events() {
    let mut app = app();
    press(&mut app, &[key(KeyCode::Tab)]);
    assert_eq!(app.screen().focus(), Pane::Tree);
    press(&mut app, &[key(KeyCode::Down)]);
    assert!(
        matches!(
            app.pixel().tree().events[app.pixel().current()].kind,
            EventKind::ShadowCast { light: 0 }
        ),
        "the key light's row"
    );
    press(&mut app, &[key(KeyCode::Down), key(KeyCode::Down)]);
    assert_eq!(app.pixel().current(), 8, "r1's row selects its cast");
    press(&mut app, &[key(KeyCode::Enter)]);
    assert!(app.pixel().collapsed().contains(&1));
    let rows = tui::view::tree::rows(app.pixel().tree(), app.pixel().collapsed());
    assert_eq!(
        rows.len(),
        3 + 1 + 3 + 3 + 1,
        "r0 and its lights, r1 collapsed, r4, r5 with their lights, r6"
    );
    press(&mut app, &[key(KeyCode::Enter)]);
    assert!(app.pixel().collapsed().is_empty());
}

#[test]
fn tab_cycles_the_panes_and_arrows_act_on_the_focused_one() {
    let mut app = app();
    let order: Vec<Pane> = (0..5)
        .map(|_| {
            press(&mut app, &[key(KeyCode::Tab)]);
            app.screen().focus()
        })
        .collect();
    assert_eq!(
        order,
        [
            Pane::Tree,
            Pane::Steps,
            Pane::Details,
            Pane::Diagram,
            Pane::Image
        ]
    );
    press(
        &mut app,
        &[
            key(KeyCode::BackTab),
            key(KeyCode::BackTab),
            key(KeyCode::BackTab),
        ],
    );
    assert_eq!(app.screen().focus(), Pane::Steps);
    press(&mut app, &[key(KeyCode::Down), key(KeyCode::Down)]);
    assert_eq!(
        (app.pixel().current(), app.pixel().cursor()),
        (2, (80, 60)),
        "in the steps pane, arrows step"
    );
}

#[test]
fn clicks_pick_pixels_and_rows() {
    let mut app = app();
    let grid = app.image_grid().unwrap();
    let (column, row, _) = grid.cursor_cell((40, 30)).unwrap();
    app.update(Action::Click(column, row));
    let picked = app.pixel().cursor();
    assert_eq!(grid.pixel_at_cell(column, row), Some(picked));
    assert!(
        picked.0.abs_diff(40) <= 3 && picked.1.abs_diff(30) <= 3,
        "{picked:?}"
    );
    assert_eq!(app.screen().focus(), Pane::Image);
    let tree = app.panes().tree;
    app.update(Action::Click(tree.x + 5, tree.y + 1));
    assert_eq!(app.screen().focus(), Pane::Tree);
    assert_eq!(app.pixel().current(), 0, "the first row is the primary ray");
}

#[test]
fn zoom_goes_down_to_one_pixel_per_half_cell() {
    let mut app = app();
    chars(&mut app, "++++++++");
    let grid = app.image_grid().unwrap();
    assert_eq!(grid.scale, 1.0);
    assert!(
        app.message()
            .unwrap_or("")
            .contains("zoomed in all the way")
    );
    assert_eq!(
        grid.sample(0, 0),
        (grid.origin.0 as u32, grid.origin.1 as u32)
    );
    assert!(
        grid.display_of(app.pixel().cursor()).is_some(),
        "the cursor stays in view"
    );
    chars(&mut app, "--------");
    assert_eq!(app.screen().zoom(), 1);
}

#[test]
fn image_cells_carry_the_pixel_colours() {
    let mut app = app();
    app.update(Action::Pick(10, 10));
    let terminal = screen(&mut app, 120, 40);
    let grid = app.image_grid().unwrap();
    let (column, row) = (grid.area.x + 20, grid.area.y + 5);
    let cell = &terminal.backend().buffer()[(column, row)];
    let [r, g, b] = app
        .renders()
        .image()
        .unwrap()
        .get_pixel(grid.sample(20, 10).0, grid.sample(20, 10).1)
        .0;
    assert_eq!(cell.symbol(), "▀");
    assert_eq!(cell.fg, Color::Rgb(r, g, b));
    let [r, g, b] = app
        .renders()
        .image()
        .unwrap()
        .get_pixel(grid.sample(20, 11).0, grid.sample(20, 11).1)
        .0;
    assert_eq!(cell.bg, Color::Rgb(r, g, b));
}

#[test]
fn reload_applies_an_edit_and_keeps_the_pixel() {
    let path = scene_file("reload-edit.toml");
    let mut app = App::open(Some(path.clone()), true).unwrap();
    app.update(Action::Pick(80, 82));
    chars(&mut app, "s");
    edit(&path, "max_depth = 3", "max_depth = 2");
    app.update(Action::Reload);
    assert_eq!(app.pixel().cursor(), (80, 82));
    assert_eq!(
        app.session().settings().max_depth,
        2,
        "the file changed max_depth"
    );
    assert!(
        !app.session().settings().switches.shadows,
        "the toggle survives the reload"
    );
    assert!(app.session().error().is_none());
}

#[test]
fn reload_with_a_broken_file_keeps_the_last_good_scene() {
    let path = scene_file("reload-broken.toml");
    let mut app = App::open(Some(path.clone()), true).unwrap();
    let objects = app.session().scene().objects.len();
    edit(&path, "radius = 1.0", "radius = \"big\"");
    app.update(Action::Reload);
    let error = app.session().error().expect("an error banner");
    assert!(
        error.starts_with("target/tui-tests/reload-broken.toml:"),
        "{error}"
    );
    assert_eq!(app.session().scene().objects.len(), objects);
    assert_eq!(
        app.pixel().tree().nodes.len(),
        7,
        "the last good scene is still traced"
    );
    edit(&path, "radius = \"big\"", "radius = 1.0");
    app.update(Action::Reload);
    assert!(app.session().error().is_none());
}

#[test]
fn the_watcher_reloads_on_save() {
    let path = scene_file("reload-watched.toml");
    let mut app = App::open(Some(path.clone()), true).unwrap().watching();
    std::thread::sleep(Duration::from_millis(100));
    edit(&path, "max_depth = 3", "max_depth = 4");
    let started = Instant::now();
    while app.session().settings().max_depth != 4 && started.elapsed() < Duration::from_secs(10) {
        app.update(Action::Tick);
        std::thread::sleep(Duration::from_millis(20));
    }
    assert_eq!(
        app.session().settings().max_depth,
        4,
        "reloaded within 10 s"
    );
}

#[test]
fn the_main_loop_runs_on_a_test_backend() {
    let mut app = app();
    let mut terminal = Terminal::new(TestBackend::new(120, 40)).unwrap();
    let mut input: VecDeque<Event> = [
        key(KeyCode::Char('l')),
        key(KeyCode::Char('n')),
        key(KeyCode::Char('?')),
    ]
    .into();
    tui::run_loop(&mut terminal, &mut app, &mut input).unwrap();
    assert!(app.should_quit());
    assert_eq!((app.pixel().cursor(), app.pixel().current()), ((81, 60), 1));
}

#[test]
fn help_closes_on_any_key_and_esc_quits() {
    let mut app = app();
    chars(&mut app, "?");
    assert_eq!(app.overlay().mode(), tui::Mode::Help);
    chars(&mut app, "n");
    assert_eq!(app.overlay().mode(), tui::Mode::Browsing);
    assert_eq!(app.pixel().current(), 0, "the key only closed the help");
    press(&mut app, &[key(KeyCode::Esc)]);
    assert!(app.should_quit());
}

#[test]
fn the_help_says_how_to_quit_on_its_first_screen() {
    // At 80x24 the help scrolls (the quit row of "Other" was below the
    // fold); at 200x60 too. Its first line says how to quit, visible at
    // both sizes: the help box is centred, so read every row.
    for (width, height) in [(80, 24), (200, 60)] {
        let mut app = app();
        chars(&mut app, "?");
        let terminal = screen(&mut app, width, height);
        let buffer = terminal.backend().buffer();
        let text: String = (0..height)
            .map(|y| {
                (0..width)
                    .map(|x| buffer[(x, y)].symbol().to_string())
                    .collect::<String>()
                    + "\n"
            })
            .collect();
        assert!(
            text.contains("To quit: q or Esc"),
            "{width}x{height}:\n{text}"
        );
    }
}

#[test]
fn q_in_the_help_closes_it_and_only_then_quits() {
    let mut app = app();
    chars(&mut app, "?q");
    assert_eq!(app.overlay().mode(), tui::Mode::Browsing);
    assert!(!app.should_quit(), "q closed the help");
    chars(&mut app, "q");
    assert!(app.should_quit());
}

#[test]
fn a_newcomer_sees_the_welcome_at_any_terminal_size() {
    // Regression: the first draw in a terminal other than 120x40 resized
    // the app, and the resize cleared the welcome before anyone saw it.
    let mut app = app();
    let terminal = screen(&mut app, 160, 48);
    assert_eq!(app.message(), Some(tui::app::WELCOME));
    let bottom: String = (0..160)
        .map(|x| terminal.backend().buffer()[(x, 47)].symbol().to_string())
        .collect();
    assert!(bottom.contains("arrows pick a pixel"), "{bottom}");
}

#[test]
fn a_toggle_shows_what_changed_for_the_pixel_until_another_is_picked() {
    // Max depth 3 -> 2 -> 1 on the centre pixel: the last toggle (2 -> 1)
    // leaves the primary ray alone, and every ray the depth-2 tree had
    // below it is gone (as record::diff says).
    let mut app = app();
    app.update(Action::Depth(-1));
    let rays = app.pixel().tree().nodes.len();
    assert!(rays > 1);
    app.update(Action::Depth(-1));
    assert_eq!(app.session().settings().max_depth, 1);
    let what_if = app
        .pixel()
        .what_if()
        .expect("a toggle records what changed");
    assert_eq!(
        what_if.matches("ray is gone").count(),
        rays - 1,
        "{what_if}"
    );
    let screen = screen(&mut app, 120, 40);
    let text: String = screen
        .backend()
        .buffer()
        .content()
        .iter()
        .map(|c| c.symbol())
        .collect();
    assert!(
        text.contains("What changed with the last toggle:"),
        "{text}"
    );
    app.update(Action::Pick(0, 0));
    assert!(app.pixel().what_if().is_none());
}

#[test]
fn the_first_pixel_is_timed_too() {
    // The status line's "pixel traced in N µs" said 0 µs until the first
    // pick: the opening recording was not timed. It is a part of opening,
    // so it is more than nothing and no more than the whole opening took.
    let started = Instant::now();
    let app = app();
    let opening = started.elapsed();
    assert!(app.pixel().pick_time() > Duration::ZERO);
    assert!(
        app.pixel().pick_time() <= opening,
        "{:?} > {opening:?}",
        app.pixel().pick_time()
    );
}

#[test]
fn one_overlay_at_a_time_help_then_mistakes_menu() {
    // Help and menu were two flags: asked for while the help was open, the
    // menu opened under it, and closing the help uncovered it. The overlay
    // is now one value, so only one of them can be open.
    let mut app = app();
    chars(&mut app, "?");
    assert_eq!(app.overlay().mode(), tui::Mode::Help);
    // With the help open, M closes it like any key: the menu waits.
    chars(&mut app, "M");
    assert_eq!(app.overlay().mode(), tui::Mode::Browsing);
    assert_eq!(app.overlay().menu_row(), None);
    chars(&mut app, "M");
    assert_eq!(app.overlay().mode(), tui::Mode::Menu);
    assert_eq!(app.overlay().menu_row(), Some(0));
    // Asked for directly, the help replaces the menu instead of lying over it.
    app.update(Action::ToggleHelp);
    assert_eq!(app.overlay().mode(), tui::Mode::Help);
    assert_eq!(
        app.overlay().menu_row(),
        None,
        "the menu closed under the help"
    );
    app.update(Action::CloseHelp);
    assert_eq!(
        app.overlay().mode(),
        tui::Mode::Browsing,
        "nothing left open"
    );
}

/// The three mistakes of refraction, which the cse167 profile does not
/// offer: it casts no transmitted ray (MODEL §11).
const REFRACTION: [Mistake; 3] = [
    Mistake::EtaInverted,
    Mistake::TirDropped,
    Mistake::RefractionOutwardNormal,
];

#[test]
fn a_cse167_scene_offers_no_mistake_of_refraction() {
    for name in ["mirrors.test", "ring.test"] {
        let path = std::path::PathBuf::from("scenes/cse167").join(name);
        let app = App::open(Some(path), true).unwrap();
        let menu = app.overlay().menu_mistakes();
        // 22 in the catalogue, less the three; each once, in its order.
        let offered: Vec<Mistake> = Mistake::ALL
            .into_iter()
            .filter(|m| !REFRACTION.contains(m))
            .collect();
        assert_eq!(menu, offered, "{name}");
        assert!(menu.contains(&Mistake::OpaqueShadows), "S is still Π k_t");
    }
    // The lecture's built-in scene: the whole catalogue, as before.
    assert_eq!(app().overlay().menu_mistakes(), Mistake::ALL);
}

#[test]
fn a_mistake_not_offered_is_not_toggled() {
    let path = std::path::PathBuf::from("scenes/cse167/mirrors.test");
    let mut app = App::open(Some(path), true).unwrap();
    app.update(Action::ToggleMistake(Mistake::EtaInverted));
    assert!(app.session().settings().mistakes.is_empty());
    assert_eq!(
        app.message(),
        Some(
            "mistake eta-inverted has no meaning under the cse167 profile: \
             it has no refraction (MODEL §11)"
        )
    );
}

#[test]
fn a_reload_into_cse167_drops_the_mistakes_of_refraction() {
    let path = scene_file("reload-profile.toml");
    let mut app = App::open(Some(path.clone()), true).unwrap();
    app.update(Action::ToggleMistake(Mistake::EtaInverted));
    app.update(Action::ToggleMistake(Mistake::ShadowAcne));
    assert_eq!(app.overlay().menu_mistakes(), Mistake::ALL);
    edit(&path, "[settings]\n", "[settings]\nprofile = \"cse167\"\n");
    app.update(Action::Reload);
    assert!(app.session().error().is_none());
    let settings = app.session().settings();
    assert_eq!(settings.profile.name(), "cse167");
    assert_eq!(
        settings.mistakes.iter().collect::<Vec<_>>(),
        [Mistake::ShadowAcne],
        "eta-inverted is switched off, shadow-acne kept"
    );
    assert!(
        !(app.overlay().menu_mistakes().iter()).any(|m| REFRACTION.contains(m)),
        "the menu follows the profile"
    );
    assert_eq!(app.overlay().menu_mistakes().len(), 19);
    let message = app.message().unwrap();
    assert!(
        message.ends_with("; switched off eta-inverted: no meaning under the cse167 profile"),
        "{message}"
    );
    // And back: the whole catalogue again, nothing switched on by itself.
    edit(&path, "profile = \"cse167\"\n", "");
    app.update(Action::Reload);
    assert_eq!(app.overlay().menu_mistakes(), Mistake::ALL);
    assert_eq!(app.session().settings().mistakes.iter().count(), 1);
}
