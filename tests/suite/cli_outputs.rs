//! Where `render` writes (issue 13, "files are never destroyed"): modes,
//! outputs that must not be replaced, `--terms` as one set, temporaries.

use std::fs;
use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::support::renders::TERM_FILES;

const SCENE: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[image]\nwidth = 8\nheight = 6\n\
[materials.m]\nkd = 1\n[[light]]\nposition = [0, 5, 5]\n[[object]]\nmaterial = \"m\"\nsphere = { center = [0, 0, 0], radius = 1 }\n";

/// A fresh folder holding `scene.toml`.
fn folder() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.toml");
    fs::write(&scene, SCENE).unwrap();
    (dir, scene)
}

/// `raystep render ARGS` under `umask`, in `cwd`.
fn render_with_umask(umask: &str, cwd: &Path, args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("umask {umask}; exec \"$0\" render \"$@\""))
        .arg(env!("CARGO_BIN_EXE_raystep"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("sh runs")
}

fn render(cwd: &Path, args: &[&str]) -> Output {
    render_with_umask("022", cwd, args)
}

/// Checks a refusal: exit code 1 and a message naming `path`; returns it.
fn refused(output: &Output, path: &str) -> String {
    let message = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains(&format!("cannot write {path}")),
        "{message}"
    );
    message
}

fn mode(path: &Path) -> u32 {
    fs::metadata(path).unwrap().permissions().mode() & 0o7777
}

/// The names in a folder, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn is_png(path: &Path) -> bool {
    fs::read(path).unwrap().starts_with(b"\x89PNG\r\n\x1a\n")
}

#[test]
fn a_new_png_gets_the_mode_the_umask_allows() {
    // A new file is created 0666 less the umask: 022 -> 0644, 002 -> 0664, 077 -> 0600.
    for (umask, expected) in [("022", 0o644), ("002", 0o664), ("077", 0o600)] {
        let (dir, _) = folder();
        let output = render_with_umask(umask, dir.path(), &["scene.toml", "-o", "out.png"]);
        assert!(output.status.success(), "{output:?}");
        assert_eq!(mode(&dir.path().join("out.png")), expected, "umask {umask}");
    }
}

#[test]
fn a_replaced_png_keeps_its_mode() {
    for old_mode in [0o644, 0o664, 0o640] {
        let (dir, _) = folder();
        let out = dir.path().join("out.png");
        fs::write(&out, b"old").unwrap();
        fs::set_permissions(&out, fs::Permissions::from_mode(old_mode)).unwrap();
        // umask 077 would make a new file 0600: the old mode wins.
        let output = render_with_umask("077", dir.path(), &["scene.toml", "-o", "out.png"]);
        assert!(output.status.success(), "{output:?}");
        assert!(is_png(&out));
        assert_eq!(mode(&out), old_mode);
    }
}

#[test]
fn the_scene_file_is_never_the_output_however_it_is_spelt() {
    let (dir, scene) = folder();
    std::os::unix::fs::symlink("scene.toml", dir.path().join("link.toml")).unwrap();
    fs::hard_link(&scene, dir.path().join("hard.toml")).unwrap();
    fs::create_dir(dir.path().join("sub")).unwrap();
    let absolute = scene.to_str().unwrap();
    for spelling in [
        "scene.toml",
        "./scene.toml",
        "sub/../scene.toml",
        absolute,
        "link.toml",
        "hard.toml",
    ] {
        let output = render(dir.path(), &["scene.toml", "-o", spelling]);
        let message = refused(&output, spelling);
        assert!(message.contains("it is the scene file"), "{message}");
        assert_eq!(fs::read_to_string(&scene).unwrap(), SCENE, "{spelling}");
    }
    assert!(
        fs::symlink_metadata(dir.path().join("link.toml"))
            .unwrap()
            .is_symlink()
    );
    assert_eq!(
        names(dir.path()),
        ["hard.toml", "link.toml", "scene.toml", "sub"]
    );
}

#[test]
fn devices_and_directories_are_refused() {
    let (dir, _) = folder();
    let output = render(dir.path(), &["scene.toml", "-o", "/dev/null"]);
    let message = refused(&output, "/dev/null");
    assert!(message.contains("not a regular file"), "{message}");
    assert!(
        fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );

    std::os::unix::fs::symlink("/dev/null", dir.path().join("null.png")).unwrap();
    let output = render(dir.path(), &["scene.toml", "-o", "null.png"]);
    refused(&output, "null.png");
    assert!(
        fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );

    fs::create_dir(dir.path().join("out.png")).unwrap();
    for spelling in ["out.png", "out.png/", "."] {
        let output = render(dir.path(), &["scene.toml", "-o", spelling]);
        let message = refused(&output, spelling);
        assert!(message.contains("it is a directory"), "{message}");
    }
    assert!(names(&dir.path().join("out.png")).is_empty());
    assert_eq!(names(dir.path()), ["null.png", "out.png", "scene.toml"]);
}

#[test]
fn a_symbolic_link_is_followed_and_stays_a_link() {
    let (dir, _) = folder();
    let real = dir.path().join("real.png");
    fs::write(&real, b"old").unwrap();
    fs::set_permissions(&real, fs::Permissions::from_mode(0o640)).unwrap();
    let link = dir.path().join("link.png");
    std::os::unix::fs::symlink("real.png", &link).unwrap();
    let output = render(dir.path(), &["scene.toml", "-o", "link.png"]);
    assert!(output.status.success(), "{output:?}");
    assert!(fs::symlink_metadata(&link).unwrap().is_symlink());
    assert!(is_png(&real));
    assert_eq!(mode(&real), 0o640);

    // A link to nothing is refused rather than guessed at.
    std::os::unix::fs::symlink("nowhere.png", dir.path().join("dangling.png")).unwrap();
    let output = render(dir.path(), &["scene.toml", "-o", "dangling.png"]);
    let message = refused(&output, "dangling.png");
    assert!(
        message.contains("nowhere.png, which does not exist"),
        "{message}"
    );
    assert_eq!(
        names(dir.path()),
        ["dangling.png", "link.png", "real.png", "scene.toml"]
    );
}

#[test]
fn the_image_is_never_one_of_the_term_files() {
    let (dir, _) = folder();
    fs::create_dir(dir.path().join("terms")).unwrap();
    for (out, terms) in [
        ("terms/diffuse.png", "terms"),
        ("terms/../terms/./cost.png", "./terms"),
    ] {
        let output = render(dir.path(), &["scene.toml", "-o", out, "--terms", terms]);
        let message = String::from_utf8_lossy(&output.stderr).into_owned();
        assert_eq!(output.status.code(), Some(1), "{message}");
        assert!(
            message.contains("it would be both the image (-o) and the"),
            "{message}"
        );
        assert!(names(&dir.path().join("terms")).is_empty(), "{out}");
    }
}

#[test]
fn terms_into_something_that_is_not_a_folder_writes_nothing() {
    let (dir, _) = folder();
    fs::write(dir.path().join("terms"), b"a file").unwrap();
    for terms in ["terms", "terms/sub"] {
        let output = render(
            dir.path(),
            &["scene.toml", "-o", "out.png", "--terms", terms],
        );
        let message = refused(&output, &format!("into {terms}"));
        assert!(message.contains("terms is not a folder"), "{message}");
    }
    let output = render(
        dir.path(),
        &["scene.toml", "-o", "out.png", "--terms", "new/../x"],
    );
    let message = refused(&output, "into new/../x");
    assert!(message.contains("below a missing folder"), "{message}");
    // /proc refuses new files, even to root.
    let output = render(
        dir.path(),
        &["scene.toml", "-o", "out.png", "--terms", "/proc/raystep"],
    );
    let message = refused(&output, "into /proc/raystep");
    assert!(message.contains("/proc is not writable"), "{message}");
    assert_eq!(fs::read(dir.path().join("terms")).unwrap(), b"a file");
    assert_eq!(names(dir.path()), ["scene.toml", "terms"]);
}

#[test]
fn terms_into_a_new_folder_write_the_whole_set_and_nothing_else() {
    let (dir, _) = folder();
    // A refused image leaves the new folder uncreated.
    let output = render(
        dir.path(),
        &["scene.toml", "-o", "/dev/null", "--terms", "a/b"],
    );
    refused(&output, "/dev/null");
    assert_eq!(names(dir.path()), ["scene.toml"]);

    let output = render(
        dir.path(),
        &["scene.toml", "-o", "out.png", "--terms", "a/b"],
    );
    assert!(output.status.success(), "{output:?}");
    assert_eq!(names(dir.path()), ["a", "out.png", "scene.toml"]);
    assert_eq!(names(&dir.path().join("a")), ["b"]);
    assert_eq!(names(&dir.path().join("a/b")), TERM_FILES);
    assert!(
        TERM_FILES
            .iter()
            .all(|f| is_png(&dir.path().join("a/b").join(f)))
    );
}

#[test]
fn a_stale_temporary_is_removed_and_a_live_one_kept() {
    let (dir, _) = folder();
    // Left by a killed run: nobody holds it locked.
    let stale = dir.path().join(".raystep-AbC123.png.tmp");
    fs::write(&stale, b"half a png").unwrap();
    // Held by a run still writing (this test holds the lock).
    let live = dir.path().join(".raystep-XyZ789.png.tmp");
    let held = fs::File::create(&live).unwrap();
    held.lock().unwrap();
    // Not ours: a similar name without the suffix.
    let other = dir.path().join(".raystep-notes.txt");
    fs::write(&other, b"keep").unwrap();

    let output = render(dir.path(), &["scene.toml", "-o", "out.png"]);
    assert!(output.status.success(), "{output:?}");
    assert_eq!(
        names(dir.path()),
        [
            ".raystep-XyZ789.png.tmp",
            ".raystep-notes.txt",
            "out.png",
            "scene.toml"
        ]
    );
    drop(held);
}

#[test]
fn terms_give_the_plain_render_s_image_and_stats() {
    // `--terms` takes the image (and with `--stats` the counts) from the
    // terms pass. Glass has every term (reflected and transmitted rays,
    // shadows), so the images must agree byte for byte with the plain
    // render's and the counts with those of `--stats` alone.
    let dir = tempfile::tempdir().unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/glass.toml");
    let size = ["--size", "40x30", "--threads", "2"];
    let mut counts = Vec::new();
    for (out, extra) in [
        ("plain.png", &[][..]),
        ("terms.png", &["--terms", "t"][..]),
        ("stats.png", &["--terms", "s", "--stats"][..]),
        ("counted.png", &["--stats"][..]),
    ] {
        let args = [&[scene, "-o", out][..], &size[..], extra].concat();
        let output = render(dir.path(), &args);
        assert!(output.status.success(), "{out}: {output:?}");
        counts.push(counts_of(&output.stdout));
    }
    assert_eq!(counts[2], counts[3]);
    assert!(counts[3]["primary"] == 1200 && counts[3]["transmitted"].as_u64() > Some(0));
    let read = |name: &str| fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("terms.png"), read("plain.png"));
    assert_eq!(read("stats.png"), read("plain.png"));
    for term in names(&dir.path().join("t")) {
        assert_eq!(
            read(&format!("t/{term}")),
            read(&format!("s/{term}")),
            "{term}"
        );
    }
    assert_eq!(names(&dir.path().join("t")).len(), 8);
}

/// The `--stats` JSON without what varies from run to run (times, memory).
fn counts_of(stdout: &[u8]) -> serde_json::Value {
    let mut json: serde_json::Value = serde_json::from_slice(stdout).unwrap_or_default();
    if let Some(map) = json.as_object_mut() {
        // Times vary; the term images' scales come only with --terms.
        map.retain(|key, _| {
            !key.ends_with("_seconds") && !key.ends_with("_per_pixel") && key != "peak_memory_mib"
        });
    }
    json
}
