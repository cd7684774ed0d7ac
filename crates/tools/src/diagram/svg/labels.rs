//! Where a figure's text goes: each label at the first place near its
//! anchor whose box lies inside the figure and meets no label, mark or ray
//! already placed, so no two ever overlap on a slide and none is cut at
//! the edge; an object's name, where there is room, where no other
//! object's outline is nearer than its own. Boxes are estimated from the
//! character count, as an SVG has no text metrics before it is drawn. The
//! boxes' geometry is `frame_geometry.rs`, the text's escaping `escaping.rs`.

use std::collections::HashMap;
use std::fmt::Write;

use glam::DVec2;

use super::cell_index::CellIndex;
use super::escaping::escape;
use super::frame_geometry::{Box2, clip, contains, overlap, segment_box_distance};

/// Placed labels' and marks' boxes, and the rays to keep labels off, each
/// kind listed by the cells of the figure it reaches (a place is tested
/// against what is near it only).
pub(crate) struct Labels {
    font_size: f64,
    /// Where labels may go: the figure less its title and legend.
    bounds: Box2,
    boxes: Vec<Box2>,
    box_cells: CellIndex,
    rays: Vec<(DVec2, DVec2)>,
    ray_cells: CellIndex,
    /// Objects' outlines, each piece with its object: a label across one
    /// reads as naming the wrong object, so they are kept clear before
    /// rays are.
    outlines: Vec<OutlinePiece>,
    outline_cells: CellIndex,
    /// Each object's pieces of `outlines`.
    outlines_of: HashMap<usize, Vec<usize>>,
}

/// The side of a cell of the figure's grid, in figure units: about a
/// label's height, so a place's box covers a handful of cells.
const CELL: f64 = 16.0;

/// A straight piece of an object's outline in the figure.
#[derive(Clone, Copy)]
struct OutlinePiece {
    a: DVec2,
    b: DVec2,
    /// The object it outlines (the scene's index).
    object: usize,
}

impl Labels {
    pub(crate) fn new(font_size: f64, bounds: Box2) -> Labels {
        Labels {
            font_size,
            bounds,
            boxes: Vec::new(),
            box_cells: CellIndex::new(bounds, CELL),
            rays: Vec::new(),
            ray_cells: CellIndex::new(bounds, CELL),
            outlines: Vec::new(),
            outline_cells: CellIndex::new(bounds, CELL),
            outlines_of: HashMap::new(),
        }
    }

    /// Keeps labels off the box `b` (a mark's, a label's, a text's).
    fn reserve_box(&mut self, b: Box2) {
        self.box_cells.insert_box(b, self.boxes.len() as u32);
        self.boxes.push(b);
    }

    /// The size of the labels placed from now on (the text's own
    /// `font-size` attribute must say the same).
    pub(crate) fn set_font_size(&mut self, size: f64) {
        self.font_size = size;
    }

    /// Keeps labels off text written elsewhere, its baseline starting at
    /// `corner` (an axis name).
    pub(crate) fn reserve_text(&mut self, corner: DVec2, text: &str) {
        let size = self.size(text);
        self.reserve_box(text_box(corner, size));
    }

    /// Keeps labels off a mark (a dot, a crossing) of this radius.
    pub(crate) fn reserve(&mut self, centre: DVec2, radius: f64) {
        let r = DVec2::splat(radius);
        self.reserve_box((centre - r, centre + r));
    }

    /// Keeps labels off a drawn ray from `a` to `b` where there is room;
    /// unlike a mark, a label may cross a ray when nothing near is free.
    pub(crate) fn reserve_ray(&mut self, a: DVec2, b: DVec2) {
        self.ray_cells.insert_segment(a, b, self.rays.len() as u32);
        self.rays.push((a, b));
    }

    /// Keeps labels off a piece of `object`'s outline from `a` to `b`;
    /// a label goes further out (up to twice as far as for a ray) before
    /// it crosses one.
    pub(crate) fn reserve_outline(&mut self, a: DVec2, b: DVec2, object: usize) {
        let piece = self.outlines.len();
        self.outline_cells.insert_segment(a, b, piece as u32);
        self.outlines_of.entry(object).or_default().push(piece);
        self.outlines.push(OutlinePiece { a, b, object });
    }

    /// Writes `text` near `at`: right, left, above or below it, or further
    /// out, at the first place whose box meets nothing placed. `attrs` are
    /// the text element's other attributes (`fill="..."`).
    pub fn place(&mut self, out: &mut String, at: DVec2, text: &str, attrs: &str) {
        let size = self.size(text);
        let candidates: Vec<DVec2> = self.rings(at, size, 8).collect();
        let corner = self.free(at, &candidates, size);
        self.write(out, corner, size, text, attrs);
    }

    /// As `place`, for `object`'s name: first at a place no other
    /// object's outline is nearer than its own, so that the name is read
    /// as its own object's (seven-rays from the side: "green ball" sat
    /// just above the glass ball, far from its own); else as `place`.
    pub(crate) fn place_name(
        &mut self,
        out: &mut String,
        at: DVec2,
        object: usize,
        text: &str,
        attrs: &str,
    ) {
        let size = self.size(text);
        let candidates: Vec<DVec2> = self.rings(at, size, 8).collect();
        let own = |corner: &DVec2| self.nearest_is_own(text_box(*corner, size), object);
        let beside: Vec<DVec2> = candidates.iter().copied().filter(own).collect();
        let corner = (self.clear(&beside, size, true))
            .or_else(|| self.clear(&beside, size, false))
            .unwrap_or_else(|| self.free(at, &candidates, size));
        self.write(out, corner, size, text, attrs);
    }

    /// As `place`, but centred on `at` first (a vertex number just outside
    /// its corner).
    pub(crate) fn place_centred(&mut self, out: &mut String, at: DVec2, text: &str, attrs: &str) {
        let size = self.size(text);
        let centred = at + DVec2::new(-size.x / 2.0, size.y / 2.0 - 2.0);
        let candidates: Vec<DVec2> = std::iter::once(centred)
            .chain(self.rings(at, size, 8))
            .collect();
        let corner = self.free(at, &candidates, size);
        self.write(out, corner, size, text, attrs);
    }

    fn size(&self, text: &str) -> DVec2 {
        let width = shown(text).chars().count() as f64 * self.font_size * 0.6;
        DVec2::new(width, self.font_size)
    }

    /// Baseline starts around `at`, ring after ring, `count` rings 10
    /// units apart.
    fn rings(&self, at: DVec2, size: DVec2, count: usize) -> impl Iterator<Item = DVec2> {
        (1..=count).flat_map(move |ring| {
            let d = 10.0 * ring as f64;
            [
                DVec2::new(d, 4.0),
                DVec2::new(-d - size.x, 4.0),
                DVec2::new(-size.x / 2.0, -d),
                DVec2::new(-size.x / 2.0, d + size.y),
                DVec2::new(d, -d),
                DVec2::new(d, d + size.y),
                DVec2::new(-d - size.x, -d),
                DVec2::new(-d - size.x, d + size.y),
            ]
            .map(|offset| at + offset)
        })
    }

    /// Whether no other object's outline comes nearer the box `b` than
    /// `object`'s own (within a unit: faces seen edge-on share their
    /// lines), and `object` has one drawn.
    fn nearest_is_own(&self, b: Box2, object: usize) -> bool {
        let distance = |piece: &OutlinePiece| segment_box_distance(piece.a, piece.b, b);
        let own = (self.outlines_of.get(&object).into_iter().flatten())
            .map(|&i| distance(&self.outlines[i]))
            .fold(f64::INFINITY, f64::min);
        if !own.is_finite() {
            return false;
        }
        // Another object's piece can only come nearer than `own` with a
        // point within `own` of the box: look in the cells that far out.
        let reach = DVec2::splat(own + 1.0);
        (self.outline_cells.near((b.0 - reach, b.1 + reach)))
            .map(|i| &self.outlines[i])
            .filter(|piece| piece.object != object)
            .all(|piece| own <= distance(piece) + 1.0)
    }

    /// Whether the box `b` is inside the figure and meets no label or
    /// mark, no outline, and (if `rays`) no ray.
    fn fits(&self, b: Box2, rays: bool) -> bool {
        contains(self.bounds, b) && self.meets_no_box(b) && !self.crosses(b, rays)
    }

    /// Whether the box `b` meets no label or mark.
    fn meets_no_box(&self, b: Box2) -> bool {
        !(self.box_cells.near(b)).any(|i| overlap(self.boxes[i], b))
    }

    /// Whether an outline, or (if `rays`) a ray, crosses the box `b`.
    fn crosses(&self, b: Box2, rays: bool) -> bool {
        let crosses = |(a, c): (DVec2, DVec2)| clip(a, c, b).is_some();
        let outlines = self.outline_cells.near(b).map(|i| &self.outlines[i]);
        (outlines.map(|p| (p.a, p.b)).any(crosses))
            || (rays && self.ray_cells.near(b).map(|i| self.rays[i]).any(crosses))
    }

    /// The first of `candidates` that `fits`.
    fn clear(&self, candidates: &[DVec2], size: DVec2, rays: bool) -> Option<DVec2> {
        (candidates.iter().copied()).find(|c| self.fits(text_box(*c, size), rays))
    }

    /// The first candidate whose box is inside the figure and free of
    /// marks, labels, outlines and rays; else the first free of outlines
    /// (crossing a ray); else, in rings as far again out about `at`, the
    /// first free of outlines; else the first free of marks and
    /// labels; crowded everywhere near, the first free place row by row.
    fn free(&self, at: DVec2, candidates: &[DVec2], size: DVec2) -> DVec2 {
        let fits = |corner: &DVec2, outlines: bool, rays: bool| {
            let b = text_box(*corner, size);
            if outlines {
                return self.fits(b, rays);
            }
            contains(self.bounds, b) && self.meets_no_box(b)
        };
        let first = |outlines, rays| (candidates.iter().copied()).find(|c| fits(c, outlines, rays));
        let further = || {
            let far: Vec<DVec2> = self.rings(at, size, 16).skip(8 * 8).collect();
            far.into_iter().find(|c| fits(c, true, false))
        };
        (first(true, true))
            .or_else(|| first(true, false))
            .or_else(further)
            .or_else(|| first(false, false))
            .unwrap_or_else(|| {
                self.scan(size)
                    .unwrap_or(self.bounds.0 + DVec2::new(1.0, size.y + 1.0))
            })
    }

    /// The first place, row by row (every 4 units down, 8 across), whose
    /// box is inside the figure and meets no label or mark. A place whose
    /// box meets one jumps past its right edge: every place between meets
    /// it too (the boxes only move right), so none is passed that fits.
    fn scan(&self, size: DVec2) -> Option<DVec2> {
        let (lo, hi) = self.bounds;
        let rows = (0..).map(|i| lo.y + size.y + 1.0 + i as f64 * 4.0);
        for y in rows.take_while(|y| *y + 3.0 <= hi.y) {
            let at = |i: usize| DVec2::new(lo.x + 1.0 + i as f64 * 8.0, y);
            let mut i = 0;
            while at(i).x + size.x <= hi.x {
                let b = text_box(at(i), size);
                let met = (self.box_cells.near(b)).find(|&o| overlap(self.boxes[o], b));
                match met {
                    None if contains(self.bounds, b) => return Some(at(i)),
                    None => i += 1,
                    Some(o) => {
                        i += 1;
                        while at(i).x < self.boxes[o].1.x && at(i).x + size.x <= hi.x {
                            i += 1;
                        }
                    }
                }
            }
        }
        None
    }

    fn write(&mut self, out: &mut String, corner: DVec2, size: DVec2, text: &str, attrs: &str) {
        self.reserve_box(text_box(corner, size));
        let shown = shown(text);
        // A shortened label keeps its whole text as the tooltip of a group
        // around it (a `<title>` inside `<text>` would come before the words).
        let whole = shown != text;
        if whole {
            let _ = write!(out, "<g><title>{}</title>", escape(text));
        }
        let _ = write!(
            out,
            "<text x=\"{:.1}\" y=\"{:.1}\"{}{attrs}>{}</text>",
            corner.x,
            corner.y,
            if attrs.is_empty() { "" } else { " " },
            escape(&shown)
        );
        out.push_str(if whole { "</g>\n" } else { "\n" });
    }
}

/// The most characters of a label drawn: a 150-character name would cross
/// the figure and every other label (40 at the largest font, 13, is about
/// 310 units, well inside the figure's width).
const MAX_LABEL_CHARS: usize = 40;

/// `text` as a label shows it: control characters spelt out (so it is
/// measured as drawn), then cut to `MAX_LABEL_CHARS` with `…` at the end.
fn shown(text: &str) -> String {
    let spelt = raystep_engine::printable::printable(text);
    if spelt.chars().count() <= MAX_LABEL_CHARS {
        return spelt.into_owned();
    }
    let mut cut: String = spelt.chars().take(MAX_LABEL_CHARS - 1).collect();
    cut.push('…');
    cut
}

/// The box of a text whose baseline starts at `corner` (descenders included).
fn text_box(corner: DVec2, size: DVec2) -> Box2 {
    (
        corner - DVec2::new(0.0, size.y),
        corner + DVec2::new(size.x, 3.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A figure large enough that its edges never matter.
    const WIDE: Box2 = (DVec2::new(0.0, 0.0), DVec2::new(800.0, 600.0));

    #[test]
    fn labels_never_overlap() {
        // Ten labels asked for at one point: each lands in its own box.
        let mut labels = Labels::new(13.0, WIDE);
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
        let mut labels = Labels::new(11.0, WIDE);
        labels.reserve(DVec2::new(100.0, 100.0), 6.0);
        let mut out = String::new();
        labels.place_centred(&mut out, DVec2::new(100.0, 100.0), "4", "fill=\"grey\"");
        assert_eq!(
            out,
            "<text x=\"110.0\" y=\"104.0\" fill=\"grey\">4</text>\n"
        );
        // Nothing reserved: it stays centred, baseline start (96.7, 103.5).
        let mut free = Labels::new(11.0, WIDE);
        let mut out = String::new();
        free.place_centred(&mut out, DVec2::new(100.0, 100.0), "4", "fill=\"grey\"");
        assert_eq!(out, "<text x=\"96.7\" y=\"103.5\" fill=\"grey\">4</text>\n");
    }

    /// Numbers in 0..1 from a fixed seed: the same figure every run.
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = (self.0)
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The row scan as it was, testing each place against every box.
    fn scan_everything(labels: &Labels, size: DVec2) -> Option<DVec2> {
        let (lo, hi) = labels.bounds;
        let rows = (0..).map(|i| lo.y + size.y + 1.0 + i as f64 * 4.0);
        let mut places = rows.take_while(|y| *y + 3.0 <= hi.y).flat_map(|y| {
            (0..)
                .map(move |i| DVec2::new(lo.x + 1.0 + i as f64 * 8.0, y))
                .take_while(move |c| c.x + size.x <= hi.x)
        });
        places.find(|c| {
            let b = text_box(*c, size);
            contains(labels.bounds, b) && !labels.boxes.iter().any(|o| overlap(*o, b))
        })
    }

    #[test]
    fn the_cells_answer_as_testing_everything_placed_would() {
        // A crowded figure at random: 300 marks, rays and outline pieces
        // of 10 objects (some past its edges), and labels filling its top
        // third. For 2,000 places at random, `fits` and `nearest_is_own`
        // answer as tests of every item do, and the row scan stops where
        // testing each place against every box did.
        let mut r = Lcg(27);
        let mut labels = Labels::new(13.0, WIDE);
        let point = |r: &mut Lcg| DVec2::new(r.next() * 900.0 - 50.0, r.next() * 700.0 - 50.0);
        for i in 0..300 {
            let (a, b) = (point(&mut r), point(&mut r));
            labels.reserve(a, 2.0 + r.next() * 10.0);
            labels.reserve_ray(a, a + (b - a) * r.next());
            let piece = DVec2::new(r.next() * 60.0 - 30.0, r.next() * 60.0 - 30.0);
            labels.reserve_outline(b, b + piece, i % 10);
        }
        for row in 0..40 {
            let mut x = r.next() * 20.0;
            while x < 800.0 {
                let corner = DVec2::new(x, 14.0 + row as f64 * 5.0);
                let width = 20.0 + r.next() * 100.0;
                labels.reserve_box(text_box(corner, DVec2::new(width, 13.0)));
                x += width + r.next() * 30.0;
            }
        }
        for _ in 0..2000 {
            let size = DVec2::new(10.0 + r.next() * 150.0, 13.0);
            let b = text_box(point(&mut r), size);
            let crosses = |(a, c): (DVec2, DVec2)| clip(a, c, b).is_some();
            for rays in [false, true] {
                let ray_crosses = rays && labels.rays.iter().copied().any(crosses);
                let everything = contains(labels.bounds, b)
                    && !labels.boxes.iter().any(|o| overlap(*o, b))
                    && !labels.outlines.iter().any(|p| crosses((p.a, p.b)))
                    && !ray_crosses;
                assert_eq!(labels.fits(b, rays), everything, "{b:?}");
            }
            // Object 10 has no outline: never its own.
            let object = (r.next() * 11.0) as usize;
            let (mut own, mut other) = (f64::INFINITY, f64::INFINITY);
            for p in &labels.outlines {
                let d = segment_box_distance(p.a, p.b, b);
                if p.object == object {
                    own = own.min(d);
                } else {
                    other = other.min(d);
                }
            }
            let nearest = own.is_finite() && own <= other + 1.0;
            assert_eq!(labels.nearest_is_own(b, object), nearest, "{b:?}");
        }
        for width in [8.0, 40.0, 120.0, 400.0] {
            let size = DVec2::new(width, 13.0);
            assert_eq!(labels.scan(size), scan_everything(&labels, size));
        }
        let scanned = labels.scan(DVec2::new(120.0, 13.0)).unwrap();
        assert!(scanned.y > 200.0, "past the crowded third: {scanned}");
    }

    #[test]
    fn a_label_stays_inside_the_figure() {
        // "abcdefghij" at 13 px: 10 x 7.8 = 78 wide. Anchored at (190, 100)
        // in a 200 x 200 figure, the first ring's right place (baseline
        // start (200, 104)) runs to x 278, outside; its left place starts at
        // 190 - 10 - 78 = 102 and spans x 102..180, y 91..107: inside.
        let mut labels = Labels::new(13.0, (DVec2::ZERO, DVec2::splat(200.0)));
        let mut out = String::new();
        labels.place(&mut out, DVec2::new(190.0, 100.0), "abcdefghij", "");
        assert_eq!(out, "<text x=\"102.0\" y=\"104.0\">abcdefghij</text>\n");
    }

    #[test]
    fn a_label_moves_off_a_ray_when_it_can() {
        // "ab" at 13 px is 15.6 wide. Anchored at (100, 100) with a ray
        // running right from it along y = 100: the right place's box
        // (110..125.6, 91..107) crosses it; the left place, x 74.4..90,
        // ends before the ray starts at x 100.
        let at = DVec2::new(100.0, 100.0);
        let mut labels = Labels::new(13.0, WIDE);
        labels.reserve_ray(at, DVec2::new(300.0, 100.0));
        let mut out = String::new();
        labels.place(&mut out, at, "ab", "");
        assert_eq!(out, "<text x=\"74.4\" y=\"104.0\">ab</text>\n");
        // The ray through the anchor both ways: left and right are crossed;
        // above, the baseline start (100 - 7.8, 100 - 10) = (92.2, 90) gives
        // the box y 77..93, clear of y = 100.
        let mut labels = Labels::new(13.0, WIDE);
        labels.reserve_ray(DVec2::new(0.0, 100.0), DVec2::new(300.0, 100.0));
        let mut out = String::new();
        labels.place(&mut out, at, "ab", "");
        assert_eq!(out, "<text x=\"92.2\" y=\"90.0\">ab</text>\n");
    }

    #[test]
    fn a_label_crosses_a_ray_rather_than_a_mark_when_all_near_is_crossed() {
        // Horizontal rays every 5 px cover every place near (100, 100): the
        // label takes the first place free of marks, the first ring's right
        // (110, 104), unless a mark is there: then its left (74.4, 104).
        let rays = |labels: &mut Labels| {
            for i in 0..120 {
                let y = i as f64 * 5.0;
                labels.reserve_ray(DVec2::new(0.0, y), DVec2::new(800.0, y));
            }
        };
        let at = DVec2::new(100.0, 100.0);
        let mut labels = Labels::new(13.0, WIDE);
        rays(&mut labels);
        let mut out = String::new();
        labels.place(&mut out, at, "ab", "");
        assert_eq!(out, "<text x=\"110.0\" y=\"104.0\">ab</text>\n");
        let mut labels = Labels::new(13.0, WIDE);
        rays(&mut labels);
        labels.reserve(DVec2::new(115.0, 100.0), 3.0);
        let mut out = String::new();
        labels.place(&mut out, at, "ab", "");
        assert_eq!(out, "<text x=\"74.4\" y=\"104.0\">ab</text>\n");
    }

    #[test]
    fn a_name_goes_where_its_own_outline_is_nearest() {
        // Object 0's outline runs down x = 100, object 1's down x = 130,
        // both y 50..150. "ab" (15.6 x 13) named at (100, 100): the first
        // place, right (box x 110..125.6, y 91..107), crosses nothing but
        // is 4.4 from object 1's line and 10 from its own. `place` takes
        // it; `place_name` takes the next, left (x 74.4..90): 10 from its
        // own, 40 from the other.
        let outlined = || {
            let mut labels = Labels::new(13.0, WIDE);
            for (x, object) in [(100.0, 0), (130.0, 1)] {
                labels.reserve_outline(DVec2::new(x, 50.0), DVec2::new(x, 150.0), object);
            }
            labels
        };
        let at = DVec2::new(100.0, 100.0);
        let mut out = String::new();
        outlined().place(&mut out, at, "ab", "");
        assert_eq!(out, "<text x=\"110.0\" y=\"104.0\">ab</text>\n");
        let mut out = String::new();
        outlined().place_name(&mut out, at, 0, "ab", "");
        assert_eq!(out, "<text x=\"74.4\" y=\"104.0\">ab</text>\n");
        // Object 1's name from (130, 100): right of its line is free.
        let mut out = String::new();
        outlined().place_name(&mut out, DVec2::new(130.0, 100.0), 1, "ab", "");
        assert_eq!(out, "<text x=\"140.0\" y=\"104.0\">ab</text>\n");
    }
}
