//! How far two images of the same size are apart: the mean absolute error,
//! NVIDIA's FLIP where the build has it (`flip`), the share of pixels past
//! a tolerance, the worst pixel, and which differences are smaller than a
//! pixel (`sub_pixel`), which the match rule allows.

use anyhow::Result;
use image::{GrayImage, RgbImage};
use serde::Serialize;

use std::sync::Arc;

use rayon::prelude::*;

use super::sub_pixel;

/// A channel may differ by this many 8-bit steps before a pixel counts as
/// different (mental ray's imf_diff counts the same way): another correct
/// tracer rounds differently in the last bit, and a student's byte
/// conversion may differ by one step.
pub(crate) const TOLERANCE_STEPS: u8 = 3;
/// The images match when at most this share of pixels is past the
/// tolerance: an independent correct tracer differs on a few pixels where a
/// ray grazes an edge or a shadow boundary, which must still match.
pub(crate) const MATCH_SHARE: f64 = 0.001;
/// And no pixel of a match has a channel more than this many steps apart
/// (unless its value lies within the reference's around it: `sub_pixel`):
/// an eighth of the range, more than rounding or float precision moves a
/// correct tracer's pixel, less than a classic mistake moves the pixels it
/// touches (a wrapped byte by about 255). So six wrapped bytes, well under
/// `MATCH_SHARE`, still make the images differ.
pub(crate) const MATCH_GAP: u8 = 32;
/// At most this many pixels past `MATCH_GAP` are listed.
const FAR_OFF_LISTED: usize = 8;

/// The match rule's settings. `compare` uses the defaults; an assignment
/// may change each for all its scenes or for one (docs/TEACHERS.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MatchRule {
    /// A channel may differ by this many steps of 255 before a pixel
    /// counts as different (`TOLERANCE_STEPS`; more for lossy images).
    pub(crate) tolerance_steps: u8,
    /// How many far-off pixels a match allows: past `MATCH_GAP` and not
    /// within reach of the reference's values around them.
    pub far_off_allowed: usize,
    /// Whether anti-aliased edges (blends, `sub_pixel`) match.
    pub antialiasing: bool,
    /// CSE 167's pass rule in place of all the above but the tolerance:
    /// at most this many hot pixels (a channel more than the tolerance
    /// apart), none excused (docs/TEACHERS.md).
    pub hot_pixels_allowed: Option<usize>,
}

impl Default for MatchRule {
    fn default() -> Self {
        MatchRule {
            tolerance_steps: TOLERANCE_STEPS,
            far_off_allowed: 0,
            antialiasing: true,
            hot_pixels_allowed: None,
        }
    }
}

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
    /// The rule's tolerance, in steps / 255.
    pub(crate) tolerance: f64,
    pub(crate) worst: Option<PixelPair>,
    /// How many pixels have a channel more than `MATCH_GAP` steps apart
    /// and are neither within reach nor an accepted blend: those a match
    /// allows `far_off_allowed` of.
    pub(crate) far_off_pixels: usize,
    /// The first of them in row-major order, at most `FAR_OFF_LISTED`.
    pub(crate) far_off: Vec<PixelPair>,
    /// Of the pixels past the tolerance, how many lie within reach of the
    /// reference's values around them (`sub_pixel`): an edge moved by less
    /// than a pixel. None of them is far off.
    pub(crate) sub_pixel_pixels: usize,
    /// Of the pixels past the tolerance, how many are accepted as
    /// anti-aliased edges (blends, `sub_pixel`): they count for nothing.
    /// Looked for only when the image would not match without them.
    pub(crate) anti_aliased_pixels: usize,
    /// Of the pixels past the tolerance, how many lie on an edge through
    /// their centre, either side of which is right (`sub_pixel::on_edge`):
    /// they count for nothing. Looked for only when the image would not
    /// match without them. None of them is anti-aliased too.
    pub(crate) on_edge_pixels: usize,
    /// The shift of the edges estimated from the pixels past the tolerance
    /// (`sub_pixel::shift`), in pixels (right, down) to three decimals,
    /// when blends were looked for and the pixels show gradients to fit:
    /// at `MAX_BLEND_SHIFT` or more no blend is accepted.
    pub(crate) edge_shift: Option<[f64; 2]>,
    /// The rule's other settings.
    pub(crate) far_off_allowed: usize,
    pub(crate) antialiasing: bool,
    /// Under the hot-pixel rule only: how many pixels are hot (past the
    /// tolerance), and how many a match allows.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) hot_pixels: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) hot_pixels_allowed: Option<usize>,
    /// How many pixels are past the tolerance, of how many.
    #[serde(skip)]
    pub(crate) over_pixels: usize,
    #[serde(skip)]
    pub(crate) pixels: usize,
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
        if let Some(allowed) = self.hot_pixels_allowed {
            return self.over_pixels <= allowed;
        }
        self.few_over_tolerance() && self.far_off_pixels <= self.far_off_allowed
    }

    /// Whether the share rule alone would call it a match: the pixels past
    /// the tolerance, but for those accepted as anti-aliased, at most
    /// `MATCH_SHARE`.
    pub(crate) fn few_over_tolerance(&self) -> bool {
        self.counted_share() <= MATCH_SHARE
    }

    /// The share of pixels past the tolerance that counts: all but the
    /// anti-aliased ones and those on an edge through their centre.
    pub(crate) fn counted_share(&self) -> f64 {
        (self.over_pixels - self.excused_pixels()) as f64 / self.pixels.max(1) as f64
    }

    /// How many pixels past the tolerance count for nothing: anti-aliased,
    /// or on an edge through their centre.
    pub(crate) fn excused_pixels(&self) -> usize {
        self.anti_aliased_pixels + self.on_edge_pixels
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

/// Whether each pixel differs past `tolerance` steps, as a mask (255 differs).
pub(crate) fn over_tolerance(yours: &RgbImage, reference: &RgbImage, tolerance: u8) -> GrayImage {
    GrayImage::from_fn(yours.width(), yours.height(), |x, y| {
        let gap = channel_gap(yours.get_pixel(x, y).0, reference.get_pixel(x, y).0);
        image::Luma([if gap > tolerance { 255 } else { 0 }])
    })
}

/// What the scene shows inside a pixel besides the reference's one ray
/// through its centre (`sub_pixel`): asked for only when an image would
/// not match without it.
pub(crate) trait InsidePixels {
    /// raystep's render at twice the size: each pixel's quarter points.
    fn fine(&self) -> Arc<RgbImage>;
    /// What raystep's rays `sub_pixel::BESIDE_CENTRE` from pixel (x, y)'s
    /// centre see.
    fn beside_centre(&self, x: u32, y: u32) -> [[u8; 3]; 4];
}

/// Measures `yours` against `reference` (same size) by `rule`; also gives
/// FLIP's error map in its magma colours where the build has FLIP. `inside`
/// gives what the scene shows inside a pixel, asked for only when pixels
/// on edges are looked for. An error when the memory FLIP needs cannot be
/// had.
pub(crate) fn measure(
    yours: &RgbImage,
    reference: &RgbImage,
    rule: &MatchRule,
    inside: &(dyn InsidePixels + Sync),
) -> Result<(Metrics, Option<RgbImage>)> {
    let (width, height) = yours.dimensions();
    let pixels = width as usize * height as usize;
    let tolerance = rule.tolerance_steps;
    let mut sum = 0u64;
    let mut worst: Option<(u8, u32, u32)> = None;
    // The pixels past the tolerance (row-major indices), and whether each
    // is within reach of the reference's values around it.
    let mut over: Vec<(u32, bool)> = Vec::new();
    for (x, y, p) in yours.enumerate_pixels() {
        let (a, b) = (p.0, reference.get_pixel(x, y).0);
        sum += (0..3).map(|c| a[c].abs_diff(b[c]) as u64).sum::<u64>();
        let gap = channel_gap(a, b);
        if gap > tolerance {
            let reach = sub_pixel::within_reach(reference, x, y, a, tolerance);
            over.push((y * width + x, reach));
        }
        if gap > 0 && worst.is_none_or(|(g, _, _)| gap > g) {
            worst = Some((gap, x, y));
        }
    }
    let pair = |index: u32| {
        let (x, y) = (index % width, index / width);
        PixelPair {
            pixel: [x, y],
            yours: yours.get_pixel(x, y).0,
            reference: reference.get_pixel(x, y).0,
        }
    };
    let far = |index: u32| {
        let p = pair(index);
        channel_gap(p.yours, p.reference) > MATCH_GAP
    };
    let far_off_within = |excused: &dyn Fn(usize) -> bool| -> Vec<u32> {
        (over.iter().enumerate())
            .filter(|&(i, &(index, reach))| !reach && !excused(i) && far(index))
            .map(|(_, &(index, _))| index)
            .collect()
    };
    let mut far_off = far_off_within(&|_| false);
    let share_matches = over.len() as f64 <= MATCH_SHARE * pixels as f64;
    let (mut on_edge, mut anti_aliased, mut edge_shift) = (vec![false; over.len()], 0, None);
    // Edges through pixels' centres lie along lines of centres (a horizon
    // on a row): more pixels over than the share plus two whole rows and
    // two whole columns are not looked at, which they could not excuse.
    let lines = 2 * (width as usize + height as usize);
    let could_excuse = over.len() as f64 <= MATCH_SHARE * pixels as f64 + lines as f64;
    // The hot-pixel rule excuses no pixel: nothing to look for.
    let hot_rule = rule.hot_pixels_allowed.is_some();
    if !hot_rule && could_excuse && !(share_matches && far_off.len() <= rule.far_off_allowed) {
        // Four rays a pixel, for the pixels past the tolerance only.
        on_edge = (over.par_iter())
            .map(|&(index, _)| {
                let (x, y) = (index % width, index / width);
                let mine = yours.get_pixel(x, y).0;
                let beside = inside.beside_centre(x, y);
                sub_pixel::on_edge(reference, x, y, beside, mine, tolerance)
            })
            .collect();
        far_off = far_off_within(&|i| on_edge[i]);
    }
    let on_edge_pixels = on_edge.iter().filter(|&&e| e).count();
    let share_matches = (over.len() - on_edge_pixels) as f64 <= MATCH_SHARE * pixels as f64;
    if !hot_rule && rule.antialiasing && !(share_matches && far_off.len() <= rule.far_off_allowed) {
        // Blends are accepted only when the edges did not all move one way
        // (pixels on an edge through their centre moved no way: left out).
        let indices: Vec<u32> = (over.iter().zip(&on_edge))
            .filter(|&(_, &edge)| !edge)
            .map(|(&(index, _), _)| index)
            .collect();
        let shift = sub_pixel::shift(yours, reference, &indices);
        edge_shift = shift.map(|s| s.map(|v| (v * 1000.0).round() / 1000.0));
        if shift.is_none_or(|[sx, sy]| sx.hypot(sy) < sub_pixel::MAX_BLEND_SHIFT) {
            let fine = inside.fine();
            let blends: Vec<bool> = (over.iter().zip(&on_edge))
                .map(|(&(index, _), &edge)| {
                    let (x, y) = (index % width, index / width);
                    let mine = yours.get_pixel(x, y).0;
                    !edge && sub_pixel::blend(reference, &fine, x, y, mine, tolerance)
                })
                .collect();
            anti_aliased = blends.iter().filter(|&&b| b).count();
            far_off = far_off_within(&|i| blends[i] || on_edge[i]);
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
        mean_abs: sum as f64 / (3.0 * 255.0 * pixels as f64),
        flip_mean,
        pixels_over_tolerance: over.len() as f64 / pixels as f64,
        tolerance: f64::from(tolerance) / 255.0,
        worst: worst.map(|(_, x, y)| pair(y * width + x)),
        far_off_pixels: far_off.len(),
        far_off: far_off
            .iter()
            .take(FAR_OFF_LISTED)
            .map(|&i| pair(i))
            .collect(),
        sub_pixel_pixels: over.iter().filter(|&&(_, reach)| reach).count(),
        anti_aliased_pixels: anti_aliased,
        on_edge_pixels,
        edge_shift,
        far_off_allowed: rule.far_off_allowed,
        antialiasing: rule.antialiasing,
        hot_pixels: rule.hot_pixels_allowed.map(|_| over.len()),
        hot_pixels_allowed: rule.hot_pixels_allowed,
        over_pixels: over.len(),
        pixels,
    };
    Ok((metrics, error_map))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each pixel of `image` four times, 2 x 2: a scene flat inside each
    /// pixel rendered at twice the size.
    fn doubled(image: &RgbImage) -> Arc<RgbImage> {
        Arc::new(RgbImage::from_fn(
            image.width() * 2,
            image.height() * 2,
            |x, y| *image.get_pixel(x / 2, y / 2),
        ))
    }

    /// A scene flat inside each pixel: the reference's value everywhere in it.
    struct Flat<'a>(&'a RgbImage);

    impl InsidePixels for Flat<'_> {
        fn fine(&self) -> Arc<RgbImage> {
            doubled(self.0)
        }

        fn beside_centre(&self, x: u32, y: u32) -> [[u8; 3]; 4] {
            [self.0.get_pixel(x, y).0; 4]
        }
    }

    /// `measure` by the default rule, the scene flat inside each pixel.
    fn measure(yours: &RgbImage, reference: &RgbImage) -> Result<(Metrics, Option<RgbImage>)> {
        super::measure(yours, reference, &MatchRule::default(), &Flat(reference))
    }

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

#[cfg(test)]
mod sub_pixel_tests {
    use super::*;

    /// A disc of radius 9 (bright, 230) about (20, 20) on a dark ground (30),
    /// sampled at (u, v) in pixel units.
    fn disc(u: f64, v: f64) -> image::Rgb<u8> {
        let inside = (u - 20.0).hypot(v - 20.0) < 9.0;
        image::Rgb([if inside { 230 } else { 30 }; 3])
    }

    /// The disc at 40 x 40 with rays through `offset` of each pixel, and at
    /// 80 x 80 through the centres (raystep's render at twice the size).
    fn sampled(offset: f64) -> (RgbImage, Arc<RgbImage>) {
        let image = RgbImage::from_fn(40, 40, |x, y| disc(x as f64 + offset, y as f64 + offset));
        let fine = RgbImage::from_fn(80, 80, |x, y| {
            disc((x as f64 + 0.5) / 2.0, (y as f64 + 0.5) / 2.0)
        });
        (image, Arc::new(fine))
    }

    /// The disc as raystep sees it: rays through each pixel's quarter
    /// points and a hair beside its centre.
    struct Disc(Arc<RgbImage>);

    impl InsidePixels for Disc {
        fn fine(&self) -> Arc<RgbImage> {
            Arc::clone(&self.0)
        }

        fn beside_centre(&self, x: u32, y: u32) -> [[u8; 3]; 4] {
            sub_pixel::BESIDE_CENTRE
                .map(|(du, dv)| disc(x as f64 + 0.5 + du, y as f64 + 0.5 + dv).0)
        }
    }

    fn measured(yours: &RgbImage, rule: MatchRule) -> Metrics {
        let (reference, fine) = sampled(0.5);
        measure(yours, &reference, &rule, &Disc(fine)).unwrap().0
    }

    #[test]
    fn a_silhouette_pixel_that_takes_its_neighbours_colour_still_matches() {
        // Issue 40: the eye moved by 1e-5 turns one silhouette pixel from
        // the disc's to the ground's colour, 200 steps apart: far off by
        // the old rule, which allowed none. (19, 11) is inside (its centre
        // lies 8.5 from (20, 20)), its neighbour (19, 10) outside (9.5).
        let (reference, _) = sampled(0.5);
        assert_eq!(reference.get_pixel(19, 11).0, [230; 3]);
        assert_eq!(reference.get_pixel(19, 10).0, [30; 3]);
        let mut moved = reference.clone();
        moved.put_pixel(19, 11, image::Rgb([30; 3]));
        let rule = MatchRule::default();
        let metrics = measured(&moved, rule);
        assert_eq!(metrics.sub_pixel_pixels, 1);
        assert_eq!(metrics.far_off_pixels, 0);
        assert_eq!(metrics.anti_aliased_pixels, 0);
        assert!(metrics.matches());
        // A value no pixel around shows (a wrapped byte: 230 + 40 = 14)
        // is far off, on a silhouette or not.
        moved.put_pixel(19, 11, image::Rgb([14, 230, 230]));
        let metrics = measured(&moved, rule);
        assert_eq!((metrics.sub_pixel_pixels, metrics.far_off_pixels), (0, 1));
        assert!(!metrics.matches());
        // Unless the assignment allows one far-off pixel.
        let lenient = MatchRule {
            far_off_allowed: 1,
            ..rule
        };
        assert!(measured(&moved, lenient).matches());
    }

    /// A horizon: sky (20, 30, 60) above v = 10.5, ground (34, 31, 23)
    /// from it down, on a 40 x 21 image: row 10's centres lie on it, and
    /// raystep's rays through them see the ground (10.5 is not above).
    struct Horizon;

    impl Horizon {
        fn at(v: f64) -> [u8; 3] {
            if v < 10.5 { [20, 30, 60] } else { [34, 31, 23] }
        }

        fn image(row_ten: [u8; 3]) -> RgbImage {
            RgbImage::from_fn(40, 21, |_, y| {
                image::Rgb(if y == 10 {
                    row_ten
                } else {
                    Self::at(y as f64 + 0.5)
                })
            })
        }
    }

    impl InsidePixels for Horizon {
        fn fine(&self) -> Arc<RgbImage> {
            Arc::new(RgbImage::from_fn(80, 42, |_, y| {
                image::Rgb(Self::at((y as f64 + 0.5) / 2.0))
            }))
        }

        fn beside_centre(&self, _: u32, y: u32) -> [[u8; 3]; 4] {
            sub_pixel::BESIDE_CENTRE.map(|(_, dv)| Self::at(y as f64 + 0.5 + dv))
        }
    }

    #[test]
    fn a_row_of_centres_on_the_horizon_may_show_either_side() {
        // Issue 40: a level camera's middle row on an endless floor's
        // horizon; an eye 1e-5 higher turns the whole row from ground to
        // sky. 40 pixels of 840 (4.8%) past the tolerance, 37 steps apart
        // in blue: the share rule refused it. Rays 0.001 above and below
        // each centre see sky and ground: on an edge through the centre,
        // either value is right.
        let reference = Horizon::image(Horizon::at(10.5));
        assert_eq!(reference.get_pixel(0, 10).0, [34, 31, 23]);
        let sky = Horizon::image([20, 30, 60]);
        let rule = MatchRule::default();
        let metrics = measure(&sky, &reference, &rule, &Horizon).unwrap().0;
        assert_eq!((metrics.over_pixels, metrics.on_edge_pixels), (40, 40));
        assert_eq!(
            (metrics.far_off_pixels, metrics.anti_aliased_pixels),
            (0, 0)
        );
        assert!(metrics.matches());
        // A value outside both sides is no rounding: (20, 30, 70) is 10
        // bluer than the sky, past the tolerance of 3.
        let bluer = Horizon::image([20, 30, 70]);
        let metrics = measure(&bluer, &reference, &rule, &Horizon).unwrap().0;
        assert_eq!(metrics.on_edge_pixels, 0);
        assert!(!metrics.matches());
        // Nor is the sky on row 11, whose centres (11.5) lie a whole pixel
        // below the horizon: the rays beside them all see the ground.
        let mut lowered = reference.clone();
        for x in 0..40 {
            lowered.put_pixel(x, 11, image::Rgb([20, 30, 60]));
        }
        let metrics = measure(&lowered, &reference, &rule, &Horizon).unwrap().0;
        assert_eq!((metrics.over_pixels, metrics.on_edge_pixels), (40, 0));
        assert!(!metrics.matches());
    }

    #[test]
    fn the_hot_pixel_rule_counts_every_pixel_past_the_tolerance() {
        // The horizon's row of centres: 40 pixels past the tolerance, all
        // on an edge through their centre, which the match rule excuses.
        // CSE 167's rule excuses none: 40 hot pixels, a match when the
        // assignment allows 40 and not 39.
        let reference = Horizon::image(Horizon::at(10.5));
        let sky = Horizon::image([20, 30, 60]);
        let rule = |allowed| MatchRule {
            hot_pixels_allowed: Some(allowed),
            ..MatchRule::default()
        };
        let metrics = measure(&sky, &reference, &rule(39), &Horizon).unwrap().0;
        assert_eq!((metrics.hot_pixels, metrics.on_edge_pixels), (Some(40), 0));
        assert!(!metrics.matches());
        assert!(
            measure(&sky, &reference, &rule(40), &Horizon)
                .unwrap()
                .0
                .matches()
        );
        // A channel 3 steps off is within the tolerance, not hot; 4 is hot,
        // however few: one pixel of 840 (0.12%, past the share of 0.1%)
        // with blue 64 for 60 fails at 0 allowed.
        let mut near = reference.clone();
        near.put_pixel(5, 2, image::Rgb([20, 30, 63]));
        let metrics = measure(&near, &reference, &rule(0), &Horizon).unwrap().0;
        assert_eq!(metrics.hot_pixels, Some(0));
        assert!(metrics.matches());
        near.put_pixel(5, 2, image::Rgb([20, 30, 64]));
        let metrics = measure(&near, &reference, &rule(0), &Horizon).unwrap().0;
        assert_eq!(metrics.hot_pixels, Some(1));
        assert!(!metrics.matches());
        // The match rule says nothing of hot pixels in its JSON.
        let plain = measure(&near, &reference, &MatchRule::default(), &Horizon)
            .unwrap()
            .0;
        let json = serde_json::to_value(&plain).unwrap();
        assert!(json.get("hot_pixels").is_none() && json.get("hot_pixels_allowed").is_none());
    }

    /// The disc averaged over 2 x 2 rays a pixel, through its quarter points
    /// (the fine render's pixels), rounded.
    fn anti_aliased() -> RgbImage {
        let (_, fine) = sampled(0.5);
        RgbImage::from_fn(40, 40, |x, y| {
            let sum: u32 = [(0, 0), (1, 0), (0, 1), (1, 1)]
                .iter()
                .map(|&(i, j)| u32::from(fine.get_pixel(2 * x + i, 2 * y + j).0[0]))
                .sum();
            image::Rgb([((sum + 2) / 4) as u8; 3])
        })
    }

    #[test]
    fn anti_aliased_edges_match_unless_the_rule_refuses_them() {
        let yours = anti_aliased();
        let (reference, _) = sampled(0.5);
        // Every pixel whose four rays do not all agree with its centre's
        // differs, by 50 steps at least (a quarter of 200): many more than
        // the 0.1% of 1,600 pixels (1.6) a match allows.
        let over: usize = (0..40)
            .flat_map(|y| (0..40).map(move |x| (x, y)))
            .filter(|&(x, y)| channel_gap(yours.get_pixel(x, y).0, reference.get_pixel(x, y).0) > 3)
            .count();
        assert!(over > 20, "{over}");
        let metrics = measured(&yours, MatchRule::default());
        assert_eq!(metrics.over_pixels, over);
        // Each lies between its own rays' values: all blends.
        assert_eq!(metrics.anti_aliased_pixels, over);
        // A disc blends evenly all round: no shift.
        let [sx, sy] = metrics.edge_shift.unwrap();
        assert!(sx.hypot(sy) < 0.1, "({sx}, {sy})");
        assert!(metrics.matches());
        // Refused by the rule, they count as before.
        let strict = MatchRule {
            antialiasing: false,
            ..MatchRule::default()
        };
        let metrics = measured(&yours, strict);
        assert_eq!((metrics.anti_aliased_pixels, metrics.edge_shift), (0, None));
        assert!(!metrics.matches());
    }

    #[test]
    fn an_image_moved_half_a_pixel_is_no_anti_aliasing() {
        // pixel-corner: rays through each pixel's top-left corner, the disc
        // moved half a pixel right and down. Its edge pixels take values
        // the scene shows right there, as blends do, but all moved one
        // way: the shift found is down and right, past half a pixel.
        let (corner, _) = sampled(0.0);
        let metrics = measured(&corner, MatchRule::default());
        let [sx, sy] = metrics.edge_shift.unwrap();
        assert!(sx > 0.5 && sy > 0.5, "({sx}, {sy})");
        assert_eq!(metrics.anti_aliased_pixels, 0);
        assert!(!metrics.matches());
    }
}
