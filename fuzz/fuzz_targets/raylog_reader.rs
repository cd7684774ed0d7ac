#![no_main]
//! The ray log reader (docs/RAYLOG.md) on arbitrary bytes, against a small
//! scene of 3 lights and 2 objects: every line reads as a ray or stops the
//! reader with an error that names the log, a line within the input and
//! a column, never a panic.

#[path = "raylog_scene.rs"]
mod raylog_scene;

use libfuzzer_sys::fuzz_target;
use raystep_tools::raylog::RaylogReader;
use raylog_scene::scene;

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
