//! raystep-flip against nv-flip (NVIDIA's C++), natively: the same errors
//! pixel by pixel, the same mean, the same magma colours, on gradients,
//! noise, a rendered scene against a mistaken render, and images smaller
//! than FLIP's filters.

use std::time::Instant;

/// The largest difference allowed between this crate's error and nv-flip's
/// at any pixel. The code follows the C++ operation for operation in f32,
/// and natively both call the same libm (powf, expf): the errors agree to
/// the bit on all these images. The allowance is for another C++ compiler
/// folding a math call at compile time where GCC does not.
const PIXEL_TOLERANCE: f32 = 1e-6;
/// The largest difference allowed between the means (the brief's).
const MEAN_TOLERANCE: f32 = 1e-4;

/// nv-flip's errors for the pair.
fn nv_flip_errors(reference: &[u8], test: &[u8], width: u32, height: u32, ppd: f32) -> Vec<f32> {
    let reference = nv_flip::FlipImageRgb8::with_data(width, height, reference);
    let test = nv_flip::FlipImageRgb8::with_data(width, height, test);
    nv_flip::flip(reference, test, ppd).to_vec()
}

/// nv-flip's pool mean of `errors`.
fn nv_flip_mean(errors: &[f32], width: u32, height: u32) -> f32 {
    let image = nv_flip::FlipImageFloat::with_data(width, height, errors);
    nv_flip::FlipPool::from_image(&image).mean()
}

/// The largest per-pixel difference and the means' difference between
/// this crate and nv-flip on the pair, checked against the tolerances.
fn agree(
    name: &str,
    reference: &[u8],
    test: &[u8],
    width: u32,
    height: u32,
    ppd: f32,
) -> (f32, f32) {
    let ours = raystep_flip::flip(reference, test, width, height, ppd);
    let theirs = nv_flip_errors(reference, test, width, height, ppd);
    assert_eq!(ours.len(), theirs.len(), "{name}");
    let mut largest = 0f32;
    for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        assert!((0.0..=1.0).contains(a), "{name}: pixel {i} is {a}");
        let difference = (a - b).abs();
        assert!(
            difference <= PIXEL_TOLERANCE,
            "{name}: pixel {i} ({}, {}): {a} against nv-flip's {b}",
            i as u32 % width,
            i as u32 / width
        );
        largest = largest.max(difference);
    }
    let (ours_mean, theirs_mean) = (
        raystep_flip::mean(&ours),
        nv_flip_mean(&theirs, width, height),
    );
    let mean_difference = (ours_mean - theirs_mean).abs();
    assert!(
        mean_difference <= MEAN_TOLERANCE,
        "{name}: mean {ours_mean} against nv-flip's {theirs_mean}"
    );
    eprintln!(
        "{name} ({width}x{height}, {ppd} ppd): mean {ours_mean} (nv-flip {theirs_mean}), \
         largest pixel difference {largest:e}, means' {mean_difference:e}"
    );
    (largest, mean_difference)
}

/// A simple linear congruential generator (Knuth's MMIX constants), so the
/// noise is the same on every run and machine.
struct Lcg(u64);

impl Lcg {
    fn byte(&mut self) -> u8 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 56) as u8
    }

    fn image(&mut self, width: u32, height: u32) -> Vec<u8> {
        (0..width * height * 3).map(|_| self.byte()).collect()
    }
}

/// A colour gradient, shifted right by `shift` pixels (the left edge
/// repeated).
fn gradient(width: u32, height: u32, shift: u32) -> Vec<u8> {
    let mut image = Vec::with_capacity((width * height * 3) as usize);
    for y in 0..height {
        for x in 0..width {
            let x = x.saturating_sub(shift);
            image.push((255 * x / (width - 1).max(1)) as u8);
            image.push((255 * y / (height - 1).max(1)) as u8);
            image.push((255 * (x + y) / (width + height - 2).max(1)) as u8);
        }
    }
    image
}

/// A PNG of tests/data as RGB bytes, with its size.
fn png(bytes: &[u8]) -> (Vec<u8>, u32, u32) {
    let image = image::load_from_memory(bytes).unwrap().into_rgb8();
    let (width, height) = image.dimensions();
    (image.into_raw(), width, height)
}

#[test]
fn the_default_viewing_is_nv_flips() {
    assert_eq!(
        raystep_flip::DEFAULT_PIXELS_PER_DEGREE,
        nv_flip::DEFAULT_PIXELS_PER_DEGREE
    );
}

#[test]
fn a_gradient_against_its_shifted_copy() {
    let ppd = raystep_flip::DEFAULT_PIXELS_PER_DEGREE;
    for shift in [1, 3] {
        agree(
            "gradient",
            &gradient(96, 64, 0),
            &gradient(96, 64, shift),
            96,
            64,
            ppd,
        );
    }
    // Identical images: no error at all.
    let same = gradient(40, 30, 0);
    let errors = raystep_flip::flip(&same, &same, 40, 30, ppd);
    assert!(errors.iter().all(|&e| e == 0.0));
}

#[test]
fn noise_pairs() {
    let mut lcg = Lcg(38);
    for (width, height, ppd) in [
        (64, 48, 67.0),
        (33, 71, 67.0),
        (50, 40, 20.0),
        (40, 30, 120.0),
    ] {
        let reference = lcg.image(width, height);
        let test = lcg.image(width, height);
        agree("noise", &reference, &test, width, height, ppd);
        // Noise against a slightly changed copy of itself: small errors,
        // where the colour error's remapping is below p_c · c_max.
        let nudged: Vec<u8> = reference
            .iter()
            .map(|&b| b.saturating_add(lcg.byte() % 8))
            .collect();
        agree("noise nudged", &reference, &nudged, width, height, ppd);
    }
}

#[test]
fn a_rendered_scene_against_a_mistaken_render() {
    // scenes/glass.toml at 160x120, right and with `--mistake eta-inverted`.
    let (reference, width, height) = png(include_bytes!("data/glass.png"));
    let (test, ..) = png(include_bytes!("data/glass-eta-inverted.png"));
    let ppd = raystep_flip::DEFAULT_PIXELS_PER_DEGREE;
    agree("glass", &reference, &test, width, height, ppd);
    agree("glass, swapped", &test, &reference, width, height, ppd);
}

#[test]
fn images_smaller_than_the_filters() {
    // The filters reach 10 pixels at 67 pixels per degree; beyond the
    // image both repeat its edge pixel.
    let mut lcg = Lcg(7);
    let ppd = raystep_flip::DEFAULT_PIXELS_PER_DEGREE;
    for (width, height) in [(1, 1), (1, 17), (17, 1), (2, 2), (5, 3), (9, 12), (21, 21)] {
        let reference = lcg.image(width, height);
        let test = lcg.image(width, height);
        agree("small", &reference, &test, width, height, ppd);
    }
    assert!(raystep_flip::flip(&[], &[], 0, 5, ppd).is_empty());
}

#[test]
fn the_magma_table_is_nv_flips() {
    let lut = nv_flip::magma_lut().to_vec();
    assert_eq!(lut.len(), 256 * 3);
    for (i, theirs) in lut.chunks_exact(3).enumerate() {
        let error = i as f32 / 255.0;
        assert_eq!(raystep_flip::magma(error), theirs, "entry {i}");
    }
    // And the lookup as nv-flip's error maps do it, between the entries.
    let errors: Vec<f32> = (0..=1000).map(|i| i as f32 / 1000.0).collect();
    let image = nv_flip::FlipImageFloat::with_data(errors.len() as u32, 1, &errors);
    let painted = image.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    for (error, theirs) in errors.iter().zip(painted.chunks_exact(3)) {
        assert_eq!(raystep_flip::magma(*error), theirs, "error {error}");
    }
}

#[test]
fn the_mean_is_nv_flips_pool_mean() {
    let mut lcg = Lcg(3);
    let errors: Vec<f32> = (0..640 * 48)
        .map(|_| f32::from(lcg.byte()) / 255.0)
        .collect();
    assert_eq!(raystep_flip::mean(&errors), nv_flip_mean(&errors, 640, 48));
}

#[test]
fn timing_of_a_320x240_pair() {
    // Not a benchmark: a figure for the report, in release mode
    // (`cargo test --release -p raystep-flip -- --nocapture timing`).
    let mut lcg = Lcg(320);
    let reference = lcg.image(320, 240);
    let test = lcg.image(320, 240);
    let ppd = raystep_flip::DEFAULT_PIXELS_PER_DEGREE;
    let start = Instant::now();
    let ours = raystep_flip::flip(&reference, &test, 320, 240, ppd);
    let ours_time = start.elapsed();
    let start = Instant::now();
    let theirs = nv_flip_errors(&reference, &test, 320, 240, ppd);
    let theirs_time = start.elapsed();
    assert_eq!(ours.len(), theirs.len());
    eprintln!("320x240: raystep-flip {ours_time:?}, nv-flip {theirs_time:?}");
}
