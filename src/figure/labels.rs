//! Where a figure's text goes: each label at the first place near its
//! anchor whose box meets no label or mark already placed, so no two ever
//! overlap on a slide. Boxes are estimated from the character count, as an
//! SVG has no text metrics before it is drawn.

use std::fmt::Write;

use glam::DVec2;

/// A box as its (top-left, bottom-right) corners.
type Box2 = (DVec2, DVec2);

/// Placed labels' and marks' boxes.
pub struct Labels {
    font_size: f64,
    /// Where the crowded-out labels start, at the left.
    margin: f64,
    boxes: Vec<Box2>,
}

impl Labels {
    pub fn new(font_size: f64, margin: f64) -> Labels {
        Labels {
            font_size,
            margin,
            boxes: Vec::new(),
        }
    }

    /// The size of the labels placed from now on (the text's own
    /// `font-size` attribute must say the same).
    pub fn set_font_size(&mut self, size: f64) {
        self.font_size = size;
    }

    /// Keeps labels off text written elsewhere, its baseline starting at
    /// `corner` (an axis name).
    pub fn reserve_text(&mut self, corner: DVec2, text: &str) {
        let size = self.size(text);
        self.boxes.push(text_box(corner, size));
    }

    /// Keeps labels off a mark (a dot, a crossing) of this radius.
    pub fn reserve(&mut self, centre: DVec2, radius: f64) {
        let r = DVec2::splat(radius);
        self.boxes.push((centre - r, centre + r));
    }

    /// Writes `text` near `at`: right, left, above or below it, or further
    /// out, at the first place whose box meets nothing placed. `attrs` are
    /// the text element's other attributes (`fill="..."`).
    pub fn place(&mut self, out: &mut String, at: DVec2, text: &str, attrs: &str) {
        let size = self.size(text);
        let corner = self.free(self.rings(at, size), size);
        self.write(out, corner, size, text, attrs);
    }

    /// As `place`, but centred on `at` first (a vertex number just outside
    /// its corner).
    pub fn place_centred(&mut self, out: &mut String, at: DVec2, text: &str, attrs: &str) {
        let size = self.size(text);
        let centred = at + DVec2::new(-size.x / 2.0, size.y / 2.0 - 2.0);
        let corner = self.free(std::iter::once(centred).chain(self.rings(at, size)), size);
        self.write(out, corner, size, text, attrs);
    }

    fn size(&self, text: &str) -> DVec2 {
        let width = text.chars().count() as f64 * self.font_size * 0.6;
        DVec2::new(width, self.font_size)
    }

    /// Baseline starts around `at`, ring after ring.
    fn rings(&self, at: DVec2, size: DVec2) -> impl Iterator<Item = DVec2> {
        (1..=6).flat_map(move |ring| {
            let d = 10.0 * ring as f64;
            [
                DVec2::new(d, 4.0),
                DVec2::new(-d - size.x, 4.0),
                DVec2::new(-size.x / 2.0, -d),
                DVec2::new(-size.x / 2.0, d + size.y),
                DVec2::new(d, -d),
                DVec2::new(d, d + size.y),
            ]
            .map(|offset| at + offset)
        })
    }

    /// The first candidate baseline start whose box is free; crowded
    /// everywhere, below all the others at the left.
    fn free(&self, candidates: impl Iterator<Item = DVec2>, size: DVec2) -> DVec2 {
        let mut candidates = candidates;
        candidates
            .find(|corner| {
                !self
                    .boxes
                    .iter()
                    .any(|o| overlap(*o, text_box(*corner, size)))
            })
            .unwrap_or_else(|| {
                let lowest = self.boxes.iter().map(|b| b.1.y).fold(self.margin, f64::max);
                DVec2::new(self.margin, lowest + size.y + 4.0)
            })
    }

    fn write(&mut self, out: &mut String, corner: DVec2, size: DVec2, text: &str, attrs: &str) {
        self.boxes.push(text_box(corner, size));
        let _ = writeln!(
            out,
            "<text x=\"{:.1}\" y=\"{:.1}\"{}{attrs}>{}</text>",
            corner.x,
            corner.y,
            if attrs.is_empty() { "" } else { " " },
            escape(text)
        );
    }
}

/// The box of a text whose baseline starts at `corner` (descenders included).
fn text_box(corner: DVec2, size: DVec2) -> Box2 {
    (
        corner - DVec2::new(0.0, size.y),
        corner + DVec2::new(size.x, 3.0),
    )
}

fn overlap(a: Box2, b: Box2) -> bool {
    a.0.x < b.1.x && b.0.x < a.1.x && a.0.y < b.1.y && b.0.y < a.1.y
}

pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_never_overlap() {
        // Ten labels asked for at one point: each lands in its own box.
        let mut labels = Labels::new(13.0, 40.0);
        let mut out = String::new();
        for i in 0..10 {
            let text = format!("label {i}");
            labels.place(&mut out, DVec2::new(400.0, 300.0), &text, "fill=\"black\"");
        }
        for (i, a) in labels.boxes.iter().enumerate() {
            for b in &labels.boxes[i + 1..] {
                assert!(!overlap(*a, *b), "{a:?} {b:?}");
            }
        }
        assert_eq!(out.matches("<text").count(), 10);
    }

    #[test]
    fn a_centred_label_moves_off_a_reserved_mark() {
        // "4" (one character, 6.6 x 11 at font size 11) centred on (100, 100)
        // spans x 96.7..103.3, y 93.5..106.5; a mark of radius 6 at (100, 100)
        // takes 94..106 both ways, so the label goes to the first ring:
        // right of the anchor, baseline start (110, 104).
        let mut labels = Labels::new(11.0, 40.0);
        labels.reserve(DVec2::new(100.0, 100.0), 6.0);
        let mut out = String::new();
        labels.place_centred(&mut out, DVec2::new(100.0, 100.0), "4", "fill=\"grey\"");
        assert_eq!(
            out,
            "<text x=\"110.0\" y=\"104.0\" fill=\"grey\">4</text>\n"
        );
        // Nothing reserved: it stays centred, baseline start (96.7, 103.5).
        let mut free = Labels::new(11.0, 40.0);
        let mut out = String::new();
        free.place_centred(&mut out, DVec2::new(100.0, 100.0), "4", "fill=\"grey\"");
        assert_eq!(out, "<text x=\"96.7\" y=\"103.5\" fill=\"grey\">4</text>\n");
    }

    #[test]
    fn names_are_escaped() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
