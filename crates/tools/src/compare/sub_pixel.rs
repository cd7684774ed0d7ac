//! Differences smaller than a pixel, which are no mistake (issue 40).
//!
//! raystep traces one ray through each pixel's centre. Another correct
//! tracer may see an edge a hair to one side (its eye, in float32 or added
//! in another order, sits 1e-5 away), so a pixel on a silhouette takes its
//! neighbour's colour; or it averages several rays a pixel (anti-aliasing),
//! so a pixel on an edge is a blend of both sides. Either way the pixel's
//! value is one the scene shows right there. Two tests say so:
//!
//! - **within reach**: each channel lies between the least and the most of
//!   the reference's 3 x 3 pixels around it, widened by the tolerance. An
//!   edge moved by less than a pixel gives such a value; such a pixel is
//!   never far off (it still counts toward the share a match allows).
//! - **a blend**: each channel lies between the least and the most of what
//!   the scene shows inside the pixel itself: raystep's ray through its
//!   centre and its four rays through the quarter points (x + 1/4 or 3/4,
//!   y + 1/4 or 3/4: raystep's render at twice the size), widened by the
//!   tolerance. A pixel averaged over rays inside it gives such a value.
//!   When anti-aliasing is accepted, a blend counts for nothing, as long as
//!   the image is not shifted (below).
//!
//! - **on an edge through its centre**: raystep's rays a thousandth of a
//!   pixel to either side of the centre (left, right, up, down) see
//!   different things, and each channel lies between the least and the
//!   most of what they and the centre's ray see, widened by the tolerance.
//!   Which side the centre's own ray falls on is then a matter of rounding:
//!   a level camera's middle row on the horizon of an endless floor turns
//!   from sky to floor, all of it, when the eye rises by 1e-5. Either value
//!   is right: such a pixel counts for nothing. An edge lies that close to
//!   a pixel's centre only by construction (a row or column of centres on
//!   a horizon or a plane seen edge-on): one edge pixel in a thousand by
//!   chance, so a mistake that moves edges is still seen on the others.
//!
//! A whole image shifted by half a pixel (`pixel-corner`: rays through the
//! pixels' corners) also changes every edge pixel to a value the scene
//! shows there. It is told apart by the direction: a shift moves every edge
//! the same way, anti-aliasing spreads each edge to both sides evenly. The
//! shift is estimated by least squares over the pixels past the tolerance
//! (yours − reference ≈ −s · ∇reference, as Lucas and Kanade estimate
//! motion), and blends are accepted only when |s| < `MAX_BLEND_SHIFT`.

use image::RgbImage;

/// Anti-aliasing is accepted only when the shift estimated from the pixels
/// past the tolerance is under this many pixels. Measured on the nine
/// teaching scenes (`scenes/*.toml`) at 80 x 60, their own size and
/// 320 x 240: raystep's render at twice the size averaged 2 x 2 gives
/// |s| ≤ 0.25 (attenuation.toml at 160 x 120: (0, −0.245)), `pixel-corner`
/// gives |s| ≥ 0.83 (highlights.toml at 80 x 60: (0.56, 0.61)). On the
/// seven small SPD scenes (`scenes/spd/*-small.nff`) at 160 x 120 and
/// 256 x 256: |s| ≤ 0.43 (tree) and ≥ 0.88 (balls). Half a pixel lies
/// between.
pub(crate) const MAX_BLEND_SHIFT: f64 = 0.5;

/// How far from a pixel's centre, in pixels, raystep looks for an edge
/// through it. Near enough that an edge found is one the centre's ray
/// grazes (one edge pixel in a thousand lies that close by chance; a
/// `pixel-corner` ray passes 0.5 away), far enough to see both sides of an
/// edge that passes exactly through the centre, which the rounding of a
/// correct tracer (float32 directions: about 1e-7 of a radian; an eye 1e-5
/// off at 7 units: 1.4e-6) puts on either side.
pub(crate) const EDGE_REACH: f64 = 1e-3;

/// Where, from a pixel's centre, the rays that look for an edge through
/// it pass (`EDGE_REACH` left, right, up and down).
pub(crate) const BESIDE_CENTRE: [(f64, f64); 4] = [
    (-EDGE_REACH, 0.0),
    (EDGE_REACH, 0.0),
    (0.0, -EDGE_REACH),
    (0.0, EDGE_REACH),
];

/// Whether a ray a hair beside pixel (x, y)'s centre (`beside`, the rays
/// through `BESIDE_CENTRE`) sees something past `tolerance` steps from its
/// centre's, and `mine` lies, in every channel, within what they all see,
/// widened by `tolerance` steps: an edge through the centre, either side
/// of which is right.
pub(crate) fn on_edge(
    reference: &RgbImage,
    x: u32,
    y: u32,
    beside: [[u8; 3]; 4],
    mine: [u8; 3],
    tolerance: u8,
) -> bool {
    let centre = reference.get_pixel(x, y).0;
    // An edge: a ray beside the centre sees something else, past the
    // tolerance (a smooth shading gradient changes by less in 1e-3 px).
    let edge = beside
        .iter()
        .any(|&b| (0..3).any(|c| b[c].abs_diff(centre[c]) > tolerance));
    edge && within(std::iter::once(centre).chain(beside), mine, tolerance)
}

/// Whether `mine` lies, in every channel, within the reference's values
/// over the 3 x 3 pixels around (x, y), widened by `tolerance` steps.
pub(crate) fn within_reach(
    reference: &RgbImage,
    x: u32,
    y: u32,
    mine: [u8; 3],
    tolerance: u8,
) -> bool {
    let (width, height) = reference.dimensions();
    let xs = x.saturating_sub(1)..=(x + 1).min(width - 1);
    let ys = y.saturating_sub(1)..=(y + 1).min(height - 1);
    let values = ys.flat_map(|ny| xs.clone().map(move |nx| reference.get_pixel(nx, ny).0));
    within(values, mine, tolerance)
}

/// Whether `mine` lies, in every channel, within what the scene shows
/// inside pixel (x, y): the reference's value there and `fine`'s four
/// (`fine` is the render at twice the size), widened by `tolerance` steps.
pub(crate) fn blend(
    reference: &RgbImage,
    fine: &RgbImage,
    x: u32,
    y: u32,
    mine: [u8; 3],
    tolerance: u8,
) -> bool {
    let quarters =
        [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(i, j)| fine.get_pixel(2 * x + i, 2 * y + j).0);
    let values = std::iter::once(reference.get_pixel(x, y).0).chain(quarters);
    within(values, mine, tolerance)
}

fn within(values: impl Iterator<Item = [u8; 3]>, mine: [u8; 3], tolerance: u8) -> bool {
    let (low, high) = values.fold(([255u8; 3], [0u8; 3]), |(low, high), v| {
        (
            [0, 1, 2].map(|c| low[c].min(v[c])),
            [0, 1, 2].map(|c| high[c].max(v[c])),
        )
    });
    (0..3).all(|c| {
        mine[c].saturating_add(tolerance) >= low[c] && mine[c] <= high[c].saturating_add(tolerance)
    })
}

/// The shift s (in pixels, right and down positive) by which `yours` is
/// the reference moved, fitted by least squares over `pixels` (row-major
/// indices): yours − reference ≈ −s · ∇reference in every channel, the
/// gradient by central differences. Pixels on the image's border are left
/// out; `None` when the rest show no gradient to fit.
pub(crate) fn shift(yours: &RgbImage, reference: &RgbImage, pixels: &[u32]) -> Option<[f64; 2]> {
    let (width, height) = reference.dimensions();
    let at = |x: u32, y: u32, c: usize| f64::from(reference.get_pixel(x, y).0[c]);
    let (mut xx, mut xy, mut yy, mut xd, mut yd) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &index in pixels {
        let (x, y) = (index % width, index / width);
        if x == 0 || y == 0 || x + 1 == width || y + 1 == height {
            continue;
        }
        for (c, mine) in yours.get_pixel(x, y).0.into_iter().enumerate() {
            let gx = (at(x + 1, y, c) - at(x - 1, y, c)) / 2.0;
            let gy = (at(x, y + 1, c) - at(x, y - 1, c)) / 2.0;
            let d = f64::from(mine) - at(x, y, c);
            xx += gx * gx;
            xy += gx * gy;
            yy += gy * gy;
            xd += gx * d;
            yd += gy * d;
        }
    }
    let det = xx * yy - xy * xy;
    // Gradients all along one line (or none) leave the shift along the
    // other direction unknown.
    if det <= 1e-9 * (xx * yy).max(1.0) {
        return None;
    }
    Some([-(yy * xd - xy * yd) / det, -(xx * yd - xy * xd) / det])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A vertical edge: columns left of `edge` (in pixels, from the left)
    /// dark (20), right of it bright (220), sampled at each pixel's centre.
    fn edge(width: u32, height: u32, edge: f64) -> RgbImage {
        RgbImage::from_fn(width, height, |x, _| {
            image::Rgb([if f64::from(x) + 0.5 < edge { 20 } else { 220 }; 3])
        })
    }

    #[test]
    fn reach_and_blend_take_the_values_around_and_inside_the_pixel() {
        // Reference: the edge at 4.6, so pixel 4 (centre 4.5) is dark and
        // pixel 5 bright. Twice the size: the edge at 9.2, so pixel 4's
        // quarter samples (columns 8 and 9, centres 8.5 and 9.5) are dark
        // and bright.
        let reference = edge(10, 3, 4.6);
        let fine = edge(20, 6, 9.2);
        // 120 lies between 20 and 220: within reach of pixels 3 to 6
        // (pixel 3's 3 x 3 holds 2, 3, 4, all dark: no; pixel 4's holds
        // pixel 5, bright: yes).
        let grey = [120; 3];
        assert!(!within_reach(&reference, 3, 1, grey, 3));
        assert!(within_reach(&reference, 4, 1, grey, 3));
        // A blend only in pixel 4, whose quarter samples see both sides;
        // pixel 5's are both bright (columns 10 and 11).
        assert!(blend(&reference, &fine, 4, 1, grey, 3));
        assert!(!blend(&reference, &fine, 5, 1, grey, 3));
        // 16 is 4 below the darkest, 20: within a tolerance of 4, not 3.
        assert!(!within_reach(&reference, 4, 1, [16; 3], 3));
        assert!(within_reach(&reference, 4, 1, [16; 3], 4));
        // Every channel must lie within: red 120 but blue 250 does not.
        assert!(!within_reach(&reference, 4, 1, [120, 120, 250], 3));
    }

    #[test]
    fn the_shift_of_a_moved_square_is_found_and_a_blend_shows_none() {
        // A ramp, 10 steps a pixel in x and 5 in y, has its gradient along
        // one line everywhere: a shift across it changes nothing, so none
        // can be fitted.
        let ramp = RgbImage::from_fn(12, 12, |x, y| image::Rgb([(x * 10 + y * 5) as u8; 3]));
        let darker = RgbImage::from_fn(12, 12, |x, y| image::Rgb([(x * 10 + y * 5 - 3) as u8; 3]));
        let all: Vec<u32> = (0..144).collect();
        assert_eq!(shift(&darker, &ramp, &all), None);
        // A bright square (200) from (5, 5) to the far corner of a 12 x 12
        // image, moved one pixel right and down: the differing pixels are
        // column 5 and row 5 (200 -> 0, d = -200). Off the border: column 5
        // at y = 6..=10 has gx = (200 - 0) / 2 = 100, gy = 0; row 5 at
        // x = 6..=10 gx = 0, gy = 100; the corner (5, 5) gx = gy = 100.
        // Sums (each channel alike): xx = yy = 6e4, xy = 1e4, xd = yd =
        // -1.2e5; s_x = -(yy xd - xy yd) / (xx yy - xy²) = 6e9 / 3.5e9 =
        // 12/7, and s_y alike: down and right, as it moved (a central
        // difference spreads the step over two pixels, so not 1).
        let square = |corner: u32| {
            RgbImage::from_fn(12, 12, |x, y| {
                image::Rgb([if x >= corner && y >= corner { 200 } else { 0 }; 3])
            })
        };
        let reference = square(5);
        let differing = |a: &RgbImage, b: &RgbImage| -> Vec<u32> {
            (0..144u32)
                .filter(|&i| a.get_pixel(i % 12, i / 12) != b.get_pixel(i % 12, i / 12))
                .collect()
        };
        let moved = square(6);
        let [sx, sy] = shift(&moved, &reference, &differing(&moved, &reference)).unwrap();
        assert!((sx - 12.0 / 7.0).abs() < 1e-12 && (sy - 12.0 / 7.0).abs() < 1e-12);
        // The square's edges blended both ways, away from its corner: the
        // pixel just outside raised by 50, the one just inside lowered by
        // 50 (x = 4 and 5 at y = 7..=10, and y = 4 and 5 at x = 7..=10).
        // Outside: gx = (200 - 0) / 2 = 100, d = 50; inside: gx = 100,
        // d = -50; xd = 4 × 5000 - 4 × 5000 = 0, likewise yd; xy = 0: s = 0.
        let blended = RgbImage::from_fn(12, 12, |x, y| {
            let v = reference.get_pixel(x, y).0[0];
            let edge = |a: u32, b: u32| (7..=10).contains(&b) && (a == 4 || a == 5);
            let v = if edge(x, y) || edge(y, x) {
                if v == 0 { 50 } else { 150 }
            } else {
                v
            };
            image::Rgb([v; 3])
        });
        let [sx, sy] = shift(&blended, &reference, &differing(&blended, &reference)).unwrap();
        assert_eq!((sx, sy), (0.0, 0.0));
    }
}
