//! The web page (dist/raystep.html) against the command line: built with
//! web/build.sh, driven in headless Chromium by web/tests/page.test.mjs
//! (Playwright) with real clicks, keys, drops and downloads, and every
//! answer compared with what `raystep` answers here. Without Debian's
//! rustc-web toolchain, Chromium, Node.js or the test's npm packages the
//! test is skipped with the reason, unless CI is set: there it fails
//! (`.ci/run` installs them).

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::{Value, json};

use crate::support::chromium::chromium_or_skip;
use crate::support::program_or_skip;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// `raystep ARGS` run in `dir`, which must succeed; its stdout.
fn raystep_in(dir: &Path, args: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_raystep"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("raystep runs");
    assert!(
        output.status.success(),
        "raystep {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

/// What the page's tests need, or `None` after saying what is missing.
fn tools_or_skip() -> Option<(PathBuf, PathBuf)> {
    for program in ["wasm-ld", "python3"] {
        program_or_skip(program)?;
    }
    let toolchain = Path::new("/usr/bin/cargo").is_file() && Path::new("/usr/bin/rustc").is_file();
    let ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0");
    if !toolchain {
        assert!(
            !ci,
            "Debian's rustc-web is not installed, and CI is set (.ci/run installs it)"
        );
        eprintln!(
            "note: the web page's test skipped: apt-get install rustc-web cargo-web rust-web-src lld"
        );
        return None;
    }
    let chromium = chromium_or_skip("the web page's test")?
        .program()
        .to_owned();
    let node = program_or_skip("node")?;
    let playwright = Path::new(ROOT).join("web/tests/node_modules/playwright-core");
    if !playwright.is_dir() {
        assert!(
            !ci,
            "web/tests has no node_modules, and CI is set (.ci/run runs npm ci there)"
        );
        eprintln!("note: the web page's test skipped: run npm ci in web/tests");
        return None;
    }
    Some((chromium, node))
}

/// Every scene under `dir`, as web/assemble.py takes them.
fn scene_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            found.extend(scene_files(&path));
        } else if path
            .extension()
            .is_some_and(|e| e == "toml" || e == "nff" || e == "test")
        {
            // An assignment lists [[scene]] tables: not a scene to open.
            let text = std::fs::read_to_string(&path).unwrap();
            if !text.lines().any(|l| l.trim() == "[[scene]]") {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

/// The rays of inspect's JSON tree: a ray and those it reflected and
/// transmitted.
fn rays_in(ray: &Value) -> usize {
    1 + ["reflected", "transmitted"]
        .iter()
        .filter(|k| ray[**k].is_object())
        .map(|k| rays_in(&ray[*k]))
        .sum::<usize>()
}

/// glass.toml with another max_depth, for the depth toggle's render.
fn with_max_depth(text: &str, depth: u32) -> String {
    assert!(
        !text.contains("max_depth"),
        "glass.toml sets max_depth: change this test"
    );
    text.replacen(
        "[settings]\n",
        &format!("[settings]\nmax_depth = {depth}\n"),
        1,
    )
}

#[test]
fn the_page_answers_as_the_command_line_does_in_a_browser() {
    let Some((chromium, node)) = tools_or_skip() else {
        return;
    };
    let root = Path::new(ROOT);
    let page = root.join("target/web-test/raystep.html");
    let built = Command::new("sh")
        .arg(root.join("web/build.sh"))
        .args(["--out", page.to_str().unwrap()])
        .status()
        .expect("web/build.sh runs");
    assert!(built.success(), "web/build.sh failed");

    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    // Every scene the page has built in, rendered by the command line.
    let scenes = scene_files(&root.join("scenes"));
    let scenes: Vec<Value> = scenes
        .iter()
        .enumerate()
        .map(|(i, path)| {
            let relative = path.strip_prefix(root.join("scenes")).unwrap();
            let png = work.join(format!("scene-{i}.png"));
            raystep_in(
                root,
                &[
                    "render",
                    path.to_str().unwrap(),
                    "-o",
                    png.to_str().unwrap(),
                ],
            );
            json!({ "path": relative.to_str().unwrap(), "png": png })
        })
        .collect();
    assert!(
        scenes.len() >= 20,
        "scenes/ holds the teaching and SPD scenes"
    );

    // A pixel of glass.toml, as explain and inspect tell it; the scene
    // copied beside the student's files, so that names match the page's.
    let glass_text = std::fs::read_to_string(root.join("scenes/glass.toml")).unwrap();
    std::fs::write(work.join("glass.toml"), &glass_text).unwrap();
    let (x, y) = (80, 60);
    let at = format!("{x},{y}");
    let explain = raystep_in(work, &["explain", "glass.toml", "--pixel", &at]);
    let tree: Value = serde_json::from_str(&raystep_in(
        work,
        &["inspect", "glass.toml", "--pixel", &at, "--format", "json"],
    ))
    .unwrap();
    let rays = rays_in(&tree["tree"]);

    // The first pixel the keyboard picks, (3, 2) of the first scene, stepped.
    let first = raystep_engine::scene::load(&root.join("scenes/seven-rays.toml")).unwrap();
    let keys_tree = raystep_engine::record::record_pixel(&first, &first.settings, 3, 2);
    use raystep_engine::record::stepping::{Step, step};
    let keys = json!({
        "into": step(&keys_tree, 0, Step::Into),
        "events": keys_tree.events.len(),
    });

    // The depth toggle ([) against the scene written with that depth.
    let scene = raystep_engine::scene::load(&root.join("scenes/glass.toml")).unwrap();
    let depth = scene.settings.max_depth - 1;
    std::fs::write(
        work.join("shallow.toml"),
        with_max_depth(&glass_text, depth),
    )
    .unwrap();
    raystep_in(work, &["render", "shallow.toml", "-o", "shallow.png"]);
    raystep_in(
        work,
        &[
            "render",
            "glass.toml",
            "--mistake",
            "flipped-y",
            "-o",
            "flipped.png",
        ],
    );

    // A mistake's render and ray log, as compare names them.
    raystep_in(
        work,
        &[
            "render",
            "glass.toml",
            "--mistake",
            "eta-inverted",
            "-o",
            "eta.png",
        ],
    );
    let compared: Value = serde_json::from_str(&raystep_in(
        work,
        &["compare", "glass.toml", "eta.png", "--format", "json"],
    ))
    .unwrap();
    let first_mistake = compared["mistakes"][0]["name"].as_str().unwrap().to_owned();
    let log = raystep_in(
        work,
        &[
            "inspect",
            "glass.toml",
            "--pixel",
            &at,
            "--format",
            "raylog",
            "--mistake",
            "eta-inverted",
        ],
    );
    std::fs::write(work.join("eta.jsonl"), log).unwrap();
    let rays_json: Value = serde_json::from_str(&raystep_in(
        work,
        &[
            "compare",
            "glass.toml",
            "--rays",
            "eta.jsonl",
            "--format",
            "json",
        ],
    ))
    .unwrap();
    let divergence = &rays_json["pixels"][0]["first_divergence"];
    let first_divergence = format!(
        "{} {}",
        divergence["path"].as_str().unwrap(),
        divergence["field"].as_str().unwrap()
    );

    // A broken scene, typed over glass.toml in the page: the command line's
    // message for the same text in a file of that name.
    let broken = glass_text.replacen("[settings]", "[settings\n", 1);
    std::fs::write(work.join("glass.toml"), &broken).unwrap();
    let refused = Command::new(env!("CARGO_BIN_EXE_raystep"))
        .args(["render", "glass.toml", "-o", "never.png"])
        .current_dir(work)
        .output()
        .unwrap();
    assert!(!refused.status.success());
    let message = String::from_utf8(refused.stderr).unwrap();

    // A CSE 167 scene's profile, in the debugger's header's words:
    // `maxdepth 4` is four bounces, MODEL's depth 5.
    let cse167 = raystep_engine::scene::Profile::Cse167;
    let profile = json!({
        "scene": "cse167/mirrors.test",
        "text": format!("profile {} (MODEL §11)", cse167.name()),
        "bounces": " (4 bounces)",
        "words": cse167.words(),
        // The mistakes menu offers what the profile offers (no refraction
        // under cse167), the whole catalogue for the lecture's glass.toml.
        "offered": cse167.offered_mistakes().map(|m| m.name()).collect::<Vec<_>>(),
        "catalogue": raystep_model::mistakes::Mistake::ALL.map(|m| m.name()),
    });

    let expectations = json!({
        "page": page,
        "chromium": chromium,
        "scenes": scenes,
        "keys": keys,
        "pixel": { "scene": "glass.toml", "x": x, "y": y, "explain": explain, "rays": rays },
        "depth": { "max_depth": depth, "png": work.join("shallow.png") },
        "mistake": { "name": "flipped-y", "png": work.join("flipped.png") },
        "compare": { "png": work.join("eta.png"), "first_mistake": first_mistake },
        "raylog": { "file": work.join("eta.jsonl"), "first": first_divergence },
        "error": { "text": broken, "message": message.trim_end() },
        "profile": profile,
    });
    let file = work.join("expectations.json");
    std::fs::write(&file, expectations.to_string()).unwrap();
    let run = Command::new(node)
        .arg(root.join("web/tests/page.test.mjs"))
        .arg(&file)
        .current_dir(root.join("web/tests"))
        .output()
        .expect("node runs");
    let said = String::from_utf8_lossy(&run.stdout);
    println!("{said}");
    assert!(
        run.status.success(),
        "the page's test failed:\n{said}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
}
