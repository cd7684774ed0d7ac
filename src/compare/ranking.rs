//! Which classic mistake explains the student's image: the scene rendered
//! again under each mistake with the same engine, and each variant measured
//! by how much of the student's difference from the reference it accounts for.
//!
//! The student's tracer is another program: its rounding speckles other
//! pixels than ours (shadow acne) and its edges fall elsewhere. So images are
//! compared by the mean colour of 8 x 8 blocks, not pixel by pixel: two
//! speckled images of the same density agree there, where a clean one does not.

use image::RgbImage;
use serde::Serialize;

use super::metrics::{TOLERANCE_STEPS, channel_gap};
use crate::mistakes::Mistake;
use crate::render::render;
use crate::scene::{Scene, Settings};
use crate::trace::NoRecorder;

/// The side of the blocks compared.
const BLOCK: u32 = 8;
/// A mistake is listed when it explains at least this share of the difference.
pub const MIN_EXPLAINS: f64 = 0.2;

/// A mistake and how much of the difference it explains.
#[derive(Clone, Debug, Serialize)]
pub struct Ranked {
    #[serde(rename = "name")]
    pub mistake: Mistake,
    /// 1 - D(yours, variant) / D(yours, reference), D the block difference:
    /// 1 when the mistaken render is the student's image, 0 or less when it
    /// is no closer than the correct one.
    pub explains: f64,
    /// A pixel where the mistake shows: the student's pixel differs from the
    /// reference there and the mistaken render comes closest to it.
    pub pixel: Option<[u32; 2]>,
}

/// Every mistake that explains at least `MIN_EXPLAINS` of the difference
/// between `yours` and `reference`, best first.
pub fn rank(
    scene: &Scene,
    settings: &Settings,
    yours: &RgbImage,
    reference: &RgbImage,
) -> Vec<Ranked> {
    let blocks_yours = block_sums(yours);
    let apart = difference(&blocks_yours, &block_sums(reference));
    if apart == 0 {
        return Vec::new();
    }
    let mut ranked: Vec<Ranked> = Mistake::ALL
        .into_iter()
        .filter_map(|mistake| {
            let mut mistaken = *settings;
            mistaken.mistakes = mistaken.mistakes.with(mistake);
            let variant = render::<NoRecorder>(scene, &mistaken, &|| {}).0;
            if variant == *reference {
                return None; // the mistake changes nothing in this scene
            }
            let left = difference(&blocks_yours, &block_sums(&variant));
            let explains = 1.0 - left as f64 / apart as f64;
            (explains >= MIN_EXPLAINS).then(|| Ranked {
                mistake,
                explains,
                pixel: showing_pixel(yours, reference, &variant),
            })
        })
        .collect();
    ranked.sort_by(|a, b| b.explains.total_cmp(&a.explains));
    ranked
}

/// Each block's channel sums, row-major by block.
fn block_sums(image: &RgbImage) -> Vec<[u32; 3]> {
    let (width, height) = image.dimensions();
    let across = width.div_ceil(BLOCK);
    let mut sums = vec![[0u32; 3]; (across * height.div_ceil(BLOCK)) as usize];
    for (x, y, p) in image.enumerate_pixels() {
        let block = &mut sums[((y / BLOCK) * across + x / BLOCK) as usize];
        for (sum, &value) in block.iter_mut().zip(&p.0) {
            *sum += value as u32;
        }
    }
    sums
}

/// The sum over blocks and channels of the blocks' difference.
fn difference(a: &[[u32; 3]], b: &[[u32; 3]]) -> u64 {
    a.iter()
        .zip(b)
        .map(|(a, b)| (0..3).map(|c| a[c].abs_diff(b[c]) as u64).sum::<u64>())
        .sum()
}

/// Where the variant comes closest to the student's image, among the pixels
/// that both the variant and the student's image change.
fn showing_pixel(yours: &RgbImage, reference: &RgbImage, variant: &RgbImage) -> Option<[u32; 2]> {
    let mut best: Option<(i32, u32, u32)> = None;
    for (x, y, p) in yours.enumerate_pixels() {
        let (r, v) = (reference.get_pixel(x, y).0, variant.get_pixel(x, y).0);
        let off = channel_gap(p.0, r);
        if off <= TOLERANCE_STEPS || channel_gap(v, r) <= TOLERANCE_STEPS {
            continue;
        }
        let gain = off as i32 - channel_gap(p.0, v) as i32;
        if best.is_none_or(|(g, _, _)| gain > g) {
            best = Some((gain, x, y));
        }
    }
    best.map(|(_, x, y)| [x, y])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_sums_make_speckles_of_equal_density_agree() {
        // Two 8 x 8 images, each with 32 white pixels on black, in other
        // places: pixel by pixel they differ everywhere they are white, but
        // their one block holds 32 * 255 in each channel in both.
        let a = RgbImage::from_fn(8, 8, |x, y| {
            image::Rgb([if (x + y) % 2 == 0 { 255 } else { 0 }; 3])
        });
        let b = RgbImage::from_fn(8, 8, |x, y| {
            image::Rgb([if (x + y) % 2 == 1 { 255 } else { 0 }; 3])
        });
        assert_eq!(difference(&block_sums(&a), &block_sums(&b)), 0);
        let black = RgbImage::new(8, 8);
        assert_eq!(
            difference(&block_sums(&a), &block_sums(&black)),
            3 * 32 * 255
        );
    }

    #[test]
    fn the_showing_pixel_is_where_the_variant_meets_the_student() {
        // Reference black; the student brightened pixels 1 and 2 to 200;
        // the variant brightens pixel 1 to 200 and pixel 2 to 50: it meets
        // the student at pixel 1 (gain 200) better than at 2 (gain 50).
        let reference = RgbImage::new(3, 1);
        let mut yours = reference.clone();
        yours.put_pixel(1, 0, image::Rgb([200; 3]));
        yours.put_pixel(2, 0, image::Rgb([200; 3]));
        let mut variant = reference.clone();
        variant.put_pixel(1, 0, image::Rgb([200; 3]));
        variant.put_pixel(2, 0, image::Rgb([50; 3]));
        assert_eq!(showing_pixel(&yours, &reference, &variant), Some([1, 0]));
    }
}
