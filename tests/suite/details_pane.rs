//! The details pane highlights the lines of the selected event by what each
//! line is about, and draws a swatch after each colour. The screen snapshots
//! hold text only, so these tests read the styles of a `TestBackend` buffer.

use glam::DVec3;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use raystep::tui::pane::details;
use raystep::tui::{Action, App};
use raystep_engine::record::EventKind;
use raystep_engine::record::stepping::Step;
use raystep_model::math::to_rgb8;

/// A mirror ball in front of a grey wall, lit from the eye's right. The centre
/// pixel hits the ball at (0, 0, 1), facing the eye: its reflected ray
/// (weight ks = 0.7 >= min_weight) goes straight back past the eye and misses.
/// Pixel (12, 20) looks at the wall left of the ball, inside its shadow: the
/// shadow ray to the lamp crosses the ball, and the wall's reflected ray
/// (weight ks = 0.5 < min_weight = 0.6) is not cast.
const SCENE: &str = r#"
[camera]
eye = [0, 0, 10]
look_at = [0, 0, 0]
up = [0, 1, 0]
fov = 40

[image]
width = 41
height = 41

[settings]
background = [0.1, 0.2, 0.3]
ambient = [0.1, 0.1, 0.1]
min_weight = 0.6

[materials.mirror]
color = [1, 1, 1]
kd = 0.3
ks = 0.7
n = 20

[materials.wall]
color = [0.5, 0.5, 0.5]
kd = 0.8
ks = 0.5
n = 10

[[light]]
name = "lamp"
position = [5, 0, 10]

[[object]]
name = "ball"
material = "mirror"
sphere = { center = [0, 0, 0], radius = 1 }

[[object]]
name = "wall"
material = "wall"
plane = { normal = [0, 0, 1], point = [0, 0, -5] }
"#;

const WIDTH: u16 = 100;
const HEIGHT: u16 = 30;

fn app_at(x: u32, y: u32) -> App {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pane.toml");
    std::fs::write(&path, SCENE).unwrap();
    let mut app = App::open(Some(path), true).unwrap();
    app.update(Action::Pick(x, y));
    app
}

/// The first event of ray `node` that `test` accepts.
fn event(app: &App, node: usize, test: impl Fn(&EventKind) -> bool) -> usize {
    app.pixel()
        .tree()
        .events
        .iter()
        .position(|e| e.node == node && test(&e.kind))
        .expect("the event")
}

/// The details pane alone, filling the screen, at event `at` (stepped to
/// from the first event, as a user would).
fn pane(app: &mut App, at: usize) -> Buffer {
    app.update(Action::Step(Step::Start));
    for _ in 0..at {
        app.update(Action::Step(Step::Next));
    }
    assert_eq!(app.pixel().current(), at);
    let mut terminal = Terminal::new(TestBackend::new(WIDTH, HEIGHT)).unwrap();
    terminal
        .draw(|frame| details::draw(frame, app, frame.area()))
        .unwrap();
    terminal.backend().buffer().clone()
}

/// A row inside the border, as text.
fn row(buffer: &Buffer, y: u16) -> String {
    let text: String = (1..WIDTH - 1).map(|x| buffer[(x, y)].symbol()).collect();
    text.trim_end().to_string()
}

/// The rows of the pane drawn bold yellow, checking that every other row
/// has no yellow at all and that a highlighted row is yellow throughout
/// (but for its swatches, which keep their colour).
fn highlighted(buffer: &Buffer) -> Vec<String> {
    let mut rows = Vec::new();
    for y in 1..HEIGHT - 1 {
        let text = row(buffer, y);
        let cells: Vec<_> = (1..1 + text.chars().count() as u16)
            .map(|x| &buffer[(x, y)])
            .filter(|c| c.symbol() != "█")
            .collect();
        let yellow = |c: &&&ratatui::buffer::Cell| c.fg == Color::Yellow;
        if !cells.is_empty() && cells.iter().all(|c| yellow(&c)) {
            assert!(cells.iter().all(|c| c.modifier == Modifier::BOLD), "{text}");
            rows.push(text);
        } else {
            assert!(!cells.iter().any(|c| yellow(&c)), "part yellow: {text}");
        }
    }
    rows
}

/// `rows` start with `prefixes`, one for one.
fn assert_rows(rows: &[String], prefixes: &[&str]) {
    assert_eq!(rows.len(), prefixes.len(), "{rows:#?}");
    for (row, prefix) in rows.iter().zip(prefixes) {
        assert!(row.starts_with(prefix), "{row:?} does not start {prefix:?}");
    }
}

/// The swatch colours of a row, left to right.
fn swatches(buffer: &Buffer, y: u16) -> Vec<Color> {
    (1..WIDTH - 1)
        .map(|x| &buffer[(x, y)])
        .filter(|c| c.symbol() == "█")
        .map(|c| c.fg)
        .step_by(2)
        .collect()
}

fn rgb(c: DVec3) -> Color {
    let [r, g, b] = to_rgb8(c);
    Color::Rgb(r, g, b)
}

#[test]
fn a_blocker_and_its_light_highlight_all_the_lights_lines() {
    let mut app = app_at(12, 20);
    // A light that is not facing away gets its lines: N·L and S (here with
    // the blocker), f_att and the cosine, then the diffuse and specular
    // terms, each as its formula and its numbers (S = 0, so both are 0;
    // the diffuse numbers wrap at 100 columns). The blocker's working comes
    // after the first line: a unit-length shadow ray, so A = 1, and the ball
    // crossed at both roots.
    let lamp = [
        "lamp: N·L = ",
        "  ball crossed at t = 4.4555 (root t0) and t = 6.4054 (root t1):",
        "    sphere: A = 1, B = ",
        "    roots t0 = 4.4555, t1 = 6.4054",
        "  f_att = 1, N·H = ",
        "  diffuse = S · f_att · I_p · k_d · O_d · (N·L)",
        "    = 0 · 1 · (1.000, 1.000, 1.000) ██ · 0.8 · (0.500, 0.500, 0.500) ██ ·",
        "        (0.000, 0.000, 0.000) ██",
        "  specular = S · f_att · I_p · k_s · (N·H)^n",
        "    = 0 · 1 · (1.000, 1.000, 1.000) ██ · 0.5 · ",
    ];
    let blocker = event(&app, 0, |k| matches!(k, EventKind::Blocker { .. }));
    let buffer = pane(&mut app, blocker);
    assert_rows(&highlighted(&buffer), &lamp);
    assert!(highlighted(&buffer)[0].contains("S = 0, blocked by ball"));
    let shadow_cast = event(&app, 0, |k| matches!(k, EventKind::ShadowCast { .. }));
    assert_rows(&highlighted(&pane(&mut app, shadow_cast)), &lamp);
    let light = event(&app, 0, |k| matches!(k, EventKind::Light { .. }));
    assert_rows(&highlighted(&pane(&mut app, light)), &lamp);
}

#[test]
fn a_ray_not_cast_highlights_its_line() {
    let mut app = app_at(12, 20);
    let at = event(&app, 0, |k| matches!(k, EventKind::NotCast(_)));
    assert_rows(
        &highlighted(&pane(&mut app, at)),
        &["reflected ray not cast: accumulated weight 0.5 < min_weight 0.6"],
    );
}

#[test]
fn a_missed_ray_highlights_its_miss_when_done() {
    let mut app = app_at(20, 20);
    // The reflected ray r1 misses; its colour is the background, on the
    // miss line, which its miss and its done events both highlight (done
    // used to highlight nothing: a miss has no "colour" line).
    let missed = "missed everything (1 primitive tested): background (0.100, 0.200, 0.300)";
    let done = event(&app, 1, |k| matches!(k, EventKind::RayDone { .. }));
    let buffer = pane(&mut app, done);
    assert_rows(&highlighted(&buffer), &[missed]);
    // Header, "from" line, then the miss line with the background's swatch.
    assert!(row(&buffer, 3).starts_with(missed));
    assert_eq!(swatches(&buffer, 3), [rgb(DVec3::new(0.1, 0.2, 0.3))]);
    let miss = event(&app, 1, |k| matches!(k, EventKind::Miss { .. }));
    assert_rows(&highlighted(&pane(&mut app, miss)), &[missed]);
}

#[test]
fn the_primary_ray_lists_its_child_and_highlights_it_returning() {
    let mut app = app_at(20, 20);
    // r1 adds 0.7 x background = (0.07, 0.14, 0.21), shown with its swatch.
    let returned = event(&app, 0, |k| matches!(k, EventKind::ChildReturned { .. }));
    let buffer = pane(&mut app, returned);
    let rows = highlighted(&buffer);
    assert_rows(&rows, &["reflected ray r1 adds (0.070, 0.140, 0.210)"]);
    let y = (1..HEIGHT - 1)
        .find(|&y| row(&buffer, y) == rows[0])
        .unwrap();
    assert_eq!(swatches(&buffer, y), [rgb(DVec3::new(0.07, 0.14, 0.21))]);
    // Done: the colour line, not the child line above it.
    let done = event(&app, 0, |k| matches!(k, EventKind::RayDone { .. }));
    assert_rows(&highlighted(&pane(&mut app, done)), &["colour ("]);
}
