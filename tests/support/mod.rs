//! Helpers shared by the test files of the tracer and the command line: a
//! scene from TOML text, the recorded tree of one primary ray cast by hand,
//! and the `raystep` binary run with arguments.

#![allow(dead_code)] // each test file uses some of them

use std::path::Path;
use std::process::{Command, Output};

use glam::DVec3;
use raystep::math::Ray;
use raystep::record::{RayTree, TreeRecorder};
use raystep::scene::{Scene, parse};
use raystep::trace::trace;

pub fn scene(text: &str) -> Scene {
    parse(Path::new("test.toml"), text).unwrap()
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

pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

pub fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}
