//! Ray logs (docs/RAYLOG.md): raystep's own `--format raylog` reads back to
//! the recorded tree bit for bit, on every pixel of every scene; every bad
//! log is refused with its LOG:line:column and what is wrong; a student's
//! NaN and infinities read as such.

use std::collections::HashMap;
use std::path::Path;

use raystep_engine::record::{RayTree, record_pixel};
use raystep_engine::scene::Scene;
use raystep_tools::raylog::{
    Hit, LoggedRay, MAX_LINE_BYTES, RayPath, RaylogError, RaylogReader, Step, raylog, rays_of,
};

use crate::support::{raystep, scene_at, stdout, top_level_toml_scenes};

/// Every ray of `log`, with its line, or the first error.
fn read(log: &str, scene: &Scene) -> Result<Vec<(usize, LoggedRay)>, RaylogError> {
    RaylogReader::new("LOG", log.as_bytes(), scene).collect()
}

fn same_bits(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits()
}

fn same_vector(a: Option<glam::DVec3>, b: glam::DVec3) -> bool {
    a.is_some_and(|a| (0..3).all(|i| same_bits(a[i], b[i])))
}

/// The rays of `tree` in the order MODEL §6 casts them: a ray, its shadow
/// rays in light order, then its reflected and its transmitted subtrees;
/// each with the tree's node and, for a shadow ray, its light's index.
fn expected_order(tree: &RayTree) -> Vec<(RayPath, usize, Option<usize>, f64)> {
    fn visit(
        tree: &RayTree,
        id: usize,
        path: RayPath,
        weight: f64,
        out: &mut Vec<(RayPath, usize, Option<usize>, f64)>,
    ) {
        let node = &tree.nodes[id];
        out.push((path.clone(), id, None, weight));
        for (i, light) in node.lights.iter().enumerate() {
            if light.shadow.is_some() {
                out.push((path.child(Step::Shadow(i)), id, Some(i), weight));
            }
        }
        for (child, step) in [
            (node.reflected, Step::Reflected),
            (node.transmitted, Step::Transmitted),
        ] {
            if let Some(child) = child {
                let w = weight * tree.nodes[child].weight;
                visit(tree, child, path.child(step), w, out);
            }
        }
    }
    let mut out = Vec::new();
    visit(tree, 0, RayPath::primary(), 1.0, &mut out);
    out
}

/// `read` holds exactly the rays of `tree`, in its order, every number
/// with the tree's bits.
fn check_against_tree(tree: &RayTree, read: &[(usize, LoggedRay)], context: &str) {
    let expected = expected_order(tree);
    let paths: Vec<String> = read.iter().map(|(_, r)| r.path.to_string()).collect();
    let wanted: Vec<String> = expected.iter().map(|(p, ..)| p.to_string()).collect();
    assert_eq!(paths, wanted, "{context}: the rays and their order");
    for ((_, ray), (_, id, light, weight)) in read.iter().zip(&expected) {
        let node = &tree.nodes[*id];
        let at = format!("{context} {}", ray.path);
        assert_eq!(ray.pixel, tree.pixel, "{at}");
        if let Some(light) = light {
            let record = &node.lights[*light];
            assert_eq!(record.light_index, *light, "{at}");
            let shadow = record.shadow.as_ref().unwrap();
            assert!(same_vector(ray.origin, shadow.origin), "{at}");
            assert!(same_vector(ray.dir, shadow.direction), "{at}");
            assert!(same_bits(ray.s.unwrap(), shadow.s), "{at}");
            assert_eq!(
                (ray.hit, ray.t, ray.color, ray.weight),
                (None, None, None, None)
            );
            continue;
        }
        assert!(same_vector(ray.origin, node.origin), "{at}");
        assert!(same_vector(ray.dir, node.direction), "{at}");
        assert!(same_vector(ray.color, node.color), "{at}");
        // Lecture scenes: the same weight on every channel.
        let logged = ray.weight.unwrap();
        assert!(
            [logged.x, logged.y, logged.z]
                .iter()
                .all(|&w| same_bits(w, *weight)),
            "{at}"
        );
        assert_eq!(ray.s, None, "{at}");
        match &node.hit {
            None => {
                assert_eq!(ray.hit, Some(Hit::Miss), "{at}");
                assert_eq!((ray.t, ray.point, ray.normal), (None, None, None), "{at}");
                assert_eq!((&ray.ambient, &ray.diffuse), (&None, &None), "{at}");
            }
            Some(hit) => {
                assert_eq!(ray.hit, Some(Hit::Object(hit.object_index)), "{at}");
                assert!(same_bits(ray.t.unwrap(), hit.t), "{at}");
                assert!(same_vector(ray.point, hit.point), "{at}");
                assert!(same_vector(ray.normal, hit.normal), "{at}");
                assert!(same_vector(ray.ambient, node.ambient), "{at}");
                let diffuse = ray.diffuse.as_ref().unwrap();
                let specular = ray.specular.as_ref().unwrap();
                assert_eq!(diffuse.len(), node.lights.len(), "{at}");
                assert_eq!(specular.len(), node.lights.len(), "{at}");
                for (i, light) in node.lights.iter().enumerate() {
                    assert!(same_vector(Some(diffuse[i]), light.diffuse), "{at}");
                    assert!(same_vector(Some(specular[i]), light.specular), "{at}");
                }
            }
        }
    }
}

#[test]
fn every_pixel_of_every_scene_reads_back_to_its_tree_bit_for_bit() {
    let scenes = top_level_toml_scenes();
    assert!(scenes.len() >= 9, "{scenes:?}");
    let (mut pixels, mut rays, mut shadow_rays) = (0, 0, 0);
    for path in &scenes {
        let scene = scene_at(path, Some((32, 24)));
        for y in 0..24 {
            for x in 0..32 {
                let tree = record_pixel(&scene, &scene.settings, x, y);
                let log = raylog(&tree);
                let read = read(&log, &scene)
                    .unwrap_or_else(|e| panic!("{} {x},{y}: {e}\n{log}", path.display()));
                check_against_tree(&tree, &read, &format!("{} {x},{y}", path.display()));
                // What the reader gives is what the writer started from.
                let ours: Vec<LoggedRay> = read.into_iter().map(|(_, r)| r).collect();
                assert_eq!(ours, rays_of(&tree));
                pixels += 1;
                rays += ours.len();
                shadow_rays += ours.iter().filter(|r| r.path.is_shadow()).count();
            }
        }
    }
    // The scenes do cast secondary and shadow rays: the check reached them.
    assert_eq!(pixels, scenes.len() * 32 * 24);
    assert!(
        shadow_rays > pixels && rays > pixels + shadow_rays,
        "{rays} {shadow_rays}"
    );
}

/// The first error of `log` read for scenes/seven-rays.toml (161x121, lights
/// `key` and `fill`, objects `glass ball`, `green ball`, `floor`).
fn error(log: &str) -> RaylogError {
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    read(log, &scene).expect_err("a bad log")
}

/// Asserts `error` is at `line`:`column` and says `words`.
fn assert_error(error: &RaylogError, line: usize, column: usize, words: &str) {
    assert_eq!((error.line, error.column), (line, column), "{error}");
    assert!(error.problem.contains(words), "{error}");
    assert!(
        error
            .to_string()
            .starts_with(&format!("LOG:{line}:{column}: ")),
        "{error}"
    );
}

const GOOD: &str = r#"{"pixel": [1, 2], "path": "P"}"#;

#[test]
fn a_line_that_is_not_json_is_named_with_its_column() {
    // The comma missing before "path": the `"` at column 28, counted in the
    // line as written (NaN is its 3 characters).
    let log = format!(
        "# a comment\n{}\n",
        r#"{"t": NaN, "pixel": [1, 2] "path": "P"}"#
    );
    assert_error(&error(&log), 2, 28, "not JSON: expected `,` or `}`");
    // A line that is JSON but no object.
    assert_error(&error("[1, 2]\n"), 1, 1, "not a JSON object");
    // NaN spelt otherwise is not JSON: `nan` starts at column 24, and
    // the reader, reading it as `null`, stops at its `a`, column 25. The
    // message says how to write it.
    let log = r#"{"pixel": [1, 2], "t": nan, "path": "P"}"#;
    assert_error(&error(log), 1, 25, "not JSON: expected ident");
    assert!(
        error(log)
            .problem
            .contains("write NaN, Infinity or -Infinity")
    );
    let log = r#"{"pixel": [1, 2], "t": -inf, "path": "P"}"#;
    assert!(
        error(log)
            .problem
            .contains("write NaN, Infinity or -Infinity")
    );
    // A number past f64 is refused, as serde_json would refuse it, at its last
    // digit (1e400 is at columns 37 to 41).
    let log = r#"{"pixel": [1, 2], "path": "P", "t": 1e400}"#;
    assert_error(&error(log), 1, 41, "not JSON: number out of range");
    // Bytes that are not UTF-8: the first bad one, after 2 characters.
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    let bytes: &[u8] = b"{\"\xff\": 1}\n";
    let e = RaylogReader::new("LOG", bytes, &scene)
        .next()
        .unwrap()
        .unwrap_err();
    assert_error(&e, 1, 3, "not UTF-8");
}

#[test]
fn a_line_over_one_megabyte_is_refused_without_reading_on() {
    // A blank line of exactly 1 MB is still a line; one byte more is not.
    let log = format!("{}\n{GOOD}\n", " ".repeat(MAX_LINE_BYTES));
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    assert_eq!(read(&log, &scene).unwrap().len(), 1);
    let log = format!("{GOOD}\n{}\n{GOOD}\n", "x".repeat(MAX_LINE_BYTES + 1));
    assert_error(&error(&log), 2, MAX_LINE_BYTES + 1, "over 1 MB");
}

#[test]
fn a_malformed_path_is_named() {
    // The path's value starts at column 27 of `{"pixel": [1, 2], "path": `.
    let line = |path: &str| format!(r#"{{"pixel": [1, 2], "path": "{path}"}}"#);
    assert_error(&error(&line("P/X")), 1, 27, r#""X" is not a step"#);
    assert_error(&error(&line("R")), 1, 27, "does not start with P");
    assert_error(
        &error(&line("P/S7")),
        1,
        27,
        "no light 7: the scene has 2 lights (S0 to S1)",
    );
    assert_error(&error(&line("P/S1/R")), 1, 27, "S1 is a shadow ray, a leaf");
    let no_path = r#"{"pixel": [1, 2]}"#;
    assert_error(&error(no_path), 1, 1, r#"no "path""#);
    let not_text = r#"{"pixel": [1, 2], "path": 3}"#;
    assert_error(&error(not_text), 1, 27, "path is not a string");
}

#[test]
fn a_pixel_outside_the_image_is_named() {
    // seven-rays is 161x121: x = 161 is one past the last column. The
    // pixel's `[` is at column 11.
    let log = format!("{GOOD}\n{}\n", r#"{"pixel": [161, 0], "path": "P"}"#);
    assert_error(
        &error(&log),
        2,
        11,
        "pixel [161, 0] is outside the image, which is 161x121",
    );
    // Columns count characters: `é` is two bytes but one column, so the
    // `[` is at column 24, not 25.
    let log = r#"{"note": "é", "pixel": [0, 121], "path": "P"}"#;
    assert_error(&error(log), 1, 24, "outside the image");
    let negative = r#"{"pixel": [-1, 0], "path": "P"}"#;
    assert_error(&error(negative), 1, 11, "pixel is not [x, y]");
    assert_error(&error(r#"{"path": "P"}"#), 1, 1, r#"no "pixel""#);
}

#[test]
fn a_vector_without_exactly_three_numbers_is_named() {
    // `dir`'s `[` is at column 39 of `{"pixel": [1, 2], "path": "P", "dir": `.
    let line = |dir: &str| format!(r#"{{"pixel": [1, 2], "path": "P", "dir": {dir}}}"#);
    assert_error(&error(&line("[0, 0]")), 1, 39, "dir has 2 numbers, not 3");
    assert_error(&error(&line("[0, 0, 1, 0]")), 1, 39, "dir has 4 numbers");
    assert_error(
        &error(&line(r#"[0, "a", 1]"#)),
        1,
        39,
        r#""a" is not a number"#,
    );
    assert_error(&error(&line("0.5")), 1, 39, "dir is not a vector");
    // One [r, g, b] per light: the scene has 2.
    let one_light = r#"{"pixel": [1, 2], "path": "P", "diffuse": [[0, 0, 0]]}"#;
    assert_error(
        &error(one_light),
        1,
        43,
        "diffuse holds 1 [r, g, b], but the scene has 2 lights",
    );
    let t = r#"{"pixel": [1, 2], "path": "P", "t": [1]}"#;
    assert_error(&error(t), 1, 37, "t is not a number");
}

#[test]
fn the_same_pixel_and_path_twice_is_named_with_its_first_line() {
    let other_pixel = r#"{"pixel": [2, 1], "path": "P"}"#;
    let log = format!("{GOOD}\n{other_pixel}\n\n{GOOD}\n");
    assert_error(
        &error(&log),
        4,
        27,
        "pixel [1, 2] path P is logged twice: first on line 1",
    );
}

#[test]
fn a_hit_on_an_object_that_does_not_exist_is_named() {
    // `hit`'s value is at column 39 of `{"pixel": [1, 2], "path": "P", "hit": `.
    let line = |hit: &str| format!(r#"{{"pixel": [1, 2], "path": "P", "hit": {hit}}}"#);
    assert_error(
        &error(&line("3")),
        1,
        39,
        "hit 3 names no object of the scene: it has 3 objects",
    );
    assert_error(
        &error(&line(r#""red ball""#)),
        1,
        39,
        r#"there is no object "red ball""#,
    );
    assert_error(&error(&line("-1")), 1, 39, "names no object");
    assert_error(&error(&line("true")), 1, 39, "hit is not an object's index");
    // By index, by name, or null for a miss.
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    let log = [
        line("2"),
        line(r#""green ball""#).replace("[1, 2]", "[1, 3]"),
        line("null").replace("[1, 2]", "[1, 4]"),
    ]
    .join("\n");
    let hits: Vec<_> = read(&log, &scene)
        .unwrap()
        .into_iter()
        .map(|(_, r)| r.hit)
        .collect();
    assert_eq!(
        hits,
        [Some(Hit::Object(2)), Some(Hit::Object(1)), Some(Hit::Miss)]
    );
}

#[test]
fn a_log_without_a_ray_is_refused() {
    assert_error(&error(""), 1, 1, "the log holds no ray");
    assert_error(
        &error("# only a comment\n\n   \n"),
        3,
        1,
        "the log holds no ray",
    );
}

#[test]
fn nan_and_infinities_read_as_such_and_unknown_keys_are_listed() {
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    let log = "  # Python's json.dumps writes NaN and Infinity bare\n\
        {\"pixel\": [1, 2], \"path\": \"P\", \"t\": NaN, \"note\": \"NaN\", \
         \"dir\": [Infinity, -Infinity, 0], \"depth\": 1}\n\
        {\"pixel\": [1, 2], \"path\": \"P/T/S1\", \"S\": -Infinity, \"weight\": 5e-324}\n";
    let mut reader = RaylogReader::new("LOG", log.as_bytes(), &scene);
    let rays: Vec<_> = reader.by_ref().collect::<Result<_, _>>().unwrap();
    assert_eq!(
        rays.iter().map(|(line, _)| *line).collect::<Vec<_>>(),
        [2, 3]
    );
    let (_, primary) = &rays[0];
    assert!(primary.t.unwrap().is_nan());
    let dir = primary.dir.unwrap();
    assert_eq!(dir.to_array(), [f64::INFINITY, f64::NEG_INFINITY, 0.0]);
    let (_, shadow) = &rays[1];
    assert_eq!(*shadow.path.steps, [Step::Transmitted, Step::Shadow(1)]);
    assert_eq!(shadow.s, Some(f64::NEG_INFINITY));
    // The smallest subnormal, exactly.
    assert_eq!(
        shadow.weight.map(|w| w.to_array().map(f64::to_bits)),
        Some([1; 3])
    );
    let unknown: Vec<_> = reader.unknown_keys().listed().collect();
    assert_eq!(unknown, ["depth", "note"]);
}

#[test]
fn inspect_prints_a_raylog_that_parses_line_by_line() {
    let output = raystep(&[
        "inspect",
        "scenes/seven-rays.toml",
        "--pixel",
        "80,60",
        "--format",
        "raylog",
    ]);
    assert!(output.status.success(), "{output:?}");
    let text = stdout(&output);
    let lines: Vec<&str> = text.lines().collect();
    // seven-rays 80,60 (MODEL's seven rays, and their shadow rays).
    assert!(lines.len() >= 7, "{text}");
    let mut paths = HashMap::new();
    for line in &lines {
        let value: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_eq!(value["pixel"], serde_json::json!([80, 60]), "{line}");
        *paths
            .entry(value["path"].as_str().unwrap().to_string())
            .or_insert(0) += 1;
    }
    assert_eq!(paths["P"], 1);
    assert!(paths.values().all(|&n| n == 1), "{paths:?}");
    // And it is the tree the library records.
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    assert_eq!(text, raylog(&record_pixel(&scene, &scene.settings, 80, 60)));
}

/// `text` with every number that has a fraction or an exponent rounded to
/// 4 decimals, so that a snapshot pins the format, not the last digits.
fn rounded(text: &str) -> String {
    let mut out = String::new();
    let mut chars = text.char_indices().peekable();
    let mut previous = ' ';
    while let Some((start, c)) = chars.next() {
        let starts_number = (c == '-' || c.is_ascii_digit()) && !previous.is_alphanumeric();
        if !starts_number {
            out.push(c);
            previous = c;
            continue;
        }
        let mut end = start + c.len_utf8();
        while let Some(&(i, d)) = chars.peek() {
            if d.is_ascii_digit() || matches!(d, '.' | 'e' | 'E' | '-' | '+') {
                end = i + 1;
                chars.next();
            } else {
                break;
            }
        }
        let token = &text[start..end];
        match token.parse::<f64>() {
            Ok(x) if token.contains(['.', 'e']) => out += &format!("{x:.4}"),
            _ => out += token,
        }
        previous = '0';
    }
    out
}

#[test]
fn the_raylog_of_seven_rays_80_60_is_pinned() {
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    let log = raylog(&record_pixel(&scene, &scene.settings, 80, 60));
    assert_eq!(
        rounded("[1.23456, -0.5, 1e-7, 3] \"P/S1\""),
        "[1.2346, -0.5000, 0.0000, 3] \"P/S1\""
    );
    snapshot!("seven_rays_80_60", rounded(&log));
}

/// Pieces of ray-log lines, right and wrong, for the reader's property test.
const PIECES: [&str; 32] = [
    "{",
    "}",
    "[",
    "]",
    ":",
    ",",
    " ",
    "\"",
    "\\",
    "\n",
    "#",
    "é",
    "\"pixel\"",
    "\"path\"",
    "\"dir\"",
    "\"hit\"",
    "\"diffuse\"",
    "\"S\"",
    "\"P\"",
    "\"P/R\"",
    "\"P/S1\"",
    "\"P/S",
    "NaN",
    "-Infinity",
    "Infinity",
    "nan",
    "null",
    "1",
    "-0.5e3",
    "160",
    "1e400",
    "\"floor\"",
];

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: 512, failure_persistence: None, ..Default::default()
    })]

    /// Whatever the log holds, the reader answers rays or an error that
    /// names a line and column within it: it never panics.
    #[test]
    fn the_reader_never_panics(
        pieces in proptest::collection::vec(0..PIECES.len(), 0..40),
        bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..40),
    ) {
        let scene = scene_at(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
            None,
        );
        let text: String = pieces.iter().map(|&i| PIECES[i]).collect();
        for log in [text.into_bytes(), bytes] {
            let lines = log.split(|&b| b == b'\n').count();
            if let Err(e) = RaylogReader::new("LOG", log.as_slice(), &scene)
                .collect::<Result<Vec<_>, _>>()
            {
                proptest::prop_assert!(e.line >= 1 && e.line <= lines, "{e}");
                proptest::prop_assert!(e.column >= 1, "{e}");
            }
        }
    }
}

#[test]
fn an_error_just_after_a_wide_character_names_its_column() {
    // Found by the_reader_never_panics when serde_json read the lines: its
    // column could fall inside a character of several bytes (`é` is two),
    // and the hint's look at the word there sliced the line inside it. A
    // string cut short after `é`: the line's 8 characters end inside the
    // string, so the column is just past them, 9. A stray `é`: column 11.
    for (log, column) in [("{\"a\": \"é", 9), ("{\"a\": \"é\" é}", 11), ("[é]", 2)] {
        let e = error(log);
        assert!(e.problem.starts_with("not JSON"), "{e}");
        assert_eq!((e.line, e.column), (1, column), "{log}: {e}");
    }
}

/// The code block of `language` in docs/RAYLOG.md's "Printing a log" section.
fn emitter(language: &str) -> String {
    let doc = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/RAYLOG.md"))
        .unwrap();
    let fence = format!("```{language}\n");
    let start = doc
        .find(&fence)
        .unwrap_or_else(|| panic!("no {language} block"))
        + fence.len();
    let end = start + doc[start..].find("```").unwrap();
    doc[start..end].to_string()
}

/// A 4x4 scene with one light and two objects, for the emitters' logs.
const EMITTED_SCENE: &str = r#"
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
[image]
width = 4
height = 4
[materials.mirror]
ks = 0.5
[[light]]
position = [0, 4, 4]
[[object]]
name = "ball"
material = "mirror"
sphere = { center = [0, 0, 0], radius = 1 }
[[object]]
name = "floor"
material = "mirror"
plane = { normal = [0, 1, 0], point = [0, -1, 0] }
"#;

/// Runs `program` with `args` in `dir`; its standard output.
fn run_in(dir: &Path, program: &str, args: &[&str]) -> String {
    let output = std::process::Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("{program} could not run: {e}"));
    assert!(
        output.status.success(),
        "{program} {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

/// What the emitters' drivers below log, as raystep reads it: pixel (1, 2);
/// the primary ray from the eye (0, 0, 5) along -z hits object 0 at t = 4;
/// its reflected ray goes back up +z and misses, with t = Infinity (as a
/// tracer's "nothing hit" often is) and, where the emitter logs a colour,
/// (NaN, 0, -Infinity).
fn check_emitted(language: &str, log: &str, with_color: bool) {
    let scene = crate::support::scene(EMITTED_SCENE);
    let rays = read(log, &scene).unwrap_or_else(|e| panic!("{language}: {e}\n{log}"));
    let paths: Vec<String> = rays.iter().map(|(_, r)| r.path.to_string()).collect();
    assert_eq!(paths, ["P", "P/R"], "{language}");
    let (primary, reflected) = (&rays[0].1, &rays[1].1);
    assert_eq!(primary.pixel, (1, 2));
    assert_eq!(primary.origin, Some(glam::DVec3::new(0.0, 0.0, 5.0)));
    assert_eq!(primary.dir, Some(glam::DVec3::new(0.0, 0.0, -1.0)));
    assert_eq!(primary.hit, Some(Hit::Object(0)));
    assert_eq!(primary.t, Some(4.0));
    assert_eq!(reflected.hit, Some(Hit::Miss));
    assert_eq!(reflected.t, Some(f64::INFINITY));
    if with_color {
        let color = reflected.color.expect("a colour");
        assert!(color.x.is_nan() && color.y == 0.0 && color.z == f64::NEG_INFINITY);
    }
}

#[test]
fn the_python_emitter_of_raylog_md_prints_what_raystep_reads() {
    let dir = tempfile::tempdir().unwrap();
    let program = emitter("python")
        + r#"
log_ray(1, 2, "P", origin=[0.0, 0.0, 5.0], dir=[0.0, 0.0, -1.0], hit=0, t=4.0)
log_ray(1, 2, "P/R", origin=[0.0, 0.0, 1.0], dir=[0.0, 0.0, 1.0], hit=None,
        t=float("inf"), color=[float("nan"), 0.0, float("-inf")])
"#;
    std::fs::write(dir.path().join("emit.py"), program).unwrap();
    let log = run_in(dir.path(), "python3", &["emit.py"]);
    check_emitted("python", &log, true);
}

#[test]
fn the_cpp_emitter_of_raylog_md_prints_what_raystep_reads() {
    let dir = tempfile::tempdir().unwrap();
    let program = emitter("cpp")
        + r#"
int main() {
    const double eye[3] = {0, 0, 5}, down[3] = {0, 0, -1};
    const double hit_point[3] = {0, 0, 1}, up[3] = {0, 0, 1};
    log_ray(1, 2, "P", eye, down, 0, 4.0);
    log_ray(1, 2, "P/R", hit_point, up, -1, INFINITY);
}
"#;
    std::fs::write(dir.path().join("emit.cpp"), program).unwrap();
    run_in(dir.path(), "g++", &["-std=c++17", "-o", "emit", "emit.cpp"]);
    let log = run_in(dir.path(), "./emit", &[]);
    check_emitted("c++", &log, false);
}

#[test]
fn the_javascript_emitter_of_raylog_md_prints_what_raystep_reads() {
    let dir = tempfile::tempdir().unwrap();
    let program = emitter("js")
        + r#"
logRay(1, 2, "P", { origin: [0, 0, 5], dir: [0, 0, -1], hit: 0, t: 4 });
logRay(1, 2, "P/R", { origin: [0, 0, 1], dir: [0, 0, 1], hit: null, t: Infinity, color: [NaN, 0, -Infinity] });
"#;
    std::fs::write(dir.path().join("emit.js"), program).unwrap();
    let log = run_in(dir.path(), "node", &["emit.js"]);
    check_emitted("javascript", &log, true);
}

#[test]
fn after_the_log_the_reader_tells_every_ray_it_held_and_no_other() {
    // The seven rays of seven-rays.toml's pixel (80, 60) with their shadow
    // rays, read to the end: each was logged; a ray of another pixel, a
    // child past max_depth (3: P/R/R/R) and a shadow ray to a light the
    // scene lacks were not.
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    let tree = record_pixel(&scene, &scene.settings, 80, 60);
    let log = raylog(&tree);
    let mut reader = RaylogReader::new("LOG", log.as_bytes(), &scene);
    assert_eq!(
        reader.by_ref().filter(|r| r.is_ok()).count(),
        log.lines().count()
    );
    let rays = rays_of(&tree);
    assert!(rays.len() >= 7);
    for ray in &rays {
        assert!(reader.was_logged((80, 60), &ray.path), "{}", ray.path);
        assert!(!reader.was_logged((80, 61), &ray.path), "{}", ray.path);
    }
    let path = RayPath::of;
    let r = Step::Reflected;
    assert!(!reader.was_logged((80, 60), &path(vec![r, r, r])));
    assert!(!reader.was_logged((80, 60), &path(vec![Step::Shadow(2)])));
}
