//! NVIDIA's FLIP (LDR-FLIP, `raystep-flip`: the same errors as NVIDIA's
//! C++ to the bit natively), run tile by tile so that its memory stays
//! bounded whatever the image's size. It comes with the `flip` feature.

use anyhow::{Result, anyhow};
use image::RgbImage;

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
/// counted from NVIDIA's code and rounded up (raystep-flip keeps fewer
/// copies, about 60 bytes): the two images and four filtered copies of
/// them in f32 colours (12 bytes each), the feature filters' copies, the
/// error and its colours.
const FLIP_BYTES_PER_PIXEL: u64 = 200;

/// FLIP's mean error and its error map in magma colours, run tile by tile
/// (in parallel) with the same values as on the whole image.
pub(super) fn flip(yours: &RgbImage, reference: &RgbImage) -> Result<(f64, RgbImage)> {
    use rayon::prelude::*;
    let (width, height) = yours.dimensions();
    flip_fits(
        (FLIP_TILE + 2 * FLIP_MARGIN).min(width),
        (FLIP_TILE + 2 * FLIP_MARGIN).min(height),
    )?;
    let tiles: Vec<(u32, u32)> = (0..height)
        .step_by(FLIP_TILE as usize)
        .flat_map(|y| (0..width).step_by(FLIP_TILE as usize).map(move |x| (x, y)))
        .collect();
    let done: Vec<Tile> = tiles
        .into_par_iter()
        .map(|(x, y)| flip_tile(yours, reference, x, y))
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
    Ok((raystep_flip::mean(&errors) as f64, map))
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
fn flip_tile(yours: &RgbImage, reference: &RgbImage, x: u32, y: u32) -> Tile {
    let (width, height) = yours.dimensions();
    let (x0, y0) = (x.saturating_sub(FLIP_MARGIN), y.saturating_sub(FLIP_MARGIN));
    let (x1, y1) = (
        (x + FLIP_TILE + FLIP_MARGIN).min(width),
        (y + FLIP_TILE + FLIP_MARGIN).min(height),
    );
    let (cut_width, cut_height) = (x1 - x0, y1 - y0);
    let cut = |image: &RgbImage| {
        image::imageops::crop_imm(image, x0, y0, cut_width, cut_height)
            .to_image()
            .into_raw()
    };
    let all_errors = raystep_flip::flip(
        &cut(reference),
        &cut(yours),
        cut_width,
        cut_height,
        raystep_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let all_colours: Vec<u8> = all_errors
        .iter()
        .flat_map(|&e| raystep_flip::magma(e))
        .collect();
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
}
