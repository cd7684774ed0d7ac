//! Issue 16's "Done when": the five questions a student asked of scenes of
//! their own are each answered by `explain` alone, and reached in the
//! debugger within 5 keys from its start (the centre pixel, no --pixel).
//!
//! (a) an opaque shadow from one of two lights   two-lights.toml 75,65
//! (b) a fractional shadow through glass and a pane   two-lights.toml 94,66
//! (c) a pixel lit mostly by a reflection          mirrors.toml 97,50
//! (d) total internal reflection in a prism        prism.toml 90,60
//! (e) a ray through the notch of a concave polygon   polygons.toml 30,30

use std::path::{Path, PathBuf};

use raystep::tui::{App, Mode};
use raystep_engine::record::{explain, explain_unwrapped, record_pixel};
use raystep_engine::scene::load;

use crate::support::debugger::*;

fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
}

/// `raystep explain scenes/NAME --pixel X,Y` before wrapping, one line per
/// sentence, so that a test finds a sentence on one line; and as printed.
fn explain_pixel(name: &str, (x, y): (u32, u32)) -> (String, String) {
    let scene = load(&scene_path(name)).unwrap();
    let tree = record_pixel(&scene, &scene.settings, x, y);
    (explain_unwrapped(&tree), explain(&tree))
}

/// The number after `prefix` in `text` (up to a space, comma or bracket).
fn number_after(text: &str, prefix: &str) -> f64 {
    let start = text
        .find(prefix)
        .unwrap_or_else(|| panic!("{prefix} in {text}"))
        + prefix.len();
    let rest = &text[start..];
    let end = rest
        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .unwrap_or(rest.len());
    rest[..end].parse().unwrap()
}

#[test]
fn a_an_opaque_shadow_from_one_of_two_lights() {
    // Pixel 92,61 looks at the floor near p = (0.84, 0, -0.89). The red ball
    // (centre c = (1.5, 0.6, -1.05), r = 0.5, opaque) stands between p and
    // the right light (6, 6, -1): along d = normalize((6, 6, -1) - p) =
    // (0.65, 0.76, -0.01), the closest approach to c is at
    // t = (c - p)·d = 0.89, at |p + t d - c| = 0.18 < 0.5: the ray enters
    // and leaves the ball (two crossings, k_t 0 each), S = 0. Towards the
    // left light (-12, 6, -0.5) it rises over the picture's left side, far
    // above the glass ball and the pane: S = 1.
    let (text, printed) = explain_pixel("two-lights.toml", (92, 61));
    assert!(text.contains("hits floor"), "{text}");
    assert!(
        text.contains("right: in shadow, blocked by red ball (opaque)"),
        "{text}"
    );
    assert!(text.contains("S = 0;"), "{text}");
    assert!(text.contains("left: lit, nothing in the way"), "{text}");
    assert!(text.contains("diffuse from left"), "{text}");
    assert!(!text.contains("diffuse from right"), "{text}");
    snapshot!("a_opaque_shadow", &printed);
}

#[test]
fn b_a_fractional_shadow_through_glass_and_a_pane() {
    // Pixel 3,64 looks at the floor near p = (-4.92, 0, -0.42). Towards the
    // left light (-12, 6, -0.5) its shadow ray passes the glass ball's
    // centre (-5.7, 0.6, -0.5) at 0.09 < r = 0.5 (at t = 0.98), entering and leaving it (k_t 0.6 twice), and then meets
    // the plane x = -6.75 at a fraction 1.83 / 7.08 = 0.26 of the way, at
    // y = 1.55, z = -0.44: inside the pane (y 0.8..2.4, z -1.4..0.4),
    // k_t 0.8. S = 0.6 x 0.6 x 0.8 = 0.288.
    let (text, printed) = explain_pixel("two-lights.toml", (3, 64));
    assert!(
        text.contains(
            "left: partly blocked through glass ball (k_t = 0.6, crossed 2 times), glass pane (k_t = 0.8): S = 0.288"
        ),
        "{text}"
    );
    assert!(text.contains("right: lit, nothing in the way"), "{text}");
    snapshot!("b_fractional_shadow", &printed);
}

#[test]
fn c_a_pixel_lit_mostly_by_a_reflection() {
    // The right mirror (k_s 0.85) reflects the red ball: the reflected ray
    // brings I_r = (0.761, 0.135, 0.103), so k_s I_r = (0.647, 0.115,
    // 0.088), sum 0.850, of a pixel (0.751, 0.282, 0.276), sum 1.309:
    // 0.850 / 1.309 = 64.9% of the brightness, the largest term.
    let (text, printed) = explain_pixel("mirrors.toml", (97, 50));
    let terms = text
        .lines()
        .skip_while(|l| !l.starts_with("Its colour is the sum"))
        .nth(1)
        .unwrap();
    assert!(terms.trim_start().starts_with("reflected ray"), "{terms}");
    let share = number_after(terms, ")   ");
    assert!((share - 64.9).abs() < 0.05, "{share} in {terms}");
    assert!(
        text.contains("Reflected ray (weight 0.85): hits red ball"),
        "{text}"
    );
    snapshot!("c_mostly_reflection", &printed);
}

#[test]
fn d_total_internal_reflection_in_a_prism() {
    // Pixel 90,60's primary ray d = (0.0468, -0.0272, -0.9985) enters the
    // front face z = 0 (cos_i = 0.9985, eta = 1/1.5) and goes on along
    // (0.0312, -0.0181, -0.9993). The right face's normal, facing the ray
    // from inside, is (-1, 0, 1)/sqrt 2: cos_i = 0.7287 (43.2 degrees, past
    // the critical 41.8), and with eta = 1.5,
    // k = 1 - 2.25 (1 - 0.7287^2) = -0.0552 < 0: TIR.
    let (text, printed) = explain_pixel("prism.toml", (90, 60));
    let line = text
        .lines()
        .find(|l| l.contains("total internal reflection at r1"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(line.contains("on prism right"), "{line}");
    let k = number_after(line, "k = ");
    assert!((k + 0.0552).abs() < 1e-4, "{k} in {line}");
    assert!(
        text.contains("total internal reflection at r2") && text.contains("on prism left"),
        "{text}"
    );
    snapshot!("d_prism_tir", &printed);
}

#[test]
fn e_a_ray_through_the_notch_of_a_concave_polygon() {
    // Left of the star's top tip the +U half-line from the hit point in
    // the star's plane crosses the tip's two edges: 2, even, outside; the
    // ray goes on to the back wall.
    let (text, printed) = explain_pixel("polygons.toml", (30, 30));
    let line = text
        .lines()
        .find(|l| l.contains("star") && l.contains("outside"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(line.contains("2 edge crossings"), "{line}");
    assert!(line.contains("even"), "{line}");
    assert!(text.contains("hits back wall"), "{text}");
    snapshot!("e_concave_notch", &printed);
}

// In the debugger, from the start: each answer in the details pane after
// at most 5 keys.

fn open(name: &str) -> App {
    App::open(Some(scene_path(name)), true).unwrap()
}

/// Every character on a 160x50 screen of the app.
fn screen_text(app: &mut App) -> String {
    let mut terminal = screen(app, 160, 50);
    let buffer = terminal.backend_mut().buffer().clone();
    (0..buffer.area.height)
        .map(|y| {
            (0..buffer.area.width)
                .map(|x| buffer[(x, y)].symbol().to_string())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Types `keys` (each char one key) and checks the count.
fn keys(app: &mut App, keys: &str, most: usize) {
    assert!(
        keys.chars().count() <= most,
        "{keys}: more than {most} keys"
    );
    chars(app, keys);
    assert_eq!(app.overlay().mode(), Mode::Browsing);
}

#[test]
fn each_answer_is_in_the_debugger_within_five_keys_of_the_start() {
    // (a) f b: from the centre (80, 60), the first blocked shadow ray in
    // reading order is on row 60, in the red ball's shadow. 2 keys.
    let mut app = open("two-lights.toml");
    keys(&mut app, "fb", 5);
    let text = screen_text(&mut app);
    assert!(
        text.contains("right: N·L") && text.contains("S = 0, blocked by red ball"),
        "{text}"
    );
    assert!(text.contains("left: N·L") && text.contains("S = 1 (nothing in the way)"));

    // (b) f p: the first partly blocked shadow ray after the centre is at
    // the left edge of row 61, through the glass ball and the pane. 2 keys.
    let mut app = open("two-lights.toml");
    keys(&mut app, "fp", 5);
    assert_eq!(app.pixel().cursor(), (0, 61));
    let text = screen_text(&mut app);
    assert!(
        text.contains("S = 0.288, partly blocked by glass ball"),
        "{text}"
    );
    assert!(text.contains("glass pane"), "{text}");

    // (c) no key: mirrors.toml's centre pixel is the right mirror, and the
    // reflected ray brings most of its colour (ray tree's share, details).
    let mut app = open("mirrors.toml");
    keys(&mut app, "", 5);
    let text = screen_text(&mut app);
    assert!(text.contains("r1 reflected → hit left mirror"), "{text}");
    assert!(
        text.contains("reflected ray r1 adds (0.469, 0.493, 0.463)"),
        "{text}"
    );
    assert!(text.contains("colour (0.569, 0.654, 0.644)"), "{text}");

    // (d) f t: the next pixel with TIR, its TIR event current. 2 keys.
    let mut app = open("prism.toml");
    keys(&mut app, "ft", 5);
    let text = screen_text(&mut app);
    assert!(
        text.contains("total internal reflection: no transmitted ray"),
        "{text}"
    );
    assert!(text.contains("k = -"), "{text}");
    assert!(
        text.contains("total internal reflection: kt goes to"),
        "{text}"
    );

    // (e) X X X f n: X chooses the centre's hit (back wall), then the floor,
    // then the star; f n goes to the next near miss of the star. 5 keys.
    let mut app = open("polygons.toml");
    keys(&mut app, "XXX", 5);
    assert_eq!(app.pixel().break_object(), Some(2), "the star");
    keys(&mut app, "fn", 2);
    let text = screen_text(&mut app);
    assert!(text.contains("passed by star"), "{text}");
    assert!(text.contains("2 edge crossings"), "{text}");
}
