//! Whether the student's image is the reference seen through another
//! camera: shifted by whole or half pixels, scaled about the image's centre
//! (another field of view) or flipped. Such an image differs almost
//! everywhere, and pixel by pixel it can look like a missing term (an edge
//! moved onto the background, a shadow's border moved), so the regions are
//! told "the geometry differs" instead.
//!
//! Each candidate change is applied to the reference (sampled bilinearly:
//! a half-pixel shift averages two neighbours) and compared with the
//! student's image by the mean colours of 4 x 4 blocks, which a moved edge
//! changes in proportion to how far it moved, where single pixels would
//! flip between two colours. Only blocks the changed reference covers
//! count (a wider view shows what the reference never rendered), and at
//! most `MAX_BLOCKS` spread over the image, which keeps a 512 x 512 image
//! as cheap as a small one.

use image::RgbImage;
use serde::Serialize;

use raystep_engine::record::num;

/// The side of the blocks compared.
const BLOCK: u32 = 4;
/// At most about this many blocks are compared, spread over the image.
const MAX_BLOCKS: u32 = 2400;
/// A change is judged on at least this many blocks: on a few, some shift
/// fits by chance (a 7 x 5 image has one block).
const MIN_BLOCKS: usize = 16;
/// Shifts are tried in half pixels up to this many pixels each way.
const MAX_SHIFT: i32 = 2;
/// Scales are tried on a grid of 2^(k / `SCALE_STEPS`), k up to
/// `SCALE_REACH` each way (a factor of 1/3 to 3: a field of view of 40°
/// read as 80°, `fov-full-angle`, scales by 0.43), then sixteen times
/// finer around the best.
const SCALE_STEPS: f64 = 16.0;
const SCALE_REACH: i32 = 26;
/// A change is the geometry's when it explains at least this share of the
/// difference where it covers the image.
pub(crate) const GEOMETRY_SHARE: f64 = 0.8;
/// And where it covers the image lies at least this share of the whole
/// difference: a small central patch that happens to fit says nothing.
const COVERED_SHARE: f64 = 0.25;

/// How the student's image is the reference moved.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum Change {
    /// Moved by [dx, dy] pixels (right and down positive), in halves.
    Shift([f64; 2]),
    /// Scaled by this factor about the image's centre (above 1: larger).
    Scale(f64),
    Flip(Flip),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum Flip {
    /// Mirrored left to right.
    Horizontal,
    /// Upside down.
    Vertical,
    /// Both: turned half a turn.
    Both,
}

/// The change found, as the JSON's `geometry` says it.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct Geometry {
    #[serde(flatten)]
    pub(crate) change: Change,
    /// For a scale, the vertical field of view in degrees that gives it,
    /// to one decimal.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) fov: Option<f64>,
    /// 1 − D(yours, changed reference) / D(yours, reference) over the
    /// blocks the changed reference covers.
    pub(crate) explains: f64,
    /// What the student's image is, in words: "yours is the reference
    /// shifted 1 pixel right".
    #[serde(skip)]
    pub(crate) words: String,
}

/// What the student's image is, in words: "yours is the reference shifted
/// 1 pixel right", "... scaled by 0.781 about the centre, as a vertical
/// field of view of 50° gives (the scene's is 40°)".
fn words(change: Change, fov: Option<f64>, scene_fov: f64) -> String {
    let what = match change {
        Change::Shift([dx, dy]) => {
            let parts: Vec<String> = [(dx, "right", "left"), (dy, "down", "up")]
                .into_iter()
                .filter(|&(d, _, _)| d != 0.0)
                .map(|(d, plus, minus)| {
                    format!("{} {}", pixels(d.abs()), if d > 0.0 { plus } else { minus })
                })
                .collect();
            format!("shifted {}", parts.join(" and "))
        }
        Change::Scale(factor) => format!(
            "scaled by {factor:.3} about the centre, as a vertical field of view of {}° \
             gives (the scene's is {}°)",
            num(fov.unwrap_or(scene_fov)),
            num(scene_fov)
        ),
        Change::Flip(Flip::Horizontal) => "mirrored left to right".into(),
        Change::Flip(Flip::Vertical) => "upside down".into(),
        Change::Flip(Flip::Both) => "turned half a turn".into(),
    };
    format!("yours is the reference {what}")
}

/// "half a pixel", "1 pixel", "1.5 pixels".
fn pixels(d: f64) -> String {
    if d == 0.5 {
        "half a pixel".into()
    } else if d == 1.0 {
        "1 pixel".into()
    } else {
        format!("{d} pixels")
    }
}

/// The change of camera that brings the reference to `yours`, when one
/// explains at least `GEOMETRY_SHARE` of the difference. `fov` is the
/// scene's vertical field of view, to say a scale as one.
pub(crate) fn estimate(yours: &RgbImage, reference: &RgbImage, fov: f64) -> Option<Geometry> {
    let (share, change) = best_change(yours, reference)?;
    let scaled = match change {
        Change::Scale(f) => Some(scaled_fov(fov, f)),
        _ => None,
    };
    (share >= GEOMETRY_SHARE).then(|| Geometry {
        change,
        fov: scaled,
        explains: share,
        words: words(change, scaled, fov),
    })
}

/// The change that explains most of the difference, with its share.
fn best_change(yours: &RgbImage, reference: &RgbImage) -> Option<(f64, Change)> {
    let blocks = Blocks::new(yours, reference)?;
    let whole = blocks.whole_difference();
    if whole == 0.0 {
        return None;
    }
    let (right, bottom) = ((blocks.width - 1) as f64, (blocks.height - 1) as f64);
    let centre = (right / 2.0, bottom / 2.0);
    let scale = |f: f64| {
        move |x: f64, y: f64| (centre.0 + (x - centre.0) / f, centre.1 + (y - centre.1) / f)
    };
    let mut best: Option<(f64, Change)> = None;
    let mut consider = |change: Change, share: Option<f64>| {
        if let Some(share) = share
            && best.is_none_or(|(b, _)| share > b)
        {
            best = Some((share, change));
        }
    };
    for hx in -2 * MAX_SHIFT..=2 * MAX_SHIFT {
        for hy in -2 * MAX_SHIFT..=2 * MAX_SHIFT {
            if (hx, hy) != (0, 0) {
                let (dx, dy) = (hx as f64 / 2.0, hy as f64 / 2.0);
                let share = blocks.explained(whole, |x, y| (x - dx, y - dy));
                consider(Change::Shift([dx, dy]), share);
            }
        }
    }
    // The scale: the best on the coarse grid, then sixteen times finer
    // around it.
    let factor = |k: f64| (k / SCALE_STEPS).exp2();
    let coarse = (-SCALE_REACH..=SCALE_REACH)
        .filter(|&k| k != 0)
        .filter_map(|k| Some((blocks.explained(whole, scale(factor(k as f64)))?, k)))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((_, k)) = coarse {
        for j in -15..=15 {
            let f = factor(k as f64 + j as f64 / 16.0);
            let rounded = (f * 1000.0).round() / 1000.0;
            consider(Change::Scale(rounded), blocks.explained(whole, scale(f)));
        }
    }
    for (flip, source) in [
        (Flip::Horizontal, (true, false)),
        (Flip::Vertical, (false, true)),
        (Flip::Both, (true, true)),
    ] {
        let share = blocks.explained(whole, |x, y| {
            (
                if source.0 { right - x } else { x },
                if source.1 { bottom - y } else { y },
            )
        });
        consider(Change::Flip(flip), share);
    }
    best
}

/// The vertical field of view whose image is the one of `fov` scaled by
/// `factor` about the centre: tan(fov' / 2) = tan(fov / 2) / factor
/// (MODEL §2: a point's place on the image is its tangent over s), to one
/// decimal.
fn scaled_fov(fov: f64, factor: f64) -> f64 {
    let degrees = 2.0
        * ((fov.to_radians() / 2.0).tan() / factor)
            .atan()
            .to_degrees();
    (degrees * 10.0).round() / 10.0
}

/// The blocks compared: their places and the two images' means there.
struct Blocks {
    /// The reference's pixels as numbers, row by row, for sampling.
    reference: Vec<[f32; 3]>,
    width: u32,
    height: u32,
    /// Top-left pixel of each block compared.
    corners: Vec<(u32, u32)>,
    yours: Vec<[f32; 3]>,
    ours: Vec<[f32; 3]>,
}

impl Blocks {
    fn new(yours: &RgbImage, reference: &RgbImage) -> Option<Blocks> {
        let (width, height) = reference.dimensions();
        let (across, down) = (width / BLOCK, height / BLOCK);
        if across == 0 || down == 0 {
            return None;
        }
        // Every stride-th block each way, so that about MAX_BLOCKS remain.
        let stride = ((across * down).div_ceil(MAX_BLOCKS) as f64).sqrt().ceil() as usize;
        let corners: Vec<(u32, u32)> = (0..down)
            .step_by(stride)
            .flat_map(|by| {
                (0..across)
                    .step_by(stride)
                    .map(move |bx| (bx * BLOCK, by * BLOCK))
            })
            .collect();
        let means = |image: &RgbImage| -> Vec<[f32; 3]> {
            corners
                .iter()
                .map(|&(x0, y0)| block_mean(|x, y| image.get_pixel(x, y).0, x0, y0))
                .collect()
        };
        Some(Blocks {
            reference: reference.pixels().map(|p| p.0.map(f32::from)).collect(),
            width,
            height,
            yours: means(yours),
            ours: means(reference),
            corners,
        })
    }

    fn whole_difference(&self) -> f64 {
        self.yours
            .iter()
            .zip(&self.ours)
            .map(|(a, b)| apart(a, b))
            .sum()
    }

    /// The share of the difference that the reference, sampled at
    /// `source(x, y)` for each pixel (x, y) of yours, explains over the
    /// blocks it covers; `None` when those are too few or hold too little
    /// of the difference. `source` is affine, so a block whose four corner pixels
    /// land inside the reference lies inside.
    fn explained(&self, whole: f64, source: impl Fn(f64, f64) -> (f64, f64)) -> Option<f64> {
        let (right, bottom) = ((self.width - 1) as f64, (self.height - 1) as f64);
        let inside = |(x, y): (f64, f64)| (0.0..=right).contains(&x) && (0.0..=bottom).contains(&y);
        let last = (BLOCK - 1) as f64;
        let (mut before, mut after, mut blocks) = (0.0, 0.0, 0);
        for (i, &(x0, y0)) in self.corners.iter().enumerate() {
            let (x0, y0) = (x0 as f64, y0 as f64);
            if ![(0.0, 0.0), (last, 0.0), (0.0, last), (last, last)]
                .into_iter()
                .all(|(dx, dy)| inside(source(x0 + dx, y0 + dy)))
            {
                continue;
            }
            let mut sum = [0f32; 3];
            for dy in 0..BLOCK {
                for dx in 0..BLOCK {
                    let (sx, sy) = source(x0 + dx as f64, y0 + dy as f64);
                    let p = self.bilinear(sx.clamp(0.0, right), sy.clamp(0.0, bottom));
                    for c in 0..3 {
                        sum[c] += p[c];
                    }
                }
            }
            let n = (BLOCK * BLOCK) as f32;
            blocks += 1;
            before += apart(&self.yours[i], &self.ours[i]);
            after += apart(&self.yours[i], &sum.map(|s| s / n));
        }
        (blocks >= MIN_BLOCKS && before > 0.0 && before >= COVERED_SHARE * whole)
            .then(|| 1.0 - after / before)
    }

    /// The reference at (x, y) in pixel coordinates (pixel centres at
    /// whole numbers), between its four nearest pixels; (x, y) lies inside.
    fn bilinear(&self, x: f64, y: f64) -> [f32; 3] {
        let (x0, y0) = (x.floor() as u32, y.floor() as u32);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (fx, fy) = ((x - x0 as f64) as f32, (y - y0 as f64) as f32);
        let at = |x: u32, y: u32| self.reference[(y * self.width + x) as usize];
        let (a, b, c, d) = (at(x0, y0), at(x1, y0), at(x0, y1), at(x1, y1));
        std::array::from_fn(|k| {
            let top = a[k] + (b[k] - a[k]) * fx;
            let bottom = c[k] + (d[k] - c[k]) * fx;
            top + (bottom - top) * fy
        })
    }
}

/// The mean colour of the block whose top-left pixel is (x0, y0).
fn block_mean(pixel: impl Fn(u32, u32) -> [u8; 3], x0: u32, y0: u32) -> [f32; 3] {
    let mut sum = [0f32; 3];
    for y in y0..y0 + BLOCK {
        for x in x0..x0 + BLOCK {
            let p = pixel(x, y);
            for c in 0..3 {
                sum[c] += p[c] as f32;
            }
        }
    }
    sum.map(|s| s / (BLOCK * BLOCK) as f32)
}

/// The summed channel difference of two colours.
fn apart(a: &[f32; 3], b: &[f32; 3]) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).abs() as f64).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::render::render;
    use raystep_engine::trace::NoRecorder;
    use raystep_model::mistakes::{Mistake, Mistakes};

    /// A smooth pattern at (x, y), which may lie between pixels: waves of
    /// about 19 and 25 pixels, unlike in each channel.
    fn pattern(x: f64, y: f64) -> image::Rgb<u8> {
        let wave = |v: f64| (128.0 + 90.0 * v).round() as u8;
        image::Rgb([
            wave((x / 3.0).sin() * (y / 4.0).cos()),
            wave((x / 4.0 + y / 5.0).sin()),
            wave((y / 3.5).cos()),
        ])
    }

    #[test]
    fn a_half_pixel_shift_of_a_smooth_image_is_found() {
        // Yours is the pattern half a pixel right and one pixel up:
        // yours(x, y) = reference(x − 0.5, y + 1). Between samples 19
        // pixels apart a bilinear half step is off by about 1% of the wave,
        // so the shift explains nearly all of the difference.
        let reference = RgbImage::from_fn(64, 48, |x, y| pattern(x as f64, y as f64));
        let yours = RgbImage::from_fn(64, 48, |x, y| pattern(x as f64 - 0.5, y as f64 + 1.0));
        let found = estimate(&yours, &reference, 40.0).expect("a shift");
        assert_eq!(found.change, Change::Shift([0.5, -1.0]));
        assert!(found.explains > 0.9, "{}", found.explains);
        assert_eq!(
            found.words,
            "yours is the reference shifted half a pixel right and 1 pixel up"
        );
    }

    #[test]
    fn a_flip_is_exact_and_a_colour_change_is_no_geometry() {
        let reference = RgbImage::from_fn(64, 48, |x, y| pattern(x as f64, y as f64));
        let mirrored = RgbImage::from_fn(64, 48, |x, y| *reference.get_pixel(63 - x, 47 - y));
        let found = estimate(&mirrored, &reference, 40.0).expect("a flip");
        assert_eq!(found.change, Change::Flip(Flip::Both));
        assert_eq!(found.explains, 1.0);
        // Every channel 20 steps darker: no move of the image gives that.
        let darker = RgbImage::from_fn(64, 48, |x, y| {
            image::Rgb(reference.get_pixel(x, y).0.map(|c| c.saturating_sub(20)))
        });
        assert!(estimate(&darker, &reference, 40.0).is_none());
        // An image of 12 x 8 pixels holds 6 blocks, too few to judge by.
        let small = RgbImage::from_fn(12, 8, |x, y| pattern(x as f64, y as f64));
        let flipped = RgbImage::from_fn(12, 8, |x, y| *small.get_pixel(11 - x, 7 - y));
        assert!(estimate(&flipped, &small, 40.0).is_none());
    }

    #[test]
    fn a_scale_is_said_as_the_field_of_view_that_gives_it() {
        // MODEL §2: a point at angle θ from the axis lands at tan θ / s on
        // the image, s = tan(fov / 2). A fov of 50 where the scene says 40
        // scales the image by tan 20° / tan 25° = 0.36397 / 0.46631 =
        // 0.78053, and back: tan(fov' / 2) = tan 20° / 0.78053 = tan 25°.
        let factor = 20f64.to_radians().tan() / 25f64.to_radians().tan();
        assert!((factor - 0.78053).abs() < 1e-5);
        assert_eq!(scaled_fov(40.0, factor), 50.0);
        assert_eq!(
            words(Change::Scale(0.781), Some(50.0), 40.0),
            "yours is the reference scaled by 0.781 about the centre, as a vertical field of \
             view of 50° gives (the scene's is 40°)"
        );
        assert_eq!(
            words(Change::Shift([-1.5, 0.0]), None, 40.0),
            "yours is the reference shifted 1.5 pixels left"
        );
        assert_eq!(
            words(Change::Flip(Flip::Horizontal), None, 40.0),
            "yours is the reference mirrored left to right"
        );
    }

    #[test]
    fn only_the_cameras_mistakes_read_as_geometry() {
        // glass.toml at 80 x 60 under each mistake of the catalogue: one
        // that changes the shading or the bytes is no change of camera;
        // flipped-y is the image upside down; pixel-corner (half a pixel
        // right and down) and fov-full-angle (a wider view) are told as
        // such or not at all.
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join("scenes/glass.toml");
        let scene = raystep_engine::scene::load(&path)
            .unwrap()
            .with_size(80, 60)
            .unwrap();
        let image = |mistakes: Mistakes| {
            let mut settings = scene.settings;
            settings.mistakes = mistakes;
            render::<NoRecorder>(&scene, &settings, &|| {}).0
        };
        let reference = image(Mistakes::NONE);
        for mistake in Mistake::ALL {
            let found = estimate(
                &image(Mistakes::NONE.with(mistake)),
                &reference,
                scene.camera.fov,
            )
            .map(|g| g.change);
            match mistake {
                Mistake::FlippedY => assert_eq!(found, Some(Change::Flip(Flip::Vertical))),
                Mistake::PixelCorner => {
                    assert!(
                        found.is_none_or(|c| c == Change::Shift([0.5, 0.5])),
                        "{found:?}"
                    )
                }
                Mistake::FovFullAngle => assert!(
                    found.is_none_or(|c| matches!(c, Change::Scale(f) if f < 1.0)),
                    "{found:?}"
                ),
                _ => assert_eq!(found, None, "{mistake}"),
            }
        }
    }
}
