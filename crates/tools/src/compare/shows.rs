//! What the student's image shows outside the catalogue of mistakes: the
//! reference with its channels swapped, times a constant factor, different
//! only along edges (anti-aliased?), or with small noise everywhere
//! (compression). Each is said only where it holds: the first three by the
//! match rule or all but a few edge pixels, the noise by its size and by
//! averaging out block by block.

use image::RgbImage;
use serde::Serialize;

use super::metrics::{MATCH_GAP, TOLERANCE_STEPS, channel_gap, reproduces};
use super::reference::Reference;

/// The differences lie along edges when at least this share of the
/// differing pixels are on edges...
const ON_EDGES: f64 = 0.95;
/// ...both brighter and darker, each at least this share (averaging
/// brightens the dark side of an edge and darkens the bright side; a
/// highlight times the object's colour only darkens)...
const BOTH_WAYS: f64 = 0.2;
/// ...and they are at most this share of all pixels (a moved or wrong
/// image differs inside its objects too).
const EDGES_AT_MOST: f64 = 0.15;
/// Noise: no pixel past `MATCH_GAP`, most pixels differ, and each 16 x 16
/// block's mean differs by at most this many steps in every channel.
const NOISE_BLOCK_STEPS: f64 = 2.0;
const NOISE_BLOCK: u32 = 16;
/// A constant factor is named only when it is at least this far from 1.
const FACTOR_FROM_ONE: f64 = 0.02;

/// What the image shows, as the JSON's `shows` says it.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct Shows {
    /// "channels-swapped", "constant-factor", "edges-only" or "noise".
    pub(crate) kind: &'static str,
    /// In words, for the student.
    pub(crate) words: String,
}

/// What `yours` shows against the reference, the first that holds.
/// Differences along edges are not looked for when the image is moved
/// (`moved`: a shift of half a pixel also differs along edges only).
pub(crate) fn shows(yours: &RgbImage, reference: &Reference, moved: bool) -> Option<Shows> {
    swapped(yours, &reference.image)
        .or_else(|| factor(yours, &reference.image))
        .or_else(|| (!moved).then(|| edges_only(yours, reference)).flatten())
        .or_else(|| noise(yours, &reference.image))
}

fn swapped(yours: &RgbImage, reference: &RgbImage) -> Option<Shows> {
    const ORDERS: [[usize; 3]; 5] = [[0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
    let names = ["R", "G", "B"];
    ORDERS.into_iter().find_map(|order| {
        let permuted = RgbImage::from_fn(reference.width(), reference.height(), |x, y| {
            let p = reference.get_pixel(x, y).0;
            image::Rgb([p[order[0]], p[order[1]], p[order[2]]])
        });
        (permuted != *reference && reproduces(yours, &permuted)).then(|| Shows {
            kind: "channels-swapped",
            words: format!(
                "channels swapped: yours is the reference with its channels in the order {}, {}, {} (check the order you write the bytes in)",
                names[order[0]], names[order[1]], names[order[2]]
            ),
        })
    })
}

fn factor(yours: &RgbImage, reference: &RgbImage) -> Option<Shows> {
    // The least-squares k of yours ≈ k × reference, over unclamped channels.
    let (mut yr, mut rr) = (0f64, 0f64);
    for (a, b) in yours.pixels().zip(reference.pixels()) {
        for k in 0..3 {
            if a.0[k] < 255 && b.0[k] < 255 {
                yr += f64::from(a.0[k]) * f64::from(b.0[k]);
                rr += f64::from(b.0[k]) * f64::from(b.0[k]);
            }
        }
    }
    if rr == 0.0 {
        return None;
    }
    let k = yr / rr;
    if (k - 1.0).abs() < FACTOR_FROM_ONE {
        return None;
    }
    let scaled = RgbImage::from_fn(reference.width(), reference.height(), |x, y| {
        let p = reference.get_pixel(x, y).0;
        image::Rgb(p.map(|c| (f64::from(c) * k).round().clamp(0.0, 255.0) as u8))
    });
    reproduces(yours, &scaled).then(|| Shows {
        kind: "constant-factor",
        words: format!(
            "a constant factor: yours is the reference times {k:.2} in every channel (a scale applied to every colour, or to the bytes?)"
        ),
    })
}

fn edges_only(yours: &RgbImage, reference: &Reference) -> Option<Shows> {
    let image = &reference.image;
    let (width, height) = image.dimensions();
    // Whether yours lies, in every channel, within the reference's values
    // around the pixel (3 x 3): what averaging rays over the pixel gives.
    let between = |x: u32, y: u32, mine: [u8; 3]| {
        (0..3).all(|k| {
            let values = (y.saturating_sub(1)..=(y + 1).min(height - 1)).flat_map(|ny| {
                (x.saturating_sub(1)..=(x + 1).min(width - 1))
                    .map(move |nx| image.get_pixel(nx, ny).0[k])
            });
            let (low, high) = values.fold((255u8, 0u8), |(l, h), v| (l.min(v), h.max(v)));
            mine[k].saturating_add(TOLERANCE_STEPS) >= low
                && mine[k] <= high.saturating_add(TOLERANCE_STEPS)
        })
    };
    let (mut differing, mut edged, mut brighter) = (0usize, 0usize, 0usize);
    for (x, y, p) in yours.enumerate_pixels() {
        let r = image.get_pixel(x, y).0;
        if channel_gap(p.0, r) > TOLERANCE_STEPS {
            differing += 1;
            edged += usize::from(between(x, y, p.0));
            let sum = |c: [u8; 3]| c.iter().map(|&v| u32::from(v)).sum::<u32>();
            brighter += usize::from(sum(p.0) > sum(r));
        }
    }
    let all = (width as usize) * (height as usize);
    let darker = differing - brighter;
    (differing > 0
        && edged as f64 >= ON_EDGES * differing as f64
        && brighter.min(darker) as f64 >= BOTH_WAYS * differing as f64
        && differing as f64 <= EDGES_AT_MOST * all as f64)
        .then(|| Shows {
            kind: "edges-only",
            words: format!(
                "differences only along edges ({edged} of {differing} differing pixels lie between the values of their neighbours in raystep's image, as averaging several rays a pixel gives): anti-aliased? raystep traces one ray through each pixel's centre (MODEL §2)"
            ),
        })
}

fn noise(yours: &RgbImage, reference: &RgbImage) -> Option<Shows> {
    let (width, height) = yours.dimensions();
    let mut differing = 0usize;
    for (a, b) in yours.pixels().zip(reference.pixels()) {
        let gap = channel_gap(a.0, b.0);
        if gap > MATCH_GAP {
            return None;
        }
        differing += usize::from(gap > TOLERANCE_STEPS);
    }
    if differing * 4 < (width * height) as usize {
        return None;
    }
    // The mean signed difference of each block, in every channel.
    let across = width.div_ceil(NOISE_BLOCK);
    let blocks = (across * height.div_ceil(NOISE_BLOCK)) as usize;
    let mut sums = vec![([0i64; 3], 0i64); blocks];
    for (x, y, p) in yours.enumerate_pixels() {
        let r = reference.get_pixel(x, y).0;
        let (sum, n) = &mut sums[((y / NOISE_BLOCK) * across + x / NOISE_BLOCK) as usize];
        for k in 0..3 {
            sum[k] += i64::from(p.0[k]) - i64::from(r[k]);
        }
        *n += 1;
    }
    sums.iter()
        .filter(|(_, n)| *n >= 64)
        .all(|(sum, n)| sum.iter().all(|s| (*s as f64 / *n as f64).abs() <= NOISE_BLOCK_STEPS))
        .then(|| Shows {
            kind: "noise",
            words: format!(
                "noise: {differing} pixels differ a little, none by more than {MATCH_GAP} steps, and it averages out over every 16 x 16 block: compression noise (saved as JPEG, or through a lossy step?)"
            ),
        })
}
