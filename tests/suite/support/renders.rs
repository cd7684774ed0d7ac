//! Renders a correct tracer other than raystep could hand in (issue 40): the
//! scene seen from an eye moved by 1e-5 (float32, another order of
//! operations), and raystep's render anti-aliased by averaging 2 x 2 rays a
//! pixel.

use std::path::{Path, PathBuf};

use super::{raystep, stderr};

/// `scene` (a TOML file with one `eye = [x, y, z]` line) copied into `dir`
/// with its eye moved by `by` along `axis` (0: x, 1: y, 2: z).
pub fn eye_moved(scene: &Path, dir: &Path, axis: usize, by: f64) -> PathBuf {
    let text = std::fs::read_to_string(scene).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("eye = ["))
        .unwrap_or_else(|| panic!("{}: no eye line", scene.display()));
    let inner = &line["eye = [".len()..line.len() - 1];
    let mut eye: Vec<f64> = inner
        .split(',')
        .map(|v| v.trim().parse().unwrap())
        .collect();
    eye[axis] += by;
    let moved = format!("eye = [{:?}, {:?}, {:?}]", eye[0], eye[1], eye[2]);
    let name = scene.file_stem().unwrap().to_str().unwrap();
    let out = dir.join(format!("{name}-eye{axis}.toml"));
    std::fs::write(&out, text.replacen(line, &moved, 1)).unwrap();
    out
}

/// raystep's render of `scene` at `width` x `height` (relative to the
/// repository's root, or absolute) written to `out`, with `extra` arguments.
pub fn render_to(scene: &Path, out: &Path, (width, height): (u32, u32), extra: &[&str]) {
    let size = format!("{width}x{height}");
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--size",
        &size,
    ];
    args.extend(extra);
    let output = raystep(&args);
    assert!(output.status.success(), "{}", stderr(&output));
}

/// raystep's render of `scene` at twice `size`, each 2 x 2 block averaged
/// (rounded to the nearest step): the image of a tracer that traces four
/// rays a pixel, through its quarter points, and averages them.
pub fn supersampled(scene: &Path, dir: &Path, (width, height): (u32, u32)) -> image::RgbImage {
    let fine = dir.join("supersampled-fine.png");
    render_to(scene, &fine, (2 * width, 2 * height), &[]);
    let fine = image::open(&fine).unwrap().into_rgb8();
    image::RgbImage::from_fn(width, height, |x, y| {
        let mut sum = [0u32; 3];
        for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let p = fine.get_pixel(2 * x + i, 2 * y + j).0;
            (0..3).for_each(|c| sum[c] += u32::from(p[c]));
        }
        image::Rgb(sum.map(|s| ((s + 2) / 4) as u8))
    })
}

/// The largest difference of one channel between two images' pixels.
pub fn largest_gap(a: &image::RgbImage, b: &image::RgbImage) -> u8 {
    (a.pixels().zip(b.pixels()))
        .flat_map(|(p, q)| (0..3).map(move |c| p.0[c].abs_diff(q.0[c])))
        .max()
        .unwrap_or(0)
}

/// The files `render --terms` writes for a scene without emission, sorted
/// (an emitting scene adds `emission.png`).
pub const TERM_FILES: [&str; 8] = [
    "ambient.png",
    "cost.png",
    "diffuse.png",
    "rays.png",
    "reflected.png",
    "shadow.png",
    "specular.png",
    "transmitted.png",
];
