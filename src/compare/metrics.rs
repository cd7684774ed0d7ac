//! How far two images of the same size are apart: the mean absolute error,
//! NVIDIA's FLIP (through the `nv-flip` crate, as wgpu's tests use it), the
//! share of pixels past a tolerance, and the worst pixel.

use anyhow::{Result, anyhow};
use image::{GrayImage, RgbImage};
use serde::Serialize;

/// A channel may differ by this many 8-bit steps before a pixel counts as
/// different (mental ray's imf_diff counts the same way): another correct
/// tracer rounds differently in the last bit, and a student's byte
/// conversion may differ by one step.
pub(crate) const TOLERANCE_STEPS: u8 = 3;
/// The images match when at most this share of pixels is past the
/// tolerance: an independent correct tracer differs on a few pixels where a
/// ray grazes an edge or a shadow boundary, which must still match.
pub(crate) const MATCH_SHARE: f64 = 0.001;
/// And no pixel of a match has a channel more than this many steps apart:
/// an eighth of the range, more than rounding or float precision moves a
/// correct tracer's pixel, less than a classic mistake moves the pixels it
/// touches (a wrapped byte by about 255). So six wrapped bytes, well under
/// `MATCH_SHARE`, still make the images differ.
pub(crate) const MATCH_GAP: u8 = 32;
/// At most this many pixels past `MATCH_GAP` are listed.
const FAR_OFF_LISTED: usize = 8;

#[derive(Clone, Debug, Serialize)]
pub(crate) struct Metrics {
    /// Mean over pixels and channels of |yours - reference|, from 0 to 1.
    pub(crate) mean_abs: f64,
    /// FLIP's mean error (LDR, 67 pixels per degree), from 0 to 1.
    pub(crate) flip_mean: f64,
    /// The share of pixels with a channel more than `tolerance` apart.
    pub(crate) pixels_over_tolerance: f64,
    /// `TOLERANCE_STEPS` / 255.
    pub(crate) tolerance: f64,
    pub(crate) worst: Option<PixelPair>,
    /// How many pixels have a channel more than `MATCH_GAP` steps apart.
    pub(crate) far_off_pixels: usize,
    /// The first of them in row-major order, at most `FAR_OFF_LISTED`.
    pub(crate) far_off: Vec<PixelPair>,
}

/// A pixel and its two values: the worst one, or one far off.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct PixelPair {
    pub(crate) pixel: [u32; 2],
    pub(crate) yours: [u8; 3],
    pub(crate) reference: [u8; 3],
}

impl Metrics {
    pub(crate) fn matches(&self) -> bool {
        self.few_over_tolerance() && self.far_off_pixels == 0
    }

    /// Whether the share rule alone would call it a match.
    pub(crate) fn few_over_tolerance(&self) -> bool {
        self.pixels_over_tolerance <= MATCH_SHARE
    }
}

/// The largest difference of one channel between the two pixels.
pub(crate) fn channel_gap(a: [u8; 3], b: [u8; 3]) -> u8 {
    (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0)
}

/// Whether each pixel differs past the tolerance, as a mask (255 differs).
pub(crate) fn over_tolerance(yours: &RgbImage, reference: &RgbImage) -> GrayImage {
    GrayImage::from_fn(yours.width(), yours.height(), |x, y| {
        let gap = channel_gap(yours.get_pixel(x, y).0, reference.get_pixel(x, y).0);
        image::Luma([if gap > TOLERANCE_STEPS { 255 } else { 0 }])
    })
}

/// Measures `yours` against `reference` (same size); also gives FLIP's
/// error map in its magma colours. An error when the memory FLIP needs
/// cannot be had.
pub(crate) fn measure(yours: &RgbImage, reference: &RgbImage) -> Result<(Metrics, RgbImage)> {
    let (width, height) = yours.dimensions();
    let pixels = (width as u64 * height as u64) as f64;
    let mut sum = 0u64;
    let mut over = 0u64;
    let mut worst: Option<(u8, u32, u32)> = None;
    let mut far_off_pixels = 0;
    let mut far_off = Vec::new();
    let pair = |x, y| PixelPair {
        pixel: [x, y],
        yours: yours.get_pixel(x, y).0,
        reference: reference.get_pixel(x, y).0,
    };
    for (x, y, p) in yours.enumerate_pixels() {
        let (a, b) = (p.0, reference.get_pixel(x, y).0);
        sum += (0..3).map(|c| a[c].abs_diff(b[c]) as u64).sum::<u64>();
        let gap = channel_gap(a, b);
        over += u64::from(gap > TOLERANCE_STEPS);
        if gap > MATCH_GAP {
            far_off_pixels += 1;
            if far_off.len() < FAR_OFF_LISTED {
                far_off.push(pair(x, y));
            }
        }
        if gap > 0 && worst.is_none_or(|(g, _, _)| gap > g) {
            worst = Some((gap, x, y));
        }
    }
    let (flip_mean, error_map) = flip(yours, reference)?;
    let metrics = Metrics {
        mean_abs: sum as f64 / (3.0 * 255.0 * pixels),
        flip_mean,
        pixels_over_tolerance: over as f64 / pixels,
        tolerance: TOLERANCE_STEPS as f64 / 255.0,
        worst: worst.map(|(_, x, y)| pair(x, y)),
        far_off_pixels,
        far_off,
    };
    Ok((metrics, error_map))
}

/// FLIP runs on tiles of this side, each cut with `FLIP_MARGIN` more of
/// the image around it: FLIP keeps up to `FLIP_BYTES_PER_PIXEL`, and on
/// tiles that is a few tens of megabytes whatever the image's size.
const FLIP_TILE: u32 = 256;
/// FLIP's filters reach 10 pixels at 67 pixels per degree (the spatial
/// filter's radius, ⌈3 √(0.04 / 2π²) · 67⌉ = 10; the feature filter's,
/// ⌈3 · 0.5 · 0.082 · 67⌉ = 9), and at the image's edge they repeat its
/// last pixel. So a tile's own pixels, with this margin around them where
/// the image goes on, get from FLIP the very values the whole image gives.
const FLIP_MARGIN: u32 = 16;
/// What FLIP allocates at most for each pixel of a tile (with its margin),
/// counted from its code and rounded up: the two images and four filtered
/// copies of them in f32 colours (12 bytes each), the feature filters'
/// copies, the error and its colours.
const FLIP_BYTES_PER_PIXEL: u64 = 200;

/// FLIP's mean error and its error map in magma colours, run tile by tile
/// (in parallel) with the same values as on the whole image.
fn flip(yours: &RgbImage, reference: &RgbImage) -> Result<(f64, RgbImage)> {
    use rayon::prelude::*;
    let (width, height) = yours.dimensions();
    flip_fits(
        (FLIP_TILE + 2 * FLIP_MARGIN).min(width),
        (FLIP_TILE + 2 * FLIP_MARGIN).min(height),
    )?;
    let lut = nv_flip::magma_lut();
    let tiles: Vec<(u32, u32)> = (0..height)
        .step_by(FLIP_TILE as usize)
        .flat_map(|y| (0..width).step_by(FLIP_TILE as usize).map(move |x| (x, y)))
        .collect();
    let done: Vec<Tile> = tiles
        .into_par_iter()
        .map(|(x, y)| flip_tile(yours, reference, x, y, &lut))
        .collect();
    let mut errors = vec![0f32; width as usize * height as usize];
    let mut map = RgbImage::new(width, height);
    for tile in &done {
        for (i, (&error, colour)) in tile.errors.iter().zip(tile.colours.chunks(3)).enumerate() {
            let (x, y) = (
                tile.x + i as u32 % tile.width,
                tile.y + i as u32 / tile.width,
            );
            errors[(y * width + x) as usize] = error;
            map.put_pixel(x, y, image::Rgb([colour[0], colour[1], colour[2]]));
        }
    }
    // FLIP's pool adds the errors in f32, row by row: so here, for the
    // same mean to the last bit.
    let sum = errors.iter().fold(0f32, |sum, &e| sum + e);
    Ok(((sum / errors.len() as f32) as f64, map))
}

/// One tile's own pixels, row by row: FLIP's error and its magma colour.
struct Tile {
    x: u32,
    y: u32,
    width: u32,
    errors: Vec<f32>,
    colours: Vec<u8>,
}

/// FLIP on the tile at (x, y), cut with its margin.
fn flip_tile(
    yours: &RgbImage,
    reference: &RgbImage,
    x: u32,
    y: u32,
    lut: &nv_flip::FlipImageRgb8,
) -> Tile {
    let (width, height) = yours.dimensions();
    let (x0, y0) = (x.saturating_sub(FLIP_MARGIN), y.saturating_sub(FLIP_MARGIN));
    let (x1, y1) = (
        (x + FLIP_TILE + FLIP_MARGIN).min(width),
        (y + FLIP_TILE + FLIP_MARGIN).min(height),
    );
    let (cut_width, cut_height) = (x1 - x0, y1 - y0);
    let cut = |image: &RgbImage| {
        let raw = image::imageops::crop_imm(image, x0, y0, cut_width, cut_height)
            .to_image()
            .into_raw();
        nv_flip::FlipImageRgb8::with_data(cut_width, cut_height, &raw)
    };
    let errors = nv_flip::flip(
        cut(reference),
        cut(yours),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let (all_errors, all_colours) = (errors.to_vec(), errors.apply_color_lut(lut).to_vec());
    let (own_width, own_height) = (FLIP_TILE.min(width - x), FLIP_TILE.min(height - y));
    let mut tile = Tile {
        x,
        y,
        width: own_width,
        errors: Vec::with_capacity((own_width * own_height) as usize),
        colours: Vec::with_capacity((own_width * own_height * 3) as usize),
    };
    for row in y..y + own_height {
        let start = ((row - y0) * cut_width + (x - x0)) as usize;
        tile.errors
            .extend_from_slice(&all_errors[start..start + own_width as usize]);
        tile.colours
            .extend_from_slice(&all_colours[3 * start..3 * (start + own_width as usize)]);
    }
    tile
}

/// Reserves what FLIP will take for a tile of `width` x `height` and gives
/// it back at once: running out of memory (under a limit such as `ulimit
/// -v`) is then this error, never an abort inside C++, which Rust cannot
/// catch.
fn flip_fits(width: u32, height: u32) -> Result<()> {
    let threads = rayon::current_num_threads() as u64;
    let bytes = u64::from(width) * u64::from(height) * FLIP_BYTES_PER_PIXEL * threads;
    let mut probe: Vec<u8> = Vec::new();
    usize::try_from(bytes)
        .ok()
        .and_then(|b| probe.try_reserve_exact(b).ok())
        .ok_or_else(|| {
            anyhow!(
                "not enough memory to compare the images: FLIP needs about {} MB",
                bytes.div_ceil(1_000_000)
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_follow_the_tolerance_and_the_worst_pixel_is_found() {
        // 4 pixels: equal; off by 3 (within); off by 4 (over); off by 40 (worst).
        let reference = RgbImage::from_pixel(4, 1, image::Rgb([100, 100, 100]));
        let mut yours = reference.clone();
        yours.put_pixel(1, 0, image::Rgb([103, 100, 100]));
        yours.put_pixel(2, 0, image::Rgb([100, 96, 100]));
        yours.put_pixel(3, 0, image::Rgb([100, 100, 140]));
        let (metrics, map) = measure(&yours, &reference).unwrap();
        // (3 + 4 + 40) / (4 pixels * 3 channels * 255) = 47 / 3060.
        assert!((metrics.mean_abs - 47.0 / 3060.0).abs() < 1e-12);
        assert_eq!(metrics.pixels_over_tolerance, 0.5);
        let worst = metrics.worst.clone().unwrap();
        assert_eq!(worst.pixel, [3, 0]);
        assert_eq!(worst.yours, [100, 100, 140]);
        assert!(!metrics.matches());
        assert_eq!(map.dimensions(), (4, 1));
        // 40 > 32: the one pixel far off.
        assert_eq!(metrics.far_off_pixels, 1);
        assert_eq!(metrics.far_off[0].pixel, [3, 0]);
    }

    #[test]
    fn a_few_pixels_far_off_make_the_images_differ() {
        // 100 x 100 = 10,000 pixels; a match allows 0.1% = 10 past the
        // tolerance. Five pixels off by 255 in one channel (a wrapped byte)
        // are 0.05%, within that share, but each is past the 32 steps.
        let reference = RgbImage::from_pixel(100, 100, image::Rgb([255, 200, 100]));
        let mut yours = reference.clone();
        for x in 0..5 {
            yours.put_pixel(x * 10, 7, image::Rgb([0, 200, 100]));
        }
        let (metrics, _) = measure(&yours, &reference).unwrap();
        assert_eq!(metrics.pixels_over_tolerance, 0.0005);
        assert!(metrics.few_over_tolerance());
        assert_eq!(metrics.far_off_pixels, 5);
        assert!(!metrics.matches());
        // Off by exactly 32 is still a match; by 33 it is not.
        let mut near = reference.clone();
        near.put_pixel(0, 0, image::Rgb([223, 200, 100]));
        assert!(measure(&near, &reference).unwrap().0.matches());
        near.put_pixel(0, 0, image::Rgb([222, 200, 100]));
        assert!(!measure(&near, &reference).unwrap().0.matches());
    }

    #[test]
    fn flip_on_tiles_gives_what_flip_on_the_whole_image_gives() {
        // 600 x 530: tiles of 256 meet inside the image at x = 256, 512 and
        // y = 256, 512, and the last ones are cut short. Two images that
        // differ everywhere by a pattern that varies within a filter's
        // reach, so a tile without its margin would be told wrong.
        let (width, height) = (600, 530);
        let reference = RgbImage::from_fn(width, height, |x, y| {
            image::Rgb([(x * 7 + y * 3) as u8, (x ^ y) as u8, (x * y / 64) as u8])
        });
        let yours = RgbImage::from_fn(width, height, |x, y| {
            let p = reference.get_pixel(x, y).0;
            let d = ((x / 3 + y / 5) % 40) as u8;
            image::Rgb([p[0].wrapping_add(d), p[1], p[2].saturating_sub(d)])
        });
        let whole = nv_flip::flip(
            nv_flip::FlipImageRgb8::with_data(width, height, reference.as_raw()),
            nv_flip::FlipImageRgb8::with_data(width, height, yours.as_raw()),
            nv_flip::DEFAULT_PIXELS_PER_DEGREE,
        );
        let whole_mean = nv_flip::FlipPool::from_image(&whole).mean() as f64;
        let whole_map = whole.apply_color_lut(&nv_flip::magma_lut()).to_vec();
        let (mean, map) = flip(&yours, &reference).unwrap();
        assert!(mean > 0.01, "{mean}");
        assert_eq!(mean.to_bits(), whole_mean.to_bits(), "{mean} {whole_mean}");
        assert!(map.as_raw() == &whole_map, "the maps differ");
    }

    #[test]
    fn identical_images_have_no_error_at_all() {
        let image = RgbImage::from_fn(16, 16, |x, y| image::Rgb([x as u8 * 16, y as u8 * 16, 9]));
        let (metrics, _) = measure(&image, &image).unwrap();
        assert_eq!(metrics.mean_abs, 0.0);
        assert_eq!(metrics.flip_mean, 0.0);
        assert!(metrics.worst.is_none());
        assert!(metrics.matches());
    }
}
