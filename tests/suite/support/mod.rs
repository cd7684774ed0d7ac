//! Helpers shared by the test files of the tracer and the command line: a
//! scene from TOML text, the recorded tree of one primary ray cast by hand,
//! the `raystep` binary run with arguments, and the one way to pin a
//! snapshot. The debugger's helpers are in `debugger.rs`, headless
//! Chromium for the class report in `chromium.rs`.

pub mod chromium;
pub mod debugger;
pub mod renders;
pub mod student;

/// Pins `value` (anything `Display`) as `snapshots/<file>__<name>.snap`,
/// `<file>` being the test file that asserts it.
macro_rules! snapshot {
    ($name:expr, $value:expr) => {
        $crate::support::snapshot_settings().bind(|| {
            insta::assert_snapshot!(
                $crate::support::snapshot_name(module_path!(), $name),
                $value
            )
        })
    };
}

/// `snapshot!` for a value serialised as JSON.
macro_rules! json_snapshot {
    ($name:expr, $value:expr) => {
        $crate::support::snapshot_settings().bind(|| {
            insta::assert_json_snapshot!(
                $crate::support::snapshot_name(module_path!(), $name),
                $value
            )
        })
    };
}

/// Where snapshots live: `snapshots/` at the root (this file's folder is
/// `tests/suite/`), named by `snapshot_name`, not by insta's module prefix.
pub fn snapshot_settings() -> insta::Settings {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings
}

/// `<file>__<name>`: `module_path` is `suite::<file>` or deeper.
pub fn snapshot_name(module_path: &str, name: &str) -> String {
    let file = module_path
        .split("::")
        .nth(1)
        .expect("a test file's module");
    format!("{file}__{name}")
}

use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Command, Output};

use glam::DVec3;
use raystep_engine::record::{RayTree, TreeRecorder};
use raystep_engine::scene::{Scene, parse};
use raystep_engine::trace::trace;
use raystep_model::math::Ray;

pub fn scene(text: &str) -> Scene {
    parse(Path::new("test.toml"), text).unwrap()
}

/// The scene file at `path`, at `size` if given (its field of view kept).
pub fn scene_at(path: &Path, size: Option<(u32, u32)>) -> Scene {
    let scene = raystep_engine::scene::load(path).unwrap();
    match size {
        Some((w, h)) => scene.with_size(w, h).unwrap(),
        None => scene,
    }
}

/// The tree of one primary ray from `origin` along `direction`.
pub fn record(scene: &Scene, origin: [f64; 3], direction: [f64; 3]) -> RayTree {
    let ray = Ray::new(DVec3::from_array(origin), DVec3::from_array(direction));
    let mut recorder = TreeRecorder::new(scene, &scene.settings);
    trace(scene, &scene.settings, &ray, &mut recorder);
    recorder.into_tree((0, 0))
}

/// The `raystep` binary run with `args` from the repository's root.
pub fn raystep(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raystep"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("raystep runs")
}

/// `raystep args`, its address space limited to `bytes` (as `ulimit -v`
/// does): an allocation past it fails instead of being granted.
pub fn raystep_within(bytes: u64, args: &[&str]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_raystep"));
    command.args(args).current_dir(env!("CARGO_MANIFEST_DIR"));
    // Two threads and two malloc arenas, as on the 2-core machine where the
    // limits were measured: on a machine with many cores each thread's
    // stack and arena (64 MiB of address space) would spend the limit.
    command
        .env("RAYON_NUM_THREADS", "2")
        .env("MALLOC_ARENA_MAX", "2");
    // SAFETY: setrlimit is async-signal-safe; nothing else runs in the child.
    unsafe {
        command.pre_exec(move || {
            let limit = libc::rlimit {
                rlim_cur: bytes,
                rlim_max: bytes,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    command.output().expect("raystep runs")
}

pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

pub fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The program `name` found on PATH, or `None` after printing that the
/// test calling it is skipped. With CI set (and not `false` or `0`), a
/// missing program fails the test instead: `.ci/run` installs it.
pub fn program_or_skip(name: &str) -> Option<std::path::PathBuf> {
    if let Some(program) = on_path(name) {
        return Some(program);
    }
    let test = std::thread::current()
        .name()
        .unwrap_or("a test")
        .to_string();
    let ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0");
    assert!(
        !ci,
        "{test}: {name} is not installed, and CI is set (.ci/run installs it)"
    );
    eprintln!("note: {test} skipped: {name} is not installed (.ci/run installs it)");
    None
}

/// The file `name` in a folder of PATH.
pub fn on_path(name: &str) -> Option<std::path::PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(name))
        .find(|file| file.is_file())
}

/// The teaching scenes, as paths from the repository's root: the ones a
/// student's tracer and compare's sweeps are tried on.
pub const TEACHING_SCENES: [&str; 9] = [
    "scenes/attenuation.toml",
    "scenes/glass.toml",
    "scenes/highlights.toml",
    "scenes/mirrors.toml",
    "scenes/polygons.toml",
    "scenes/prism.toml",
    "scenes/seven-rays.toml",
    "scenes/shadows.toml",
    "scenes/two-lights.toml",
];

/// A path as the command line takes it (the tests' paths are UTF-8).
pub fn path(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

/// A JSON file read whole.
pub fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

/// The TOML scenes at the top of `scenes/` (not the SPD, mesh or assignment
/// folders), in name order.
pub fn top_level_toml_scenes() -> Vec<std::path::PathBuf> {
    let scenes = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut found: Vec<_> = std::fs::read_dir(scenes)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    found.sort();
    found
}
