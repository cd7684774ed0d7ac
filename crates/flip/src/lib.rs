//! LDR-FLIP in pure Rust: how different two 8-bit sRGB images look to a
//! viewer flipping between them, one error in [0, 1] per pixel.
//!
//! FLIP is by Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and
//! Fairchild ("FLIP: A Difference Evaluator for Alternating Images", HPG
//! 2020). raystep's compare ran NVIDIA's C++ through the `nv-flip` crate;
//! the web page builds the engine for WebAssembly, where no C++ compiler
//! goes, so this crate is that same C++ (nv-flip-sys's CPP/image.h,
//! color.h and sharedflip.h), rewritten with no dependency at all. It
//! follows the C++ operation for operation in f32, so that a student's
//! FLIP mean and error map are the same numbers in the browser as on the
//! command line; the tests hold it to nv-flip.
//!
//! The steps (paper, section 4; `image::FLIP` in the C++):
//!
//! 1. Both images go from sRGB to YCxCz, a linear opponent space
//!    ([`colour_spaces`]).
//! 2. Each channel is blurred by the eye's contrast sensitivity at the
//!    given viewing distance (pixels per degree), a separable filter
//!    ([`separable`]); detail finer than the eye resolves is gone.
//! 3. The blurred colours go to Lab with the Hunt adjustment; their HyAB
//!    distance, compressed and remapped to [0, 1], is the colour error.
//! 4. Edges (first derivative of a Gaussian) and points (second
//!    derivative) are found in each image's achromatic channel; where they
//!    differ, the colour error is raised towards 1: the error is
//!    `colour ^ (1 − feature)`.
//!
//! Beyond the image, every filter repeats the edge pixel, as the C++ does,
//! so images smaller than a filter (even 1 × 1) are fine.
//!
//! [`magma`] paints an error the way nv-flip's error maps are painted, and
//! [`mean`] pools the errors as nv-flip's `FlipPool::mean` does.
//!
//! How close to nv-flip: natively both call the platform's powf and expf,
//! and the errors agree to the bit (so the means too) on every image of
//! the tests. That takes keeping the optimiser from replacing the C++'s
//! math calls with its own: see the two `black_box`es. In WebAssembly,
//! Rust's own math library rounds some powf and expf results the other way
//! (the sRGB transfer on a few bytes, Lab's cube roots, the filters'
//! weights); FLIP's compressions (a 0.7 power of a small HyAB distance)
//! magnify that to at most 4e-5 on a pixel where the two images are nearly
//! the same colour, and the mean moves by less than 1e-7 (measured under
//! Node on glass.toml against its eta-inverted render at 640 × 480, and on
//! 320 × 240 noise). Either is far below one step of the magma map
//! (1/255).

mod colour_spaces;
mod magma_map;
mod separable;

use colour_spaces::{ColourDifference, linear_rgb_to_xyz, srgb_to_linear, xyz_to_ycxcz};
use separable::{FeatureKernels, PaddedRow, SpatialKernels, column_row, rows};

/// nv-flip's `DEFAULT_PIXELS_PER_DEGREE`, 67.0: roughly a 0.7 m wide
/// 4K monitor seen from 0.7 m (NVIDIA's tool computes that viewing as
/// 67.02 pixels per degree; nv-flip rounds it, and compare has always run
/// with nv-flip's value).
pub const DEFAULT_PIXELS_PER_DEGREE: f32 = 67.0;

/// `FLIPConstants.gqf`: the exponent on the feature difference (paper,
/// section 4.2, q_f).
const GQF: f32 = 0.5;

/// The LDR-FLIP error of `test` against `reference`, one value in [0, 1]
/// per pixel, row by row: `reference` and `test` are 8-bit sRGB, three
/// bytes a pixel, row-major from the top left, `width` × `height`.
/// `pixels_per_degree` sets how far the viewer sits (the filters' sizes);
/// [`DEFAULT_PIXELS_PER_DEGREE`] is nv-flip's.
///
/// # Panics
///
/// If either image is not `width * height * 3` bytes (or that overflows).
pub fn flip(
    reference: &[u8],
    test: &[u8],
    width: u32,
    height: u32,
    pixels_per_degree: f32,
) -> Vec<f32> {
    let (width, height) = (width as usize, height as usize);
    let size = width
        .checked_mul(height)
        .filter(|size| size.checked_mul(3).is_some())
        .expect("the image's size overflows usize");
    assert_eq!(
        reference.len(),
        size * 3,
        "reference is not {width} x {height} RGB"
    );
    assert_eq!(test.len(), size * 3, "test is not {width} x {height} RGB");
    if size == 0 {
        return Vec::new();
    }
    let reference = Opponent::new(reference);
    let test = Opponent::new(test);
    let colour = colour_errors(&reference, &test, (width, height), pixels_per_degree);
    feature_errors(
        &reference.y,
        &test.y,
        colour,
        (width, height),
        pixels_per_degree,
    )
}

/// The mean of `errors` as nv-flip's `FlipPool::mean` gives it: summed in
/// f32 in their order (row by row), divided by their count (NaN for none).
pub fn mean(errors: &[f32]) -> f32 {
    errors.iter().fold(0f32, |sum, &error| sum + error) / errors.len() as f32
}

/// The magma colour of `error`, as nv-flip's error maps (`apply_color_lut`
/// with `magma_lut()`) paint it: entry `⌊255 · error + 0.5⌋` of the table.
/// An error outside [0, 1] (never FLIP's) takes the nearer end, where the
/// C++ would wrap or read past its table.
pub fn magma(error: f32) -> [u8; 3] {
    let index = ((error * 255.0 + 0.5) as i32).clamp(0, 255);
    magma_map::MAGMA_BYTES[index as usize]
}

/// An image in YCxCz, one plane a channel.
struct Opponent {
    y: Vec<f32>,
    cx: Vec<f32>,
    cz: Vec<f32>,
}

impl Opponent {
    /// `tensor::sRGB2YCxCz` on nv-flip's bytes (each `byte / 255.0f`).
    fn new(srgb: &[u8]) -> Self {
        // 256 possible channel values: the transfer function (a powf)
        // once each, at run time as in the C++ (`black_box`): on constants
        // the optimiser would fold the powf with its own pow, which differs
        // from the math library's in the last bit on some bytes (252 in
        // WebAssembly).
        let linear: Vec<f32> = (0..=255u8)
            .map(|byte| srgb_to_linear(std::hint::black_box(f32::from(byte) / 255.0)))
            .collect();
        let size = srgb.len() / 3;
        let mut image = Self {
            y: Vec::with_capacity(size),
            cx: Vec::with_capacity(size),
            cz: Vec::with_capacity(size),
        };
        for pixel in srgb.chunks_exact(3) {
            let rgb = [0, 1, 2].map(|c| linear[usize::from(pixel[c])]);
            let [y, cx, cz] = xyz_to_ycxcz(linear_rgb_to_xyz(rgb));
            image.y.push(y);
            image.cx.push(cx);
            image.cz.push(cz);
        }
        image
    }
}

/// `image::computeColorDifference`: both images filtered by the contrast
/// sensitivity functions (rows, then columns), then each pixel's colour
/// error.
fn colour_errors(
    reference: &Opponent,
    test: &Opponent,
    (width, height): (usize, usize),
    pixels_per_degree: f32,
) -> Vec<f32> {
    let kernels = SpatialKernels::new(pixels_per_degree);
    let mut padded = PaddedRow::new(kernels.y.len() / 2);
    // The horizontal pass: Y, Cx, and Cz twice (its two Gaussians).
    let mut across = |image: &Opponent| {
        [
            rows(&image.y, width, &kernels.y, &mut padded),
            rows(&image.cx, width, &kernels.cx, &mut padded),
            rows(&image.cz, width, &kernels.cz1, &mut padded),
            rows(&image.cz, width, &kernels.cz2, &mut padded),
        ]
    };
    let (reference, test) = (across(reference), across(test));
    let weights = [&kernels.y, &kernels.cx, &kernels.cz1, &kernels.cz2];
    let difference = ColourDifference::new();
    let mut errors = Vec::with_capacity(width * height);
    let mut filtered = vec![vec![0f32; width]; 8];
    for y in 0..height {
        // The vertical pass, one row of the eight planes at a time.
        for (i, (plane, out)) in reference.iter().chain(&test).zip(&mut filtered).enumerate() {
            column_row(plane, (width, height), y, weights[i % 4], out);
        }
        errors.extend((0..width).map(|x| {
            let at = |c: usize| filtered[c][x];
            let reference = [at(0), at(1), at(2) + at(3)];
            let test = [at(4), at(5), at(6) + at(7)];
            difference.error(reference, test)
        }));
    }
    errors
}

/// `image::computeFeatureDifferenceAndFinalError`: edges and points of
/// both images' achromatic channels (rows, then columns), their
/// differences, and the final error `colour ^ (1 − feature)` in place of
/// `colour`.
fn feature_errors(
    reference_y: &[f32],
    test_y: &[f32],
    mut errors: Vec<f32>,
    (width, height): (usize, usize),
    pixels_per_degree: f32,
) -> Vec<f32> {
    let kernels = FeatureKernels::new(pixels_per_degree);
    let mut padded = PaddedRow::new(kernels.gaussian.len() / 2);
    // The achromatic channel to [0, 1], as the C++ writes it
    // (`y * oneOver116 + sixteenOver116`).
    let (one_over_116, sixteen_over_116) = (1.0f32 / 116.0, 16.0f32 / 116.0);
    // The horizontal pass: first and second derivatives along x, and the
    // Gaussian that the vertical pass differentiates along y.
    let mut across = |luma: &[f32]| {
        let grey: Vec<f32> = luma
            .iter()
            .map(|&y| y * one_over_116 + sixteen_over_116)
            .collect();
        [
            rows(&grey, width, &kernels.first, &mut padded),
            rows(&grey, width, &kernels.second, &mut padded),
            rows(&grey, width, &kernels.gaussian, &mut padded),
        ]
    };
    let (reference, test) = (across(reference_y), across(test_y));
    // Per image: d/dx, d²/dx² (each blurred along y), d/dy, d²/dy² (of the
    // blurred rows).
    let passes = [
        (0, &kernels.gaussian),
        (1, &kernels.gaussian),
        (2, &kernels.first),
        (2, &kernels.second),
    ];
    let mut filtered = vec![vec![0f32; width]; 8];
    let normalisation = 1.0 / 2f32.sqrt();
    // The C++'s powf, not the square root that LLVM puts for a known
    // power of 0.5 (correctly rounded, where powf is a last bit away on
    // some values).
    let gqf = std::hint::black_box(GQF);
    for y in 0..height {
        for (i, out) in filtered.iter_mut().enumerate() {
            let planes = if i < 4 { &reference } else { &test };
            let (plane, kernel) = passes[i % 4];
            column_row(&planes[plane], (width, height), y, kernel, out);
        }
        for (x, error) in errors[y * width..(y + 1) * width].iter_mut().enumerate() {
            let at = |c: usize| filtered[c][x];
            let (dx, ddx, dy, ddy) = (at(0), at(1), at(2), at(3));
            let edge_reference = (dx * dx + dy * dy).sqrt();
            let point_reference = (ddx * ddx + ddy * ddy).sqrt();
            let (dx, ddx, dy, ddy) = (at(4), at(5), at(6), at(7));
            let edge_test = (dx * dx + dy * dy).sqrt();
            let point_test = (ddx * ddx + ddy * ddy).sqrt();
            let edge = (edge_reference - edge_test).abs();
            let point = (point_reference - point_test).abs();
            // `Max(edge, point)` as the C++'s macro picks.
            let largest = if edge > point { edge } else { point };
            let feature = (normalisation * largest).powf(gqf);
            *error = error.powf(1.0 - feature);
        }
    }
    errors
}
