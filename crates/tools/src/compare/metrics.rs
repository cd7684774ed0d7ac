//! How far two images of the same size are apart: the mean absolute error,
//! NVIDIA's FLIP where the build has it (`flip`), the share of pixels past
//! a tolerance, and the worst pixel.

use anyhow::Result;
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
pub struct Metrics {
    /// Mean over pixels and channels of |yours - reference|, from 0 to 1.
    pub mean_abs: f64,
    /// FLIP's mean error (LDR, 67 pixels per degree), from 0 to 1, where
    /// the build has FLIP (the `flip` feature).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flip_mean: Option<f64>,
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

/// Whether `other` reproduces `yours` by the match rule: at most
/// `MATCH_SHARE` of the pixels past the tolerance and none past
/// `MATCH_GAP` (what `matches` says of the reference, said of any image).
pub(crate) fn reproduces(yours: &RgbImage, other: &RgbImage) -> bool {
    let mut over = 0u64;
    for (a, b) in yours.pixels().zip(other.pixels()) {
        let gap = channel_gap(a.0, b.0);
        if gap > MATCH_GAP {
            return false;
        }
        over += u64::from(gap > TOLERANCE_STEPS);
    }
    over as f64 <= MATCH_SHARE * (yours.width() as u64 * yours.height() as u64) as f64
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
/// error map in its magma colours where the build has FLIP. An error when
/// the memory FLIP needs cannot be had.
pub(crate) fn measure(
    yours: &RgbImage,
    reference: &RgbImage,
) -> Result<(Metrics, Option<RgbImage>)> {
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
    #[cfg(feature = "flip")]
    let (flip_mean, error_map) = {
        let (mean, map) = super::flip::flip(yours, reference)?;
        (Some(mean), Some(map))
    };
    #[cfg(not(feature = "flip"))]
    let (flip_mean, error_map) = (None, None);
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
        #[cfg(feature = "flip")]
        assert_eq!(map.unwrap().dimensions(), (4, 1));
        #[cfg(not(feature = "flip"))]
        assert!(map.is_none());
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
    fn identical_images_have_no_error_at_all() {
        let image = RgbImage::from_fn(16, 16, |x, y| image::Rgb([x as u8 * 16, y as u8 * 16, 9]));
        let (metrics, _) = measure(&image, &image).unwrap();
        assert_eq!(metrics.mean_abs, 0.0);
        #[cfg(feature = "flip")]
        assert_eq!(metrics.flip_mean, Some(0.0));
        #[cfg(not(feature = "flip"))]
        assert_eq!(metrics.flip_mean, None);
        assert!(metrics.worst.is_none());
        assert!(metrics.matches());
    }
}
