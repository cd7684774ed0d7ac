#![no_main]
//! The ray log reader (docs/RAYLOG.md) on arbitrary bytes, against a small
//! scene of 3 lights and 2 objects: every line reads as a ray or stops the
//! reader with an error that names the log, a line within the input and
//! a column, never a panic.

use std::path::Path;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
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
    let lines = data.split(|&b| b == b'\n').count();
    for ray in RaylogReader::new("fuzz.jsonl", data, scene()) {
        match ray {
            Ok((line, ray)) => {
                assert!(line >= 1 && line <= lines);
                assert!(ray.pixel.0 < 8 && ray.pixel.1 < 6);
            }
            Err(error) => {
                assert!(error.line >= 1 && error.line <= lines.max(1), "{error}");
                assert!(error.column >= 1, "{error}");
                assert!(error.to_string().starts_with("fuzz.jsonl:"));
                break;
            }
        }
    }
});
