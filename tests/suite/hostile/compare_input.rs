//! `compare` and `grade` on images whose decoded size, not file size, is the danger, and thresholds that are not numbers.

use std::io::Write;
use std::path::Path;

use flate2::{Compression, write::ZlibEncoder};
use image::{ImageFormat, RgbImage};

use crate::support::{raystep, raystep_within, stderr};

/// A PNG chunk: length, type, data, CRC-32 of type and data.
fn chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let mut crc = flate2::Crc::new();
    crc.update(kind);
    crc.update(data);
    let mut out = (data.len() as u32).to_be_bytes().to_vec();
    out.extend(kind);
    out.extend(data);
    out.extend(crc.sum().to_be_bytes());
    out
}

/// `png` with `extra` put right after its header (the signature's 8 bytes
/// and IHDR's 25), where an iCCP chunk belongs.
fn with_chunk(png: &[u8], extra: &[u8]) -> Vec<u8> {
    [&png[..33], extra, &png[33..]].concat()
}

/// An iCCP chunk whose profile is `zeros` zero bytes, compressed.
fn iccp(zeros: usize) -> Vec<u8> {
    let mut data = ZlibEncoder::new(b"bomb\0\0".to_vec(), Compression::best());
    let block = vec![0u8; 1 << 20];
    for start in (0..zeros).step_by(block.len()) {
        data.write_all(&block[..block.len().min(zeros - start)])
            .unwrap();
    }
    chunk(b"iCCP", &data.finish().unwrap())
}

/// A 16 x 12 PNG of one grey.
fn small_png() -> Vec<u8> {
    let mut png = Vec::new();
    RgbImage::from_pixel(16, 12, image::Rgb([90, 90, 90]))
        .write_to(&mut std::io::Cursor::new(&mut png), ImageFormat::Png)
        .unwrap();
    png
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn an_icc_profile_inflating_to_a_gibibyte_is_refused_by_name_not_by_a_signal() {
    // 16 x 12 pixels and a 1 MB iCCP chunk whose zlib stream inflates to
    // 1 GiB of zeros (deflate's longest match, 258 bytes, in about two
    // bits: 1 GiB / 1032 is about 1 MB). main inflated up to the
    // decoder's default 512 MiB and died by SIGABRT under a 400 MB limit.
    let dir = tempfile::tempdir().unwrap();
    let bomb = iccp(1 << 30);
    assert!(bomb.len() < 2 << 20, "{} bytes", bomb.len());
    let image = write(dir.path(), "bomb.png", &with_chunk(&small_png(), &bomb));
    let output = raystep_within(400_000_000, &["compare", "scenes/shadows.toml", &image]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert_eq!(
        stderr(&output),
        format!(
            "error: {image}: its ICC profile (iCCP chunk) inflates to more than 16 MiB: \
             save the image without a colour profile, or with sRGB's\n"
        )
    );
    // A real profile's size (sRGB's is about 3 KB; a printer's a few MB)
    // is read as before.
    let image = write(
        dir.path(),
        "profile.png",
        &with_chunk(&small_png(), &iccp(3 << 20)),
    );
    let output = raystep(&["compare", "scenes/shadows.toml", &image]);
    assert!(output.status.success(), "{}", stderr(&output));
}

#[test]
fn grade_refuses_an_icc_bomb_by_name_and_writes_its_results_under_a_memory_limit() {
    // raystep's own 16 x 12 render of shadows.toml, the size the
    // assignment asks for, with an iCCP chunk inflating to 512 MiB put in
    // (about 520 KB: within the 16 x 12 x 8 bytes and 1 MiB a submission
    // of that size may take, so the file's length lets it through). main
    // read the size with the image crate's decoder, which inflates the
    // profile whole first, and died by SIGABRT under 400 MB before any
    // results file was written.
    let dir = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(
        root.join("scenes/shadows.toml"),
        dir.path().join("shadows.toml"),
    )
    .unwrap();
    let assignment = write(
        dir.path(),
        "a.toml",
        b"title = \"bomb\"\n\n[[scene]]\nfile = \"shadows.toml\"\n\
          submit = \"shadows.png\"\npoints = 10\nsize = [16, 12]\n",
    );
    let render = dir.path().join("render.png");
    let rendered = raystep(&[
        "render",
        "scenes/shadows.toml",
        "--size",
        "16x12",
        "-o",
        render.to_str().unwrap(),
    ]);
    assert!(rendered.status.success(), "{}", stderr(&rendered));
    let render = std::fs::read(render).unwrap();
    let student = dir.path().join("student");
    std::fs::create_dir(&student).unwrap();
    let grade = |png: &[u8]| {
        write(&student, "shadows.png", png);
        let results = dir.path().join("gradescope.json");
        let _ = std::fs::remove_file(&results);
        let output = raystep_within(
            400_000_000,
            &[
                "grade",
                &assignment,
                "--submission",
                student.to_str().unwrap(),
                "--gradescope",
                results.to_str().unwrap(),
            ],
        );
        // Graded (exit 0, whatever the grade), not killed by a signal.
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        let results: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&results).unwrap()).unwrap();
        results["tests"][0].clone()
    };
    let bomb = with_chunk(&render, &iccp(512 << 20));
    assert!(bomb.len() < 16 * 12 * 8 + (1 << 20), "{} bytes", bomb.len());
    let test = grade(&bomb);
    // The refusal compare gives, naming the file (as the assignment
    // spells it), in grade's words for a file not graded.
    assert_eq!(test["score"], 0.0);
    assert_eq!(
        test["output"],
        "0 of 10 points: not graded, shadows.png: its ICC profile (iCCP chunk) inflates \
         to more than 16 MiB: save the image without a colour profile, or with sRGB's.\n"
    );
    // The same render with a 3 MB profile (a printer's) is read whole and
    // matches: 10 of 10.
    let test = grade(&with_chunk(&render, &iccp(3 << 20)));
    assert_eq!(test["score"], 10.0, "{}", test["output"]);
}

#[test]
fn an_image_too_large_to_compare_is_refused_from_its_header() {
    // A header of 8192 x 8192 pixels at 16 bits in four channels (a size
    // raystep renders, and 512 MiB decoded) and a few bytes of pixels.
    // main took the header, allocated the 512 MiB and died by SIGABRT
    // under a 400 MB limit.
    // Now the header is refused before anything is decoded: 8192 x 8192 is
    // past the 2048 x 2048 pixels compared.
    let dir = tempfile::tempdir().unwrap();
    let mut header = 8192u32.to_be_bytes().to_vec();
    header.extend(8192u32.to_be_bytes());
    header.extend([16, 6, 0, 0, 0]);
    let mut pixels = ZlibEncoder::new(Vec::new(), Compression::best());
    pixels.write_all(&[0; 100]).unwrap();
    let png = [
        b"\x89PNG\r\n\x1a\n".to_vec(),
        chunk(b"IHDR", &header),
        chunk(b"IDAT", &pixels.finish().unwrap()),
        chunk(b"IEND", &[]),
    ]
    .concat();
    let image = write(dir.path(), "huge.png", &png);
    let output = raystep_within(400_000_000, &["compare", "scenes/shadows.toml", &image]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert_eq!(
        stderr(&output),
        format!(
            "error: {image}: image size 8192x8192 is too large to compare: \
             at most 4194304 pixels (2048 x 2048) are compared\n"
        )
    );
    // 2049 x 2048 is one column past; 4096 x 1024 is exactly 2048².
    for (size, refused) in [((2049u32, 2048u32), true), ((4096, 1024), false)] {
        let mut header = size.0.to_be_bytes().to_vec();
        header.extend(size.1.to_be_bytes());
        header.extend([8, 2, 0, 0, 0]);
        let png = [
            b"\x89PNG\r\n\x1a\n".to_vec(),
            chunk(b"IHDR", &header),
            chunk(b"IEND", &[]),
        ]
        .concat();
        let image = write(dir.path(), "edge.png", &png);
        let said = stderr(&raystep(&["compare", "scenes/shadows.toml", &image]));
        // Within the cap, the missing pixels are what the decoder refuses.
        assert_eq!(said.contains("too large to compare"), refused, "{said}");
    }
}

#[test]
fn thresholds_that_are_not_numbers_from_zero_up_are_bad_command_lines() {
    // main: `--max-flip nan` exited 0 for any image (every comparison with
    // NaN is false) and `--max-flip=-1` exited 3 for an identical one.
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("same.png");
    let image = image.to_str().unwrap();
    let rendered = raystep(&[
        "render",
        "scenes/shadows.toml",
        "--size",
        "16x12",
        "-o",
        image,
    ]);
    assert!(rendered.status.success(), "{}", stderr(&rendered));
    for (flag, value) in [
        ("--max-flip", "nan"),
        ("--max-flip", "NaN"),
        ("--max-flip", "-1"),
        ("--max-flip", "inf"),
        ("--max-mean-abs", "NaN"),
        ("--max-mean-abs", "-0.5"),
        ("--max-mean-abs", "1e400"),
        ("--max-mean-abs", "-infinity"),
    ] {
        let output = raystep(&["compare", "scenes/shadows.toml", image, flag, value]);
        assert_eq!(output.status.code(), Some(2), "{flag} {value}");
        let said = stderr(&output);
        assert!(
            said.starts_with(&format!("error: invalid value '{value}' for '{flag} <")),
            "{said}"
        );
        assert!(said.contains("give a number of at least 0"), "{said}");
    }
    // 0 is a threshold: the identical image is not above it.
    let output = raystep(&[
        "compare",
        "scenes/shadows.toml",
        image,
        "--max-flip",
        "0",
        "--max-mean-abs=0",
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}
