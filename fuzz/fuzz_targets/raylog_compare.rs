#![no_main]
//! `compare --rays`'s engine on arbitrary bytes, against the reader
//! target's scene of 3 lights and 2 objects (a glass ball and a glass
//! floor, so every ray kind is cast): every log is compared or refused with
//! a named error; a comparison's report, text and JSON, is whole; never a
//! panic, whatever numbers a student's log holds (NaN, huge, negative).

use std::path::Path;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use raystep::divergence::{Tolerance, compare_log, json, text};
use raystep::raylog::RaylogReader;
use raystep::scene::Scene;

const SCENE: &str = r#"
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
[image]
width = 8
height = 6
[materials.glass]
ks = 0.3
kt = 0.5
ior = 1.5
[[light]]
position = [0, 4, 4]
[[light]]
position = [4, 4, 4]
[[light]]
position = [-4, 4, 4]
[[object]]
name = "ball"
material = "glass"
sphere = { center = [0, 0, 0], radius = 1 }
[[object]]
name = "floor"
material = "glass"
plane = { normal = [0, 1, 0], point = [0, -1, 0] }
"#;

fn scene() -> &'static Scene {
    static SCENE_ONCE: OnceLock<Scene> = OnceLock::new();
    SCENE_ONCE.get_or_init(|| raystep::scene::parse(Path::new("fuzz.toml"), SCENE).unwrap())
}

fuzz_target!(|data: &[u8]| {
    match compare_log(scene(), RaylogReader::new("fuzz.jsonl", data, scene()), Tolerance::default()) {
        Ok(found) => {
            assert!(found.pixels.len() <= found.pixel_count);
            assert!(found.matching <= found.pixel_count);
            for pixel in &found.pixels {
                assert_eq!(pixel.matches, pixel.first_divergence.is_none());
                assert!(pixel.matches || pixel.later_differences < 1 << 20);
            }
            let words = text(&found, "fuzz.jsonl", "fuzz.toml", None);
            assert!(words.contains("logged"));
            let value = json(&found);
            assert!(value.to_string().starts_with('{'));
        }
        Err(error) => assert!(error.to_string().starts_with("fuzz.jsonl:")),
    }
});
