#![no_main]
//! Load, then record one pixel of a 4x4 image: no panic, a finite pixel, and
//! a recording whose every number is finite (what `inspect --format json`
//! checks before printing).
//!
//! The first byte picks the format (even: TOML, odd: NFF) and the pixel
//! (bits 1-2: x, bits 3-4: y); the rest is the scene text.

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use raystep_engine::record::record_pixel;

/// The image is resized to SIDE x SIDE, so any pixel of the 16 is cheap.
const SIDE: u32 = 4;
/// max_depth is clamped to this, so that the known exponential ray tree
/// (max_depth = 64 on two facing glass surfaces) does not drown every other
/// finding in timeouts. Set RAYSTEP_FUZZ_MAX_DEPTH to change it (0: no clamp).
const DEFAULT_DEPTH_CLAMP: u32 = 8;

fn depth_clamp() -> u32 {
    std::env::var("RAYSTEP_FUZZ_MAX_DEPTH")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_DEPTH_CLAMP)
}

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    let name = if selector & 1 == 0 { "fuzz.toml" } else { "fuzz.nff" };
    let text = String::from_utf8_lossy(rest);
    let Ok(scene) = raystep_engine::scene::parse(Path::new(name), &text) else {
        return;
    };
    let Ok(mut scene) = scene.with_size(SIDE, SIDE) else {
        return;
    };
    let clamp = depth_clamp();
    if clamp > 0 {
        scene.settings.max_depth = scene.settings.max_depth.min(clamp);
    }
    let (x, y) = (u32::from(selector >> 1) % SIDE, u32::from(selector >> 3) % SIDE);
    let tree = record_pixel(&scene, &scene.settings, x, y);
    let color = tree.color();
    assert!(color.is_finite(), "pixel ({x}, {y}) is {color}");
    if let Err(error) = tree.check_finite() {
        panic!("{error}");
    }
    let _ = raystep_model::math::to_rgb8(color);
});
