//! The three images of a submission (yours, the reference, FLIP's error
//! map) as `<img>` elements at a size fit for where they are shown: small
//! in the class table, readable on a student's page. Pixels stay square
//! and sharp (`image-rendering: pixelated`, in the page's style).

use super::escape::{escape, url};

/// The box a thumbnail fits in, in CSS pixels, at most: three per scene in
/// a row of the class table (with the cell's gaps, padding and border,
/// 213 px a scene) leave five scenes on a 1366-pixel screen.
const THUMBNAIL: (f64, f64) = (64.0, 48.0);
/// The width the class table's scene columns may take between them on a
/// 1366-pixel screen: the window less the page's margins (36), a scroll
/// bar (15), the name column (141 at its narrowest) and the total (55),
/// and some slack for fonts wider than the test's.
const SCENES_WIDTH: f64 = 1100.0;
/// What a scene's cell takes beside its three thumbnails: two 3-px gaps,
/// 14 px of padding and a 1-px border.
const CELL_EXTRA: f64 = 21.0;
/// Thumbnails are never narrower than this: past it (ten scenes and more)
/// the table scrolls sideways, the names staying in view.
const NARROWEST: f64 = 32.0;
/// The box an image on a student's page fits in: 160x120 shows at 320x240,
/// so three side by side fit a laptop's width.
const READABLE: (f64, f64) = (400.0, 300.0);

/// `width` x `height` scaled into the thumbnail box, narrowed so that the
/// class table's `scenes` columns fit `SCENES_WIDTH` (six scenes: 1100 / 6
/// = 183 px a cell, 162 for three thumbnails, 54 px each).
pub(super) fn thumbnail_size(width: u32, height: u32, scenes: usize) -> (u32, u32) {
    let (most_w, most_h) = THUMBNAIL;
    let share = ((SCENES_WIDTH / scenes.max(1) as f64 - CELL_EXTRA) / 3.0).floor();
    let box_w = share.clamp(NARROWEST, most_w);
    fit(width, height, (box_w, most_h * box_w / most_w), false)
}

/// `width` x `height` at a readable size: enlarged by a whole factor (so
/// every pixel is the same number of screen pixels), or shrunk to fit.
pub(super) fn readable_size(width: u32, height: u32) -> (u32, u32) {
    fit(width, height, READABLE, true)
}

fn fit(width: u32, height: u32, (box_w, box_h): (f64, f64), whole: bool) -> (u32, u32) {
    let (w, h) = (f64::from(width.max(1)), f64::from(height.max(1)));
    let mut scale = (box_w / w).min(box_h / h);
    if whole && scale >= 1.0 {
        scale = scale.floor();
    }
    let side = |s: f64| (s * scale).round().max(1.0) as u32;
    (side(w), side(h))
}

/// An `<img>` of `path` (relative to REPORT/, reached through `prefix`:
/// `""` from index.html, `"../"` from a student's page), or a grey box of
/// the same size saying `missing` when there is no image.
pub(super) fn image(
    path: Option<&str>,
    prefix: &str,
    alt: &str,
    size: (u32, u32),
    missing: &str,
) -> String {
    let (width, height) = size;
    match path {
        Some(path) => format!(
            "<img class=\"px\" src=\"{prefix}{}\" alt=\"{}\" width=\"{width}\" height=\"{height}\" loading=\"lazy\" decoding=\"async\">",
            escape(&url(path)),
            escape(alt),
        ),
        None => format!(
            "<span class=\"noimg\" style=\"width:{width}px;height:{height}px\">{}</span>",
            escape(missing)
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_keep_the_aspect_and_whole_enlargements() {
        // 160x120 into 64x48: 0.4 both ways. Readable: 400/160 = 2.5 and
        // 300/120 = 2.5, floored to 2: 320x240.
        assert_eq!(thumbnail_size(160, 120, 5), (64, 48));
        assert_eq!(readable_size(160, 120), (320, 240));
        // 512x512: min(64/512, 48/512) = 0.09375, 48x48; readable shrinks
        // by 300/512 to 300x300, no flooring below 1.
        assert_eq!(thumbnail_size(512, 512, 5), (48, 48));
        assert_eq!(readable_size(512, 512), (300, 300));
        // A 1x1000 sliver keeps at least one pixel across.
        assert_eq!(thumbnail_size(1, 1000, 5), (1, 48));
    }

    #[test]
    fn thumbnails_narrow_so_that_six_scenes_fit_a_laptop() {
        // One to five scenes: 1100 / 5 - 21 = 199, / 3 = 66, capped at 64.
        assert_eq!(thumbnail_size(160, 120, 1), (64, 48));
        // Six: 1100 / 6 = 183.3, - 21 = 162.3, / 3 = 54.1, floored to 54;
        // the box 54 x 40.5 takes 160x120 at 0.3375: 54 x 40.5, rounded 41.
        // Three of them and the cell's 21 px make 183, six 1098 <= 1100.
        assert_eq!(thumbnail_size(160, 120, 6), (54, 41));
        // Seven: 1100 / 7 = 157.1 - 21 = 136.1, / 3 = 45.4: 45 x 33.75.
        assert_eq!(thumbnail_size(160, 120, 7), (45, 34));
        // Twenty: 55 - 21 = 34 / 3 = 11.3, held at 32 (the table scrolls).
        assert_eq!(thumbnail_size(160, 120, 20), (32, 24));
    }

    #[test]
    fn an_image_or_a_box_its_size() {
        assert_eq!(
            image(Some("a b.png"), "../", "yours", (64, 48), "none"),
            "<img class=\"px\" src=\"../a%20b.png\" alt=\"yours\" width=\"64\" height=\"48\" loading=\"lazy\" decoding=\"async\">"
        );
        assert_eq!(
            image(None, "", "yours", (64, 48), "no image"),
            "<span class=\"noimg\" style=\"width:64px;height:48px\">no image</span>"
        );
    }
}
