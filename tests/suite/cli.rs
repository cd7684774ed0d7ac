//! Bad input through the command line: a clear message, a non-zero exit,
//! never a panic, and nothing already written damaged.

use crate::support::{raystep, stderr};

use std::path::{Path, PathBuf};

/// A scene file in a fresh temporary directory.
fn scene_file(dir: &tempfile::TempDir, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    path
}

const GOOD: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[image]\nwidth = 8\nheight = 6\n\
[materials.m]\nkd = 1\n[[light]]\nposition = [0, 5, 5]\n[[object]]\nmaterial = \"m\"\nsphere = { center = [0, 0, 0], radius = 1 }\n";

/// Runs `render` on a scene text and returns the failure's stderr, checking the exit code.
fn render_fails(name: &str, text: &str) -> String {
    render_fails_bytes(name, text.as_bytes())
}

/// `render_fails` for a file that need not be UTF-8.
fn render_fails_bytes(name: &str, text: &[u8]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(&dir, name, text);
    let out = dir.path().join("out.png");
    let output = raystep(&[
        "render",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let message = stderr(&output);
    assert_eq!(
        output.status.code(),
        Some(1),
        "exit code, stderr: {message}"
    );
    assert!(!message.contains("panicked"), "{message}");
    assert!(!out.exists(), "no output written on failure");
    message
}

#[test]
fn good_scene_renders() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(&dir, "good.toml", GOOD);
    let out = dir.path().join("out.png");
    let output = raystep(&[
        "render",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let image = image::open(&out).unwrap();
    assert_eq!((image.width(), image.height()), (8, 6));
}

#[test]
fn syntax_error_names_file_line_and_column() {
    let message = render_fails("bad.toml", "[camera]\nfov = abc\n");
    assert!(message.contains("bad.toml:2:7:"), "{message}");
    assert!(
        message.contains("2 | fov = abc"),
        "shows the offending line: {message}"
    );
}

#[test]
fn misspelt_key_is_an_error() {
    let message = render_fails("typo.toml", &GOOD.replace("radius", "radious"));
    assert!(
        message.contains("radious") && message.contains("typo.toml:13:"),
        "{message}"
    );
}

#[test]
fn unknown_material_is_named() {
    let message = render_fails(
        "mat.toml",
        &GOOD.replace("material = \"m\"", "material = \"glas\""),
    );
    assert!(
        message.contains("unknown material `glas`") && message.contains("mat.toml:12:12"),
        "{message}"
    );
}

#[test]
fn degenerate_geometry_is_refused() {
    let cases = [
        (
            "radius = 1 }",
            "radius = -1 }",
            "sphere.radius` must be between 0.001 and 10000",
        ),
        (
            "sphere = { center = [0, 0, 0], radius = 1 }",
            "polygon = { vertices = [[0, 0, 0], [1, 0, 0]] }",
            "at least 3 vertices",
        ),
        (
            "sphere = { center = [0, 0, 0], radius = 1 }",
            "polygon = { vertices = [[0, 0, 0], [1, 0, 0], [2, 0, 0]] }",
            "collinear",
        ),
        (
            "sphere = { center = [0, 0, 0], radius = 1 }",
            "polygon = { vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 1]] }",
            "not planar",
        ),
        (
            "sphere = { center = [0, 0, 0], radius = 1 }",
            "plane = { normal = [0, 0, 0], point = [0, 0, 0] }",
            "normal must be non-zero",
        ),
        (
            "sphere = { center = [0, 0, 0], radius = 1 }",
            "cone = { base = [0, 0, 0], base_radius = 1, apex = [0, 0, 0], apex_radius = 0 }",
            "ends coincide",
        ),
    ];
    for (from, to, expected) in cases {
        let message = render_fails("geometry.toml", &GOOD.replace(from, to));
        assert!(
            message.contains(expected) && message.contains("geometry.toml:13:"),
            "{expected}: {message}"
        );
    }
}

#[test]
fn non_finite_numbers_are_refused() {
    let message = render_fails("nan.toml", &GOOD.replace("radius = 1", "radius = nan"));
    assert!(
        message.contains("finite") && message.contains("nan.toml:13:"),
        "{message}"
    );
    let message = render_fails(
        "inf.toml",
        &GOOD.replace("eye = [0, 0, 5]", "eye = [0, inf, 5]"),
    );
    assert!(
        message.contains("finite") && message.contains("inf.toml:2:"),
        "{message}"
    );
}

#[test]
fn field_of_view_must_lie_strictly_between_0_and_180() {
    for fov in ["0", "180", "-5"] {
        let message = render_fails(
            "fov.toml",
            &GOOD.replace(
                "look_at = [0, 0, 0]\n",
                &format!("look_at = [0, 0, 0]\nfov = {fov}\n"),
            ),
        );
        assert!(
            message.contains("fov must be between 0 and 180"),
            "{message}"
        );
    }
}

#[test]
fn empty_and_absurd_image_sizes_are_refused() {
    let message = render_fails("zero.toml", &GOOD.replace("width = 8", "width = 0"));
    assert!(
        message.contains("empty") && message.contains("zero.toml:"),
        "{message}"
    );
    let message = render_fails("huge.toml", &GOOD.replace("width = 8", "width = 100000"));
    assert!(message.contains("at most 16384"), "{message}");
    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(&dir, "good.toml", GOOD);
    let out = dir.path().join("out.png");
    let output = raystep(&[
        "render",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--size",
        "0x10",
    ]);
    assert_eq!(output.status.code(), Some(2), "clap rejects the argument");
    assert!(stderr(&output).contains("empty"), "{}", stderr(&output));
}

#[test]
fn nff_with_missing_or_extra_numbers() {
    let view = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 6\n";
    let message = render_fails("short.nff", &format!("{view}s 0 0 0\n"));
    assert!(
        message.contains("short.nff:8:") && message.contains("expected a number"),
        "{message}"
    );
    let message = render_fails("long.nff", &format!("{view}s 0 0 0 1 7\n"));
    assert!(
        message.contains("long.nff:8:11") && message.contains("unexpected number"),
        "{message}"
    );
}

#[test]
fn unreadable_input_and_unwritable_output() {
    let output = raystep(&["render", "/no/such/scene.toml", "-o", "/tmp/x.png"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("cannot read /no/such/scene.toml"),
        "{}",
        stderr(&output)
    );

    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(&dir, "good.toml", GOOD);
    let output = raystep(&[
        "render",
        path.to_str().unwrap(),
        "-o",
        "/no/such/dir/out.png",
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("cannot write /no/such/dir/out.png"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn failed_render_leaves_an_existing_file_intact() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    std::fs::write(&out, b"previous contents").unwrap();
    let bad = scene_file(&dir, "bad.toml", "[camera]\n");
    let output = raystep(&["render", bad.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    assert_eq!(std::fs::read(&out).unwrap(), b"previous contents");
    // No temporary file is left behind either.
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn pixel_outside_the_image_and_malformed_pixel() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml");
    let scene = scene.to_str().unwrap();
    let output = raystep(&["inspect", scene, "--pixel", "161,0"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("pixel (161, 0) is outside the 161x121 image"),
        "{}",
        stderr(&output)
    );
    for bad in ["12", "a,b", "-1,3", "1,2,3"] {
        let output = raystep(&["explain", scene, &format!("--pixel={bad}")]);
        assert_eq!(output.status.code(), Some(2), "{bad}");
        assert!(
            stderr(&output).contains("is not a pixel"),
            "{bad}: {}",
            stderr(&output)
        );
    }
    // Written as a separate argument, a negative coordinate is the pixel's
    // value (not taken for an option) and the message says what is wrong.
    let output = raystep(&["explain", scene, "--pixel", "-1,2"]);
    assert_eq!(output.status.code(), Some(2));
    assert!(
        stderr(&output)
            .contains("`-1,2` is not a pixel: -1 is negative, and pixels are counted from 0"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn stats_are_one_json_object() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let output = raystep(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--stats",
        "--size",
        "16x12",
    ]);
    assert!(output.status.success());
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    // 16 x 12 = 192 primary rays, one per pixel.
    assert_eq!(json["primary"], 192);
    for key in [
        "primary_hit",
        "reflected",
        "transmitted",
        "shadow",
        "shadow_blocked",
        "shadow_opaque",
        "closest_nodes",
        "closest_primitives",
        "shadow_nodes",
        "shadow_primitives",
        "prepare_seconds",
        "trace_seconds",
    ] {
        assert!(json.get(key).is_some(), "{key} missing");
    }
}

#[test]
fn timings_report_a_plain_render_without_counts() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let (scene, out_path) = (scene.to_str().unwrap(), out.to_str().unwrap());
    let render = |report: &[&str]| {
        let mut args = vec!["render", scene, "-o", out_path, "--size", "16x12"];
        args.extend(report);
        raystep(&args)
    };
    let output = render(&["--timings"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["width"], 16);
    assert_eq!(json["height"], 12);
    assert!(json["trace_seconds"].as_f64().unwrap() > 0.0, "{json}");
    // No counters ran, so none are reported.
    assert!(
        json.get("primary").is_none() && json.get("closest_nodes").is_none(),
        "{json}"
    );
    // The same image as a render that counts.
    let plain = std::fs::read(&out).unwrap();
    assert!(render(&["--stats"]).status.success());
    assert_eq!(std::fs::read(&out).unwrap(), plain);
    // Asking for both is a usage error.
    assert_eq!(render(&["--stats", "--timings"]).status.code(), Some(2));
}

/// Asserts that a failure's whole output stays small and names `place`.
fn assert_bounded(message: &str, place: &str) {
    assert!(message.len() < 2000, "{} bytes of stderr", message.len());
    assert!(message.contains(place), "names {place}: {message}");
}

#[test]
fn an_error_on_a_line_of_megabytes_prints_a_bounded_excerpt() {
    const HEAD: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n";
    let long = "x".repeat(3_000_000);
    // TOML's own syntax error: the value after "fov = " starts at column 7.
    let message = render_fails("a.toml", &format!("{HEAD}fov = 3 {long}\n"));
    assert_bounded(&message, "a.toml:4:7:");
    assert!(message.contains("4 | fov = 3 xxx"), "{message}");
    // A type error whose message quotes the 3 MB string itself.
    let message = render_fails("b.toml", &format!("{HEAD}fov = \"{long}\"\n"));
    assert_bounded(&message, "b.toml:4:7: invalid type: string");
    assert!(message.contains("xxx\", expected f64"), "{message}");
    // NFF: the radius "xxx..." is line 8's fifth word, after "s 0 0 0 " (column 9).
    let nff = format!(
        "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 6\ns 0 0 0 {long}\n"
    );
    let message = render_fails("c.nff", &nff);
    assert_bounded(
        &message,
        "c.nff:8:9: expected a number for the sphere's radius",
    );
}

#[test]
fn invalid_utf8_names_line_and_column() {
    // Byte 0xFF after "look_at = [0, " (14 characters): line 3, column 15.
    let toml = b"[camera]\neye = [0, 0, 5]\nlook_at = [0, \xff, 0]\n";
    let message = render_fails_bytes("u.toml", toml);
    assert_bounded(&message, "u.toml:3:15: invalid UTF-8 (byte 0xFF)");
    assert!(
        message.contains("3 | look_at = [0, \u{fffd}, 0]"),
        "{message}"
    );
    // In NFF after "at 0 " (5 characters): line 3, column 6.
    let message = render_fails_bytes("u.nff", b"v\nfrom 0 0 5\nat 0 \xff 0\n");
    assert_bounded(&message, "u.nff:3:6: invalid UTF-8 (byte 0xFF)");
}

#[test]
fn arrays_nested_100000_deep_are_refused_with_line_and_column() {
    // The TOML reader allows 80 levels: the 81st `[`, after "a = " and 80
    // others, is at column 4 + 81 = 85 of line 4.
    let deep = format!(
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\na = {}\n",
        "[".repeat(100_000)
    );
    let message = render_fails("deep.toml", &deep);
    assert_bounded(&message, "deep.toml:4:85:");
    // Inline tables: "a = " then "{ b = " (6 characters) per level; the
    // 81st `{` is at column 4 + 80 * 6 + 1 = 485.
    let head = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[materials.m]\n";
    let message = render_fails(
        "inline.toml",
        &format!("{head}a = {}\n", "{ b = ".repeat(100_000)),
    );
    assert_bounded(&message, "inline.toml:5:485:");
    // Inside an object, read as its own section: after "sphere = " the
    // 81st `[` is at column 9 + 81 = 90 of line 7.
    let object = format!(
        "[[object]]\nmaterial = \"m\"\nsphere = {}\n",
        "[".repeat(100_000)
    );
    let message = render_fails("object.toml", &format!("{head}{object}"));
    assert_bounded(&message, "object.toml:7:90:");
    // A dotted key of a million parts in a header on line 5, from column 2.
    let key = vec!["a"; 1_000_000].join(".");
    let message = render_fails("key.toml", &format!("{head}[{key}]\n"));
    assert_bounded(&message, "key.toml:5:2: a dotted key of 81 or more parts");
}

/// serde_json prints NaN as `null`. The scene puts the light exactly at the
/// hit point of the only pixel's ray, where L = normalize(0) used to be NaN
/// and was printed as `null`: now a number stands wherever a number belongs.
#[test]
fn json_output_never_hides_a_non_finite_number() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(
        &dir,
        "lit.toml",
        "[camera]\neye = [0, 5, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\n\
         [image]\nwidth = 1\nheight = 1\n[materials.m]\nkd = 1\n\
         [[light]]\nposition = [0, 0, 0]\n\
         [[object]]\nmaterial = \"m\"\nplane = { normal = [0, 1, 0], point = [0, 0, 0] }\n",
    );
    let output = raystep(&[
        "inspect",
        path.to_str().unwrap(),
        "--pixel",
        "0,0",
        "--format",
        "json",
    ]);
    // The light sits exactly at the hit point: MODEL §4 says it adds
    // nothing and is recorded with N·L = 0 and `at_point`, so the JSON has
    // numbers only (a NaN would be refused by `check_finite`, unit-tested
    // in crates/engine/src/record/finite.rs, never written as null).
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert!(json["color"].as_array().unwrap().iter().all(|c| c.is_f64()));
    let light = &json["tree"]["lights"][0];
    assert_eq!(light["n_dot_l"].as_f64(), Some(0.0));
    assert_eq!(light["at_point"].as_bool(), Some(true));
}

/// `debug --compare` reads the student's image before anything else: a bad
/// one is the error reported, exit 1, even without a terminal (stdin here
/// is not a TTY), and nothing is written to stdout (no escape codes).
#[test]
fn debug_compare_reports_a_bad_image_before_the_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_file(&dir, "scene.toml", GOOD);
    let scene = scene.to_str().unwrap();
    let missing = dir.path().join("missing.png");
    let missing = missing.to_str().unwrap();
    let not_png = scene_file(&dir, "notes.png", "not an image");
    let not_png = not_png.to_str().unwrap();
    for (args, want) in [
        (vec!["debug", scene, "--compare", missing], "cannot read"),
        (vec![scene, "--compare", missing], "cannot read"),
        (
            vec!["debug", scene, "--compare", not_png],
            "is not a PNG image",
        ),
    ] {
        let output = raystep(&args);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(message.contains(want), "{args:?}: {message}");
        assert!(!message.contains("needs a terminal"), "{message}");
        assert!(output.stdout.is_empty(), "{args:?} wrote to stdout");
    }
}

/// A good image gets as far as the terminal check.
#[test]
fn debug_compare_with_a_good_image_still_needs_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_file(&dir, "scene.toml", GOOD);
    let png = dir.path().join("yours.png");
    image::RgbImage::new(8, 6).save(&png).unwrap();
    let output = raystep(&[
        "debug",
        scene.to_str().unwrap(),
        "--compare",
        png.to_str().unwrap(),
    ]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("the debugger needs a terminal"),
        "{message}"
    );
    assert!(output.stdout.is_empty());
}
