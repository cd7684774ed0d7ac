#![no_main]
//! The CSE 167 `.test` reader on arbitrary text, through to raystep's scene
//! (`scene::parse` of a `.test` path: the parser, then `to_scene`, the
//! acceleration structure built): a scene or an error, never a panic, and
//! the error prints (its excerpt slices the text by byte offsets).

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Err(error) = raystep_engine::scene::parse(Path::new("fuzz.test"), &text) {
        let _ = error.to_string();
    }
});
