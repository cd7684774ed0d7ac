//! Helpers shared by the tracer's test files: a scene from TOML text, and
//! the recorded tree of one primary ray cast by hand.

use std::path::Path;

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
