#![no_main]
//! `raystep compare`'s reader of the student's PNG on arbitrary bytes: an
//! image or an error naming the input, never a panic.

use std::io::Cursor;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match raystep_tools::compare::student::read(Cursor::new(data), "fuzz.png") {
        Ok(student) => {
            let (w, h) = student.image.dimensions();
            assert!(w > 0 && h > 0);
        }
        Err(error) => assert!(format!("{error:#}").contains("fuzz.png")),
    }
});
