#![no_main]
//! The mesh loaders on arbitrary bytes: the first byte picks OBJ or STL,
//! the rest is the file. Triangles or an error, never a panic, and the
//! error prints (an OBJ error's excerpt slices the text by byte offsets).

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&kind, bytes)) = data.split_first() else {
        return;
    };
    let name = if kind % 2 == 0 { "fuzz.obj" } else { "fuzz.stl" };
    if let Err(error) = raystep_engine::scene::mesh::load_bytes(Path::new(name), bytes) {
        let _ = error.to_string();
    }
});
