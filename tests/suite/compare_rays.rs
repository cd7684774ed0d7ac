//! `compare --rays` (docs/RAYLOG.md): raystep's own log matches itself on
//! every pixel of every scene, shown or counted; the command's text, its
//! JSON (a contract, pinned), the image beside the log, and every bad
//! command line or log refused with the right status.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use raystep_engine::record::record_pixel;
use raystep_engine::scene::{Scene, Settings};
use raystep_model::mistakes::{Mistake, Mistakes};
use raystep_tools::divergence::{PIXELS_SHOWN, Tolerance, compare_log};
use raystep_tools::raylog::{RaylogReader, raylog};

use crate::support::{raystep, scene_at, stderr, stdout, top_level_toml_scenes};

const GLASS: &str = "scenes/glass.toml";

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// raystep's own log of the pixels, with `mistakes` switched on.
fn log_of(scene: &Scene, mistakes: &[Mistake], pixels: &[(u32, u32)]) -> String {
    let settings = Settings {
        mistakes: mistakes.iter().copied().collect::<Mistakes>(),
        ..scene.settings
    };
    pixels
        .iter()
        .map(|&(x, y)| raylog(&record_pixel(scene, &settings, x, y)))
        .collect()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let file = dir.join(name);
    std::fs::write(&file, text).unwrap();
    file
}

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn json(output: &Output) -> serde_json::Value {
    serde_json::from_str(&stdout(output)).expect("compare --format json prints JSON")
}

#[test]
fn every_pixel_of_every_scene_matches_itself_shown_or_counted() {
    // One log per scene holding all 768 pixels at 32x24: the first 64 are
    // compared in full, the other 704 ray by ray as they stream past. Both
    // ways must find raystep's own rays equal to raystep's.
    let scenes = top_level_toml_scenes();
    assert!(scenes.len() >= 9, "{scenes:?}");
    let pixels: Vec<(u32, u32)> = (0..24).flat_map(|y| (0..32).map(move |x| (x, y))).collect();
    for file in &scenes {
        let scene = scene_at(file, Some((32, 24)));
        let log = log_of(&scene, &[], &pixels);
        let found = compare_log(
            &scene,
            RaylogReader::new("LOG", log.as_bytes(), &scene),
            Tolerance::default(),
        )
        .unwrap();
        assert_eq!(found.pixel_count, 768, "{}", file.display());
        assert_eq!(found.matching, 768, "{}", file.display());
        assert_eq!(found.pixels.len(), PIXELS_SHOWN);
        assert_eq!(found.rays_read, log.lines().count());
        for pixel in &found.pixels {
            assert!(pixel.first_divergence.is_none() && pixel.mistakes.is_empty());
            assert!(pixel.only_yours.is_empty() && pixel.only_ours.is_empty());
        }
    }
}

#[test]
fn a_counted_pixel_that_differs_is_counted_so() {
    // 70 pixels: 64 shown, 6 counted; the 70th is logged under no-ambient,
    // whose ambient term differs on glass.toml's floor (I_a 0.1, k_a > 0).
    let scene = scene_at(&root().join(GLASS), Some((32, 24)));
    let pixels: Vec<(u32, u32)> = (0..70).map(|i| (i % 32, 20 + i / 32)).collect();
    let mut log = log_of(&scene, &[], &pixels[..69]);
    log += &log_of(&scene, &[Mistake::NoAmbient], &pixels[69..]);
    let found = compare_log(
        &scene,
        RaylogReader::new("LOG", log.as_bytes(), &scene),
        Tolerance::default(),
    )
    .unwrap();
    assert_eq!((found.pixel_count, found.matching), (70, 69));
    // A looser colour tolerance than the ambient term (0.1 * k_a * O_d is
    // far below 1) lets it pass.
    let loose = compare_log(
        &scene,
        RaylogReader::new("LOG", log.as_bytes(), &scene),
        Tolerance::parse("1e-4,1").unwrap(),
    )
    .unwrap();
    assert_eq!(loose.matching, 70);
}

#[test]
fn the_text_names_the_first_divergence_its_kind_and_the_catalogue_mistake() {
    // glass.toml's pixel (72, 45) looks into the glass ball. Under
    // eta-inverted, eta = ior = 1.5 entering instead of 1/1.5, so the first
    // number that differs is the transmitted direction P/T's dir, refracted
    // with 1/eta: the kind is eta_swapped.
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_at(&root().join(GLASS), None);
    // Two pixels through the ball: a name needs the mistake's tree to be
    // the log at every logged pixel and to change the colour at two.
    let log = write(
        dir.path(),
        "eta.jsonl",
        &log_of(&scene, &[Mistake::EtaInverted], &[(72, 45), (73, 45)]),
    );
    let output = raystep(&["compare", GLASS, "--rays", path(&log)]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = stdout(&output);
    for words in [
        "Pixel (72, 45): differs",
        "First divergence: P/T dir",
        "eta_swapped: yours is refracted with η = 1.5, ours with η = 0.6667 (entering, ior 1.5)",
        "η = 1 / ior = 1 / 1.5 = 0.666667 (entering)",
        "Your rays are raystep's under the catalogue's mistake: eta-inverted.",
        "2 pixels logged",
    ] {
        assert!(text.contains(words), "{words:?} in\n{text}");
    }
    // One pixel alone names nothing: the mistake is consistent with it,
    // and another pixel would tell (issue 39).
    let log = write(
        dir.path(),
        "one.jsonl",
        &log_of(&scene, &[Mistake::EtaInverted], &[(72, 45)]),
    );
    let text = stdout(&raystep(&["compare", GLASS, "--rays", path(&log)]));
    assert!(
        !text.contains("Your rays are raystep's under the catalogue's mistake"),
        "{text}"
    );
    assert!(
        text.contains("Consistent with eta-inverted here; log pixel "),
        "{text}"
    );
}

#[test]
fn the_json_is_pinned() {
    // Two pixels: (72, 45) under eta-inverted as above, and (10, 10), the
    // background, as raystep logs it (it matches). Reviewed against
    // docs/RAYLOG.md's keys: pixels[] with pixel, matches,
    // first_divergence {path, field, yours, ours, kind, words, meaning},
    // later_differences, only_yours, only_ours, unpaired, mistakes[{name}],
    // consistent_with[{name, tell}], colour_agrees, notes, rays_yours,
    // rays_ours; then pixel_count, matching_pixels, colour_agreeing_pixels,
    // rays_read, tolerance, traced_at and unknown_keys. One pixel where
    // eta-inverted acts names nothing: it is consistent with it, and pixel
    // 72,44 (where eta-inverted's colour differs from ours) would tell.
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_at(&root().join(GLASS), None);
    let mut text = log_of(&scene, &[Mistake::EtaInverted], &[(72, 45)]);
    text += &log_of(&scene, &[], &[(10, 10)]);
    text = text.replacen("\"path\": \"P\"", "\"path\": \"P\", \"student\": 1", 1);
    let log = write(dir.path(), "two.jsonl", &text);
    let output = raystep(&["compare", GLASS, "--rays", path(&log), "--format", "json"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let value = json(&output);
    assert_eq!(value["unknown_keys"], serde_json::json!(["student"]));
    json_snapshot!("two_pixels", rounded(&value));
}

/// Every float to 6 decimals, so the snapshot holds across platforms.
fn rounded(value: &serde_json::Value) -> serde_json::Value {
    use serde_json::Value;
    match value {
        Value::Number(n) if n.is_f64() => {
            let x = n.as_f64().unwrap();
            serde_json::json!((x * 1e6).round() / 1e6)
        }
        Value::Array(items) => Value::Array(items.iter().map(rounded).collect()),
        Value::Object(map) => {
            Value::Object(map.iter().map(|(k, v)| (k.clone(), rounded(v))).collect())
        }
        other => other.clone(),
    }
}

#[test]
fn with_an_image_beside_the_log_both_parts_are_reported() {
    // The image is raystep's own render under gamma: it differs everywhere
    // (a mistake of the bytes), while the log, rays only, matches: the text
    // says the difference lies past tracing, and the JSON holds the image's
    // report under "image".
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("gamma.png");
    let render = raystep(&[
        "render",
        GLASS,
        "-o",
        path(&image),
        "--size",
        "40x30",
        "--mistake",
        "gamma",
    ]);
    assert!(render.status.success(), "{}", stderr(&render));
    let scene = scene_at(&root().join(GLASS), Some((40, 30)));
    let log = write(
        dir.path(),
        "ok.jsonl",
        &log_of(&scene, &[], &[(20, 15), (5, 25)]),
    );
    let output = raystep(&["compare", GLASS, path(&image), "--rays", path(&log)]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("gamma"), "{text}");
    assert!(
        text.contains("Your rays match ours but your image does not"),
        "{text}"
    );
    let output = raystep(&[
        "compare",
        GLASS,
        path(&image),
        "--rays",
        path(&log),
        "--format",
        "json",
    ]);
    let value = json(&output);
    assert_eq!(value["matching_pixels"], 2);
    assert_eq!(value["image"]["matches"], false);
    assert_eq!(value["image"]["mistakes"][0]["name"], "gamma");
}

#[test]
fn a_log_reads_from_stdin_with_a_dash() {
    let scene = scene_at(&root().join(GLASS), None);
    let mut child = Command::new(env!("CARGO_BIN_EXE_raystep"))
        .args(["compare", GLASS, "--rays", "-"])
        .current_dir(root())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let log = log_of(&scene, &[], &[(80, 60)]);
    child
        .stdin
        .take()
        .unwrap()
        .write_all(log.as_bytes())
        .unwrap();
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(stdout(&output).contains("Pixel (80, 60): matches ours"));
}

#[test]
fn bad_logs_and_bad_command_lines_are_refused_with_their_status() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_at(&root().join(GLASS), None);
    let good = log_of(&scene, &[], &[(80, 60)]);
    let good = write(dir.path(), "good.jsonl", &good);
    // A bad log: exit 1, LOG:line:column and what is wrong, nothing on stdout.
    let bad = write(
        dir.path(),
        "bad.jsonl",
        "# a comment\n{\"pixel\": [1, 2], \"path\": \"P\"}\n{\"pixel\": [1, 2], \"path\": \"P/X\"}\n",
    );
    let output = raystep(&["compare", GLASS, "--rays", path(&bad)]);
    assert_eq!(output.status.code(), Some(1));
    let said = stderr(&output);
    assert!(said.contains("bad.jsonl:3:"), "{said}");
    assert!(said.contains("\"X\" is not a step"), "{said}");
    assert_eq!(stdout(&output), "");
    // A pixel of the scene's 160x120 is outside a --size of 40x30.
    let output = raystep(&["compare", GLASS, "--rays", path(&good), "--size", "40x30"]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("good.jsonl:1:"),
        "{}",
        stderr(&output)
    );
    // A log that does not exist.
    let output = raystep(&["compare", GLASS, "--rays", "no-such.jsonl"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("no-such.jsonl"),
        "{}",
        stderr(&output)
    );
    // Bad command lines: exit 2.
    for args in [
        vec!["compare", GLASS],
        vec!["compare", GLASS, "--rays", path(&good), "--tolerance", "-1"],
        vec![
            "compare",
            GLASS,
            "--rays",
            path(&good),
            "--tolerance",
            "1,2,3",
        ],
        vec!["compare", GLASS, "x.png", "--size", "40x30"],
        vec!["compare", GLASS, "x.png", "--tolerance", "1e-3"],
    ] {
        let output = raystep(&args);
        assert_eq!(
            output.status.code(),
            Some(2),
            "{args:?}: {}",
            stderr(&output)
        );
    }
}

#[test]
fn a_size_that_is_not_the_images_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("ours.png");
    let render = raystep(&["render", GLASS, "-o", path(&image), "--size", "40x30"]);
    assert!(render.status.success(), "{}", stderr(&render));
    let scene = scene_at(&root().join(GLASS), Some((40, 30)));
    let log = write(dir.path(), "ok.jsonl", &log_of(&scene, &[], &[(20, 15)]));
    let output = raystep(&[
        "compare",
        GLASS,
        path(&image),
        "--rays",
        path(&log),
        "--size",
        "80x60",
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("--size 80x60 is not your image's size, 40x30"),
        "{}",
        stderr(&output)
    );
}
