//! Names are data: control characters never reach a terminal raw or break SVG, dot or JSON.
//!
//! Issue 27, item 4: TOML spells any character in a name (`"\u001b"`), so
//! a scene may name its object, material and light with ESC, BEL, BS, DEL,
//! NUL and the noncharacter U+FFFE. Text meant for a terminal (`inspect`,
//! `explain`, error messages), SVG and dot spell each as `\u{1b}`; JSON
//! keeps the exact name.

use std::path::Path;

use crate::support::{raystep, stderr, stdout, top_level_toml_scenes};

/// The hostile tail of every name: ESC starting a colour change, BEL, BS,
/// DEL, NUL and U+FFFE, as TOML spells them.
const TAIL_TOML: &str = r"\u001b[31m\u0007\b\u007f\u0000\uFFFE";
/// The same characters as the scene holds them.
const TAIL: &str = "\u{1b}[31m\u{7}\u{8}\u{7f}\u{0}\u{fffe}";
/// The same as every readable output spells them (`crate::printable`).
const TAIL_SPELT: &str = r"\u{1b}[31m\u{7}\u{8}\u{7f}\u{0}\u{fffe}";

/// A red ball named "ball" + TAIL, of material "paint" + TAIL, on a floor,
/// lit by "lamp" + TAIL up behind it on the left. At 40 x 30, pixel
/// (20, 12) hits the ball and (30, 22) is floor in the ball's shadow (the
/// lamp at (-2, 4, -2) through the ball's centre (0, 1, 0) meets the floor
/// at (0.67, 0, 0.67), in front of the ball and right of it), so between
/// them every kind of name is written: hit object, material, light, blocker.
fn hostile_scene(dir: &Path) -> String {
    let text = format!(
        r#"
[camera]
eye = [0, 2, 6]
look_at = [0, 0.5, 0]
up = [0, 1, 0]
fov = 40

[image]
width = 40
height = 30

[materials."paint{TAIL_TOML}"]
color = [0.8, 0.2, 0.2]
kd = 0.8
ks = 0.3

[materials.floor]
color = [0.9, 0.9, 0.9]
kd = 0.8

[[light]]
name = "lamp{TAIL_TOML}"
position = [-2, 4, -2]

[[object]]
name = "ball{TAIL_TOML}"
material = "paint{TAIL_TOML}"
sphere = {{ center = [0, 1, 0], radius = 1 }}

[[object]]
name = "floor"
material = "floor"
plane = {{ normal = [0, 1, 0], point = [0, 0, 0] }}
"#
    );
    let path = dir.join("hostile.toml");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

const BALL: &str = "20,12";
const SHADOW: &str = "30,22";

/// Panics if `text` holds a byte a terminal would obey or XML refuses:
/// below 0x20 other than a line break, DEL, or U+FFFE/U+FFFF.
fn assert_printable(what: &str, text: &str) {
    let bad: Vec<char> = text
        .chars()
        .filter(|&c| (c < ' ' && c != '\n') || ('\u{7f}'..='\u{9f}').contains(&c))
        .chain(text.chars().filter(|&c| c == '\u{fffe}' || c == '\u{ffff}'))
        .collect();
    assert!(bad.is_empty(), "{what}: raw {bad:?} in\n{text}");
}

/// Runs raystep, asserts it succeeded and returns its stdout.
fn run_ok(args: &[&str]) -> String {
    let output = raystep(args);
    assert!(output.status.success(), "{args:?}: {}", stderr(&output));
    stdout(&output)
}

#[test]
fn text_on_a_terminal_spells_control_characters_out() {
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    for (command, pixel, names) in [
        ("inspect", BALL, &["ball", "paint", "lamp"][..]),
        ("explain", BALL, &["ball", "paint", "lamp"][..]),
        ("inspect", SHADOW, &["lamp", "ball"][..]),
        ("explain", SHADOW, &["lamp", "ball"][..]),
    ] {
        let text = run_ok(&[command, &scene, "--pixel", pixel]);
        let what = format!("{command} {pixel}");
        assert_printable(&what, &text);
        for name in names {
            let spelt = format!("{name}{TAIL_SPELT}");
            assert!(text.contains(&spelt), "{what}: no {spelt} in\n{text}");
        }
    }
}

#[test]
fn an_error_naming_a_hostile_name_spells_it_out() {
    // An object whose material does not exist: the message names both.
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    let text = std::fs::read_to_string(&scene).unwrap();
    let broken = text.replace(
        "material = \"floor\"",
        &format!("material = \"nothing{TAIL_TOML}\""),
    );
    std::fs::write(&scene, broken).unwrap();
    let output = raystep(&["explain", &scene, "--pixel", BALL]);
    assert_eq!(output.status.code(), Some(1));
    let err = stderr(&output);
    assert!(err.starts_with("error: "), "{err}");
    assert_printable("the error", &err);
    assert!(err.contains(&format!("nothing{TAIL_SPELT}")), "{err}");
}

#[test]
fn the_diagram_is_well_formed_xml_with_the_names_spelt_out() {
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    for pixel in [BALL, SHADOW] {
        for plane in ["top", "side", "ray"] {
            let out = dir.path().join(format!("{plane}.svg"));
            run_ok(&[
                "diagram",
                &scene,
                "--pixel",
                pixel,
                "--plane",
                plane,
                "-o",
                out.to_str().unwrap(),
            ]);
            let svg = std::fs::read_to_string(&out).unwrap();
            let what = format!("diagram {pixel} {plane}");
            assert_printable(&what, &svg);
            let doc = roxmltree::Document::parse(&svg)
                .unwrap_or_else(|e| panic!("{what}: not well-formed XML: {e}"));
            let texts: String = doc
                .descendants()
                .filter_map(|n| n.text())
                .collect::<Vec<_>>()
                .join("\n");
            // The ball and the lamp are named in every figure.
            for name in ["ball", "lamp"] {
                let spelt = format!("{name}{TAIL_SPELT}");
                assert!(texts.contains(&spelt), "{what}: no {spelt} in\n{texts}");
            }
        }
    }
}

#[test]
fn dot_quotes_the_names_spelt_out() {
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    for pixel in [BALL, SHADOW] {
        let dot = run_ok(&["inspect", &scene, "--pixel", pixel, "--format", "dot"]);
        assert_printable(&format!("dot {pixel}"), &dot);
        // Inside a dot string a backslash is doubled: `\u{1b}` is written
        // `\\u{1b}`, which Graphviz reads back as `\u{1b}`.
        let doubled = TAIL_SPELT.replace('\\', "\\\\");
        for name in ["ball", "lamp"] {
            let spelt = format!("{name}{doubled}");
            assert!(dot.contains(&spelt), "dot {pixel}: no {spelt} in\n{dot}");
        }
    }
}

#[test]
fn json_keeps_the_exact_names() {
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    let json = run_ok(&["inspect", &scene, "--pixel", SHADOW, "--format", "json"]);
    // serde_json writes the C0 controls as \u001b-style escapes and the
    // rest (DEL, U+FFFE) raw, which JSON allows: either way the parsed
    // value is the name, character for character.
    let written = r#""light": "lamp\u001b[31m\u0007\b"#.to_owned() + "\u{7f}\\u0000\u{fffe}\"";
    assert!(json.contains(&written), "no {written} in\n{json}");
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    let light = &value["tree"]["lights"][0];
    assert_eq!(light["light"], format!("lamp{TAIL}").as_str(), "{light}");
    let blockers = &light["shadow"]["blockers"];
    assert_eq!(
        blockers[0]["object"],
        format!("ball{TAIL}").as_str(),
        "{blockers}"
    );
}

// Issue 27, item 8: the smaller ones.

/// `--set` on `explain` at the hostile scene's ball pixel.
fn explain_set(scene: &str, pixel: &str, assignment: &str) -> std::process::Output {
    raystep(&["explain", scene, "--pixel", pixel, "--set", assignment])
}

#[test]
fn a_set_error_quotes_a_bounded_excerpt_of_the_value() {
    // 100,000 characters in: the message is cut, as a scene error's is, to
    // MAX_MESSAGE_CHARS (400) with an ellipsis; with "error: " and a line
    // break, well under 1,000 bytes (the ellipsis is 3 bytes of UTF-8).
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    let long = "7".repeat(100_000);
    for value in [format!("x{long}"), format!("[{long}"), format!("{long}]")] {
        let output = explain_set(&scene, BALL, &format!("settings.ambient={value}"));
        assert_eq!(output.status.code(), Some(1));
        let err = stderr(&output);
        assert!(err.starts_with("error: --set settings.ambient="), "{err}");
        assert!(err.len() < 1_000, "{} bytes of stderr", err.len());
        assert!(err.contains('…'), "{err}");
    }
}

#[test]
fn a_set_array_without_its_closing_bracket_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    for (value, says) in [
        ("[0.1, 0.2, 0.3", "has no closing ]"),
        ("0.1, 0.2, 0.3]", "has no opening ["),
    ] {
        let output = explain_set(&scene, BALL, &format!("settings.ambient={value}"));
        assert_eq!(output.status.code(), Some(1), "{value}");
        let err = stderr(&output);
        assert!(err.contains(says), "{value}: {err}");
    }
    // Closed, or no brackets at all, as before.
    for value in ["[0.1, 0.2, 0.3]", "0.1, 0.2, 0.3", "0.1"] {
        let output = explain_set(&scene, BALL, &format!("settings.ambient={value}"));
        assert!(output.status.success(), "{value}: {}", stderr(&output));
    }
}

#[test]
fn set_reaches_a_material_named_with_a_dot_or_an_equals_sign_quoted() {
    // The hostile scene with its ball's material named "a.b" and the
    // floor's "x=y". Pixel (20, 12) hits the ball, whose colour is all its
    // reflection (weight k_s = 0.3): k_s = 0 leaves it black. Pixel
    // (20, 26) is lit floor: its colour is all diffuse, so halving k_d
    // (0.8 -> 0.4) halves it, 0.454 -> 0.227.
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    let paint = format!("\"paint{TAIL_TOML}\"");
    let text = std::fs::read_to_string(&scene)
        .unwrap()
        .replace(&paint, "\"a.b\"")
        .replace("materials.floor", "materials.\"x=y\"")
        .replace("material = \"floor\"", "material = \"x=y\"");
    std::fs::write(&scene, text).unwrap();
    for (pixel, assignment, changed) in [
        (
            BALL,
            r#"materials."a.b".ks=0"#,
            "colour (0.035, 0.035, 0.035) -> (0.000, 0.000, 0.000)",
        ),
        (
            "20,26",
            "materials.'x=y'.kd=0.4",
            "colour (0.454, 0.454, 0.454) -> (0.227, 0.227, 0.227)",
        ),
        (
            "20,26",
            r#"materials."x\u003dy".kd=0.4"#,
            "colour (0.454, 0.454, 0.454) -> (0.227, 0.227, 0.227)",
        ),
    ] {
        let output = explain_set(&scene, pixel, assignment);
        assert!(output.status.success(), "{assignment}: {}", stderr(&output));
        let text = stdout(&output);
        assert!(text.contains(changed), "{assignment}: {text}");
    }
    // A quote left open, or text after the closing quote, is told.
    for (assignment, says) in [
        (r#"materials."a.b.ks=0"#, "is not KEY=VALUE"),
        (r#"materials."a.b"c.ks=0"#, "is not a quoted TOML key"),
    ] {
        let output = explain_set(&scene, BALL, assignment);
        assert_eq!(output.status.code(), Some(1), "{assignment}");
        assert!(stderr(&output).contains(says), "{}", stderr(&output));
    }
}

#[test]
fn zoom_on_the_crossing_figure_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("f.svg");
    let output = raystep(&[
        "diagram",
        "scenes/polygons.toml",
        "--pixel",
        "40,54",
        "--plane",
        "crossing",
        "--zoom",
        "2",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert!(stderr(&output).contains("--zoom magnifies"));
    assert!(!out.exists());
}

#[test]
fn long_names_are_shortened_with_the_whole_name_as_a_tooltip() {
    // The hostile scene's names made 150-character ones: each label is cut
    // to 40 characters (39 and "…"), which at the largest label font (13,
    // 0.6 of it per character: 312 units) fits the 800-unit figure.
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    let long = "x".repeat(150);
    let text = std::fs::read_to_string(&scene)
        .unwrap()
        .replace(&format!("ball{TAIL_TOML}\""), &format!("ball {long}\""))
        .replace(&format!("lamp{TAIL_TOML}\""), &format!("lamp {long}\""))
        .replace("name = \"floor\"", &format!("name = \"floor {long}\""));
    std::fs::write(&scene, text).unwrap();
    let out = dir.path().join("f.svg");
    run_ok(&[
        "diagram",
        &scene,
        "--pixel",
        SHADOW,
        "-o",
        out.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&out).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    for node in doc.descendants().filter(|n| n.has_tag_name("text")) {
        let words = node.text().unwrap_or("");
        let x: f64 = node.attribute("x").unwrap().parse().unwrap();
        let chars = words.chars().count() as f64;
        if words.contains("xxx") {
            assert_eq!(chars, 40.0, "{words}");
            assert!(words.ends_with('…'), "{words}");
            assert!(x + chars * 13.0 * 0.6 <= 800.0, "{words} at x = {x}");
        }
    }
    let titles: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("title"))
        .filter_map(|n| n.text())
        .collect();
    for name in ["ball", "floor", "light lamp"] {
        let whole = format!("{name} {long}");
        assert!(titles.contains(&whole.as_str()), "no {whole} in {titles:?}");
    }
}

#[test]
fn the_debugger_draws_no_unprintable_character() {
    // The debugger opens on the centre pixel, (20, 15), which hits the
    // ball: its panes name the ball, its material and the lamp. ratatui
    // drops control characters; U+FFFE, not a control, must not reach a
    // cell either.
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    let mut app = raystep::tui::App::open(Some(scene.into()), true).unwrap();
    let terminal = crate::support::debugger::screen(&mut app, 200, 60);
    let buffer = terminal.backend().buffer();
    let mut shown = String::new();
    for y in 0..buffer.area.height {
        for x in 0..buffer.area.width {
            shown.push_str(buffer[(x, y)].symbol());
        }
        shown.push('\n');
    }
    assert_printable("the debugger's screen", &shown);
    assert!(shown.contains("ball"), "{shown}");
}

/// What Graphviz makes of `dot` text: `dot -Tsvg` run on it, which must
/// succeed without a word on stderr; the SVG's text, line by line.
fn graphviz_texts(dot_program: &Path, what: &str, dot: &str) -> String {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(dot_program)
        .arg("-Tsvg")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("dot starts");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(dot.as_bytes())
        .unwrap();
    let output = child.wait_with_output().unwrap();
    let (svg, err) = (stdout(&output), stderr(&output));
    assert!(output.status.success(), "{what}: dot failed: {err}\n{dot}");
    assert!(err.is_empty(), "{what}: dot warned: {err}\n{dot}");
    // Graphviz's SVG starts with its DTD's declaration.
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(&svg, options)
        .unwrap_or_else(|e| panic!("{what}: dot's SVG is not XML: {e}"));
    (doc.descendants().filter_map(|n| n.text()))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn graphviz_draws_our_dot_for_any_name_and_every_scene() {
    let Some(dot_program) = crate::support::program_or_skip("dot") else {
        return;
    };
    // The hostile scene's names again, each now also holding what dot's
    // strings and Graphviz's labels read specially: `&lt;` (an entity
    // Graphviz turns into `<` in any label, unless `&` is written
    // `&amp;`), `<`, `>`, a quote, a backslash (`\l` ends a line in dot),
    // a line break; and the floor named with 150 characters.
    let dir = tempfile::tempdir().unwrap();
    let scene = hostile_scene(dir.path());
    let special = r#"&lt;x<y>\"q\"\\l\n"#;
    let long = "f".repeat(150);
    let text = std::fs::read_to_string(&scene).unwrap();
    let text = text
        .replace(TAIL_TOML, &format!("{special}{TAIL_TOML}"))
        .replace("name = \"floor\"", &format!("name = \"{long}\""));
    std::fs::write(&scene, text).unwrap();
    // As Graphviz shows them: the characters themselves, the line break
    // and the controls spelt out (`crate::printable`).
    let shown = format!("&lt;x<y>\"q\"\\l\\u{{a}}{TAIL_SPELT}");
    for pixel in [BALL, SHADOW] {
        let dot = run_ok(&["inspect", &scene, "--pixel", pixel, "--format", "dot"]);
        let what = format!("dot {pixel}");
        let texts = graphviz_texts(&dot_program, &what, &dot);
        for name in ["ball", "lamp"] {
            let spelt = format!("{name}{shown}");
            assert!(texts.contains(&spelt), "{what}: no {spelt} in\n{texts}");
        }
    }
    // The floor is hit at SHADOW: its name cut to 99 characters and `…`
    // (MODEL §10: 100 at most in a label).
    let dot = run_ok(&["inspect", &scene, "--pixel", SHADOW, "--format", "dot"]);
    let texts = graphviz_texts(&dot_program, "the floor", &dot);
    assert!(
        texts.contains(&format!("hit {}… at", &long[..99])),
        "{texts}"
    );
    assert!(!texts.contains(&long[..100]), "{texts}");

    // Every scene of scenes/, at its centre pixel of a 16x12 image.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes = top_level_toml_scenes();
    scenes.push(root.join("scenes/cornell/cornell.toml"));
    assert!(scenes.len() >= 10, "{scenes:?}");
    for scene in scenes {
        let scene = scene.to_str().unwrap();
        let args = [
            "inspect", scene, "--size", "16x12", "--pixel", "8,6", "--format", "dot",
        ];
        let dot = run_ok(&args);
        let texts = graphviz_texts(&dot_program, scene, &dot);
        assert!(texts.contains("primary ray (depth 1)"), "{scene}: {texts}");
    }
}
