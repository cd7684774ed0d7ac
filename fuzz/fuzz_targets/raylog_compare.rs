#![no_main]
//! `compare --rays`'s engine on arbitrary bytes, against the reader
//! target's scene of 3 lights and 2 objects (a glass ball and a glass
//! floor, so every ray kind is cast): every log is compared or refused with
//! a named error; a comparison's report, text and JSON, is whole; never a
//! panic, whatever numbers a student's log holds (NaN, huge, negative).

#[path = "raylog_scene.rs"]
mod raylog_scene;

use libfuzzer_sys::fuzz_target;
use raystep_tools::divergence::{Tolerance, compare_log, json, text};
use raystep_tools::raylog::RaylogReader;
use raylog_scene::scene;

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
