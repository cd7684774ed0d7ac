//! The ray diagram pane: the textbook figure of the selected pixel's ray
//! tree, drawn in Braille on a ratatui `Canvas`. It only draws the
//! assembled `raystep_tools::diagram::Diagram` (the one `raystep diagram` writes as
//! SVG): object outlines, the eye (◉), the lights (☼), every ray with the
//! current event's in white, blockers (×), passed-by rings (○) and dotted
//! lines to lights that face away.

use std::borrow::Cow;
use std::sync::Arc;

use glam::DVec2;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::{Line as TextLine, Span};
use ratatui::widgets::canvas::{Canvas, Circle, Context, Line, Points};
use ratatui::widgets::{Block, Widget};

use crate::tui::App;
use crate::tui::view::canvas_lines::{CanvasLines, View};
use crate::tui::view::cell_labels::{Wanted, cell, place};
use crate::tui::view::pan_zoom::PanZoom;
use raystep_engine::scene::Scene;
use raystep_model::math::to_rgb8;
use raystep_tools::diagram::{
    Anchor, Diagram, LegendRow, Named, ObjectOutline, Outline, Progress, Segment, Stroke,
};

/// The passed-by ring, and its and the faces-away line's key entries.
const PASSED_BY: &str = "○";
const PASSED_BY_KEY: &str = "○ passed by";
const FACES_AWAY_KEY: &str = "┈ light faces away";
/// Marks that are no ray: passed-by rings and faces-away lines.
const MARK_GREY: Color = Color::Gray;

fn stroke_color(stroke: Stroke) -> Color {
    match stroke {
        Stroke::Primary => Color::Cyan,
        Stroke::Reflected => Color::Magenta,
        Stroke::Transmitted => Color::LightBlue,
        Stroke::ShadowLit => Color::Yellow,
        Stroke::ShadowPartial => Color::Rgb(0xee, 0x77, 0x33),
        Stroke::ShadowBlocked => Color::Red,
        Stroke::Normal => Color::Green,
        Stroke::Later => Color::DarkGray,
        Stroke::Current => Color::White,
    }
}

/// The ray key for the pane's bottom border (the marks' key goes in
/// the drawing: a narrow pane's border has no room left).
fn legend() -> TextLine<'static> {
    let item = |name: &'static str, stroke| {
        Span::styled(format!(" {name}"), Style::new().fg(stroke_color(stroke)))
    };
    TextLine::from(vec![
        item("primary", Stroke::Primary),
        item("reflected", Stroke::Reflected),
        item("transmitted", Stroke::Transmitted),
        // Shadow rays by S (MODEL §4), short enough for a narrow pane.
        item("S=1", Stroke::ShadowLit),
        item("0<S<1", Stroke::ShadowPartial),
        item("S=0 ", Stroke::ShadowBlocked),
    ])
}

/// The world rectangle shown: the diagram's extent (every ray, the eye,
/// the lights, what the rays meet or pass by), with a margin, stretched so that one unit is as wide as it is tall on screen
/// (a Braille dot is about square).
fn bounds(points: &[DVec2], area: Rect) -> ([f64; 2], [f64; 2]) {
    let min = points.iter().fold(DVec2::INFINITY, |a, &p| a.min(p));
    let max = points.iter().fold(DVec2::NEG_INFINITY, |a, &p| a.max(p));
    let (min, max) = if min.is_finite() && max.is_finite() {
        (min, max)
    } else {
        (DVec2::splat(-1.0), DVec2::splat(1.0))
    };
    let centre = (min + max) / 2.0;
    let size = (max - min).max(DVec2::splat(1e-3)) * 1.1;
    let dots = DVec2::new(
        area.width.max(1) as f64 * 2.0,
        area.height.max(1) as f64 * 4.0,
    );
    let per_dot = (size.x / dots.x).max(size.y / dots.y);
    let half = dots * per_dot / 2.0;
    (
        [centre.x - half.x, centre.x + half.x],
        [centre.y - half.y, centre.y + half.y],
    )
}

/// Where an object's name goes: above a circle, at a polygon's first
/// corner, on a plane's line where a ray hits it (`hit`; none if no ray does).
fn label_point(outline: &Outline, hit: Option<DVec2>) -> Option<DVec2> {
    match outline {
        Outline::Circle { center, radius } => Some(*center + DVec2::new(-radius / 2.0, *radius)),
        Outline::Polyline(points) => points.first().copied(),
        Outline::Line { .. } => hit,
    }
}

fn draw_outline(ctx: &mut Context, outline: &Outline, color: Color, x: [f64; 2], y: [f64; 2]) {
    match outline {
        Outline::Circle { center, radius } => ctx.draw(&Circle {
            x: center.x,
            y: center.y,
            radius: *radius,
            color,
        }),
        Outline::Polyline(points) => {
            for pair in points.windows(2) {
                ctx.draw(&Line::new(
                    pair[0].x, pair[0].y, pair[1].x, pair[1].y, color,
                ));
            }
        }
        Outline::Line { normal, c } => {
            // a·p + c = 0: solve for the coordinate the line is steeper in.
            let (x1, y1, x2, y2) = if normal.y.abs() > normal.x.abs() {
                let at = |u: f64| -(normal.x * u + c) / normal.y;
                (x[0], at(x[0]), x[1], at(x[1]))
            } else {
                let at = |v: f64| -(normal.y * v + c) / normal.x;
                (at(y[0]), y[0], at(y[1]), y[1])
            };
            ctx.draw(&Line::new(x1, y1, x2, y2, color));
        }
    }
}

/// A material's colour, darkened so rays stand out against outlines.
fn object_color(scene: &Scene, object: usize) -> Color {
    let [r, g, b] = to_rgb8(scene.material_of(object).color * 0.75);
    Color::Rgb(r, g, b)
}

/// The marks the ray key in the border has no room for: drawn in the
/// drawing's bottom-right corner, only when the diagram holds one.
fn mark_key(diagram: &Diagram) -> Vec<(&'static str, Color)> {
    (diagram.legend().iter())
        .filter_map(|row| match row {
            LegendRow::PassedBy => Some((PASSED_BY_KEY, MARK_GREY)),
            LegendRow::FacesAway => Some((FACES_AWAY_KEY, MARK_GREY)),
            _ => None,
        })
        .collect()
}

/// Draws the app's diagram into `area` (block included): its pixel's tree
/// at its current event, on its plane, panned and zoomed as it says.
pub(crate) fn render(area: Rect, buf: &mut ratatui::buffer::Buffer, block: Block, app: &App) {
    let (scene, pixel, screen) = (app.session().scene(), app.pixel(), app.screen());
    let diagram = pixel.diagram(scene, screen.plane());
    let progress = Progress::at(pixel.tree(), pixel.current());
    let view = screen.diagram_pan_zoom();
    let lines = |view| pixel.canvas_lines(scene, screen.plane(), view);
    draw(
        area,
        buf,
        block,
        (diagram, progress),
        scene,
        (view, Some(&lines)),
    );
}

/// The segments of a diagram grouped for a view (`view::canvas_lines`),
/// kept between frames by the caller; `None` draws every segment.
type Lines<'a> = Option<&'a dyn Fn(View) -> Arc<CanvasLines>>;

/// Paints `diagram` (of a pixel of `scene`) into `area`, its rays stroked
/// with the step-through at `progress`, the block's border holding the ray
/// key, its window fitted to the diagram then panned and zoomed by `view`;
/// of the segments painting one line of dots, only the last one `lines`
/// keeps (the same cells: `view::canvas_lines`).
fn draw(
    area: Rect,
    buf: &mut ratatui::buffer::Buffer,
    block: Block,
    (diagram, progress): (&Diagram, Progress),
    scene: &Scene,
    (view, lines): (PanZoom, Lines),
) {
    let block = block.title_bottom(legend());
    let inner = block.inner(area);
    let (x, y) = bounds(&diagram.extent(), inner);
    // The projection's origin is the primary ray's first hit (the eye on
    // a miss): the zoom magnifies about it, as `raystep diagram --zoom`.
    let (x, y) = view.window(x, y, (0.0, 0.0));
    // In object order, as the scene lists them: where two cross, the later
    // one's colour shows.
    let mut objects: Vec<&ObjectOutline> = diagram.objects.iter().collect();
    objects.sort_by_key(|o| o.object);
    let grouped = lines.map(|lines| {
        lines(View {
            x,
            y,
            cells: (inner.width, inner.height),
        })
    });
    // A dot every third Braille dot across.
    let spacing = 3.0 * (x[1] - x[0]) / (f64::from(inner.width.max(1)) * 2.0);
    let paint = |ctx: &mut Context| {
        for object in &objects {
            for shape in &object.shapes {
                draw_outline(ctx, shape, object_color(scene, object.object), x, y);
            }
        }
        ctx.layer();
        for line in &diagram.faces_away {
            ctx.draw(&Points {
                coords: &dotted(line.hit, line.light, spacing),
                color: MARK_GREY,
            });
        }
        let draw = |ctx: &mut Context, s: &Segment, stroke| {
            ctx.draw(&Line::new(
                s.from.x,
                s.from.y,
                s.to.x,
                s.to.y,
                stroke_color(stroke),
            ));
        };
        let segments = &diagram.segments;
        let current = |i: usize| segments[i].stroke_at(progress) == Stroke::Current;
        // The rays, then the current one on its own layer above them.
        let layers: [Vec<usize>; 2] = match &grouped {
            Some(lines) => [lines.kept(|i| !current(i)), lines.kept(current)],
            None => [
                (0..segments.len()).filter(|&i| !current(i)).collect(),
                (0..segments.len()).filter(|&i| current(i)).collect(),
            ],
        };
        for (n, layer) in layers.iter().enumerate() {
            if n > 0 {
                ctx.layer();
            }
            for &i in layer {
                draw(ctx, &segments[i], segments[i].stroke_at(progress));
            }
        }
    };
    Canvas::default()
        .block(block)
        .x_bounds(x)
        .y_bounds(y)
        .paint(paint)
        .render(area, buf);
    // Most important first: the eye, the lights, the blockers, the
    // passed-by rings, the key to the marks, then names; the eye's and
    // lights' markers keep a blank cell before their name.
    let mut labels = vec![Label::marker(diagram.eye, "◉ ", Color::Cyan)];
    labels.extend((diagram.lights.iter()).map(|l| Label::marker(l.at, "☼ ", Color::Yellow)));
    labels.extend(
        (diagram.blockers.iter()).map(|b| Label::marker(b.at, "×", stroke_color(b.stroke))),
    );
    let rings = labels.len();
    labels.extend((diagram.passed.iter()).map(|m| Label::marker(m.at, PASSED_BY, MARK_GREY)));
    let key = mark_key(diagram);
    let key_rows = key.len() as i32;
    let keys = key.iter().enumerate().map(|(i, (text, colour))| {
        // Right-aligned on the drawing's last rows.
        let col = i32::from(inner.width) - text.chars().count() as i32;
        let row = i32::from(inner.height) - key_rows + i as i32;
        Label::at_cell((col, row), text, *colour)
    });
    labels.extend(keys);
    for label in diagram.labels() {
        let (point, after, colour) = match (label.named, label.anchor) {
            (Named::Eye, Anchor::Point(p)) => (p, 2, Color::Cyan),
            (Named::Light, Anchor::Point(p)) => (p, 2, Color::Yellow),
            (Named::PassedBy(mark), Anchor::Point(p)) => {
                // Said only beside its ring: on a cell another marker took,
                // it would name that one.
                let name = Label::named(p, label.text, 2, MARK_GREY);
                labels.push(Label {
                    with: Some(rings + mark),
                    ..name
                });
                continue;
            }
            (_, Anchor::Point(p)) => (p, 0, Color::DarkGray),
            (_, Anchor::Outline { outline, hits }) => {
                let Some(at) = label_point(outline, hits.first().copied()) else {
                    continue;
                };
                (at, 0, Color::DarkGray)
            }
        };
        labels.push(Label::named(point, label.text, after, colour));
    }
    write_labels(buf, inner, (x, y), &labels);
}

/// Points from `a` to `b` every `spacing` (a dotted line), none when the
/// spacing is not a positive length.
fn dotted(a: DVec2, b: DVec2, spacing: f64) -> Vec<(f64, f64)> {
    let n = ((b - a).length() / spacing).floor();
    if !(n.is_finite() && n >= 1.0) {
        return Vec::new();
    }
    // Bounded so that a deep zoom on a long line stays cheap.
    let n = n.min(100_000.0) as usize;
    (0..=n)
        .map(|i| a.lerp(b, i as f64 / n as f64))
        .map(|p| (p.x, p.y))
        .collect()
}

/// A label over the drawing: a marker on its point, or a name that many
/// cells right of it (after the eye's or a light's marker and a space), or
/// a key entry asked at a cell.
struct Label<'a> {
    at: Place,
    text: Cow<'a, str>,
    marker: bool,
    colour: Color,
    /// Shown only with the label at this index (a ring's name with it).
    with: Option<usize>,
}

/// Where a label is asked for.
enum Place {
    /// At a point of the plane, `after` cells to its right.
    Point { point: DVec2, after: i32 },
    /// At a cell of the drawing area.
    Cell((i32, i32)),
}

impl<'a> Label<'a> {
    fn marker(point: DVec2, text: &'a str, colour: Color) -> Self {
        Label {
            at: Place::Point { point, after: 0 },
            text: Cow::Borrowed(text),
            marker: true,
            colour,
            with: None,
        }
    }

    fn named(point: DVec2, text: impl Into<Cow<'a, str>>, after: i32, colour: Color) -> Self {
        Label {
            at: Place::Point { point, after },
            text: text.into(),
            marker: false,
            colour,
            with: None,
        }
    }

    fn at_cell(cell: (i32, i32), text: &'a str, colour: Color) -> Self {
        Label {
            at: Place::Cell(cell),
            text: Cow::Borrowed(text),
            marker: false,
            colour,
            with: None,
        }
    }
}

/// Writes the labels over the drawing, none over another (`view::cell_labels`);
/// earlier ones win.
fn write_labels(
    buf: &mut ratatui::buffer::Buffer,
    inner: Rect,
    (x, y): ([f64; 2], [f64; 2]),
    labels: &[Label],
) {
    let size = (inner.width, inner.height);
    // Where each label is among those shown (a companion's index moves).
    let mut shown_at = vec![None; labels.len()];
    let mut shown_so_far = 0;
    let shown: Vec<(Wanted, &Label)> = labels
        .iter()
        .enumerate()
        .filter(|(_, l)| !l.text.is_empty())
        .filter_map(|(i, l)| {
            let at = match l.at {
                Place::Point { point, after } => {
                    let (col, row) = cell((point.x, point.y), x, y, size)?;
                    (col + after, row)
                }
                Place::Cell(at) => at,
            };
            // A companion not shown: `place` leaves the label out with it.
            let with = l.with.map(|c| shown_at[c].unwrap_or(usize::MAX));
            shown_at[i] = Some(shown_so_far);
            shown_so_far += 1;
            Some((
                Wanted {
                    at,
                    text: &l.text,
                    fixed: l.marker,
                    with,
                },
                l,
            ))
        })
        .collect();
    let asked: Vec<Wanted> = shown.iter().map(|w| w.0).collect();
    for (placed, (_, label)) in place(&asked, size).into_iter().zip(&shown) {
        let Some(placed) = placed else { continue };
        let style = Style::new().fg(label.colour);
        let style = if label.marker { style.bold() } else { style };
        buf.set_string(
            inner.x + placed.at.0,
            inner.y + placed.at.1,
            &placed.text,
            style,
        );
    }
}

#[cfg(test)]
mod tests {
    use ratatui::buffer::Buffer;

    use super::*;
    use raystep_engine::test_scenes::pebble;
    use raystep_tools::diagram::{DiagramPlane, Progress, svg};

    #[test]
    fn both_media_draw_the_marks_of_one_diagram() {
        // The pebble scene's centre pixel (diagram::assembly's tests): an
        // eye, two lights, one ring where the primary ray passes the
        // pebble by, one light ("back") facing away from the hit, no
        // blocker. The SVG and the pane each draw every one of them, and
        // each names the ring and the dotted line in its legend.
        let (scene, tree) = pebble();
        let d = Diagram::new(&scene, &tree, DiagramPlane::Top, Progress::done(&tree));
        let figure = svg::figure(&d, 1.0);
        let area = Rect::new(0, 0, 60, 30);
        let mut buf = Buffer::empty(area);
        draw(
            area,
            &mut buf,
            Block::bordered(),
            (&d, Progress::done(&tree)),
            &scene,
            (PanZoom::fit(), None),
        );
        let text: String = (buf.content.iter()).map(|c| c.symbol()).collect();

        assert_eq!(figure.matches("class=\"passed-by\"").count(), 1);
        assert_eq!(figure.matches("stroke-dasharray=\"2 4\"").count(), 1 + 1);
        assert_eq!(figure.matches("l8 8m0 -8l-8 8").count(), 0);
        assert!(figure.contains(">passed by: ray crosses a polygon's plane"));
        assert!(figure.contains(">light facing away (no shadow ray)<"));
        assert!(figure.contains(">pebble: passed by<"));

        // The ring, and the ring in the key; the key's dotted line.
        assert_eq!(text.matches('○').count(), 1 + 1, "{text}");
        assert!(text.contains("○ passed by"), "{text}");
        assert!(text.contains("┈ light faces away"), "{text}");
        assert!(text.contains("pebble: passed by"), "{text}");
        assert_eq!(text.matches('◉').count(), 1);
        assert_eq!(text.matches('☼').count(), 2);
        assert_eq!(text.matches('×').count(), 0);
        // The dotted line: grey Braille cells (no ray or outline is grey).
        let dotted = (buf.content.iter())
            .filter(|c| c.fg == MARK_GREY)
            .filter(|c| {
                c.symbol()
                    .chars()
                    .all(|ch| ('\u{2800}'..='\u{28ff}').contains(&ch))
            })
            .count();
        assert!(dotted > 3, "{dotted}");
    }

    /// `diagram` at `progress` drawn in a `size` pane with every segment,
    /// and with only those `CanvasLines` keeps: the two buffers.
    fn drawn_both_ways(
        scene: &Scene,
        diagram: &Diagram,
        progress: Progress,
        size: (u16, u16),
        view: PanZoom,
    ) -> (Buffer, Buffer, usize) {
        let area = Rect::new(0, 0, size.0, size.1);
        let mut all = Buffer::empty(area);
        draw(
            area,
            &mut all,
            Block::bordered(),
            (diagram, progress),
            scene,
            (view, None),
        );
        let lines = std::cell::Cell::new(0);
        let group = |v| {
            let grouped = CanvasLines::new(diagram.segments.iter().map(|s| (s.from, s.to)), v);
            lines.set(grouped.lines());
            Arc::new(grouped)
        };
        let mut thinned = Buffer::empty(area);
        let kept: Lines = Some(&group);
        let parts = (diagram, progress);
        draw(
            area,
            &mut thinned,
            Block::bordered(),
            parts,
            scene,
            (view, kept),
        );
        (all, thinned, lines.get())
    }

    #[test]
    fn thinned_rays_draw_the_very_same_cells() {
        // The bench's tree: the three glass planes' pixel (16, 12) with no
        // weight cutoff and the largest budget, 65,536 rays; and the small
        // trees of the ball and the pebble. Each on every plane, at its
        // start, its middle and its end (the current ray on its own layer),
        // fitted and zoomed in 8 times (most segments then leave the window
        // and are clipped), at the bench's 200x60 and a narrow 41x13. The
        // cells (symbol and colours) must not differ in one.
        let text = include_str!("../../../tests/scenes/three-glass-planes.toml").replace(
            "[settings]\n",
            "[settings]\nmin_weight = 0\nmax_rays = 65536\n",
        );
        let scene = raystep_engine::scene::parse(std::path::Path::new("big.toml"), &text).unwrap();
        let big = raystep_engine::record::record_pixel(&scene, &scene.settings, 16, 12);
        assert_eq!(big.nodes.len(), 65536);
        let mut zoomed = PanZoom::fit();
        zoomed.zoom_by(6);
        assert!(zoomed.magnification() >= 4.0, "{}", zoomed.magnification());
        let cases = [(scene, big), pebble(), raystep_engine::test_scenes::ball()];
        for (n, (scene, tree)) in cases.iter().enumerate() {
            for plane in [DiagramPlane::Top, DiagramPlane::Side, DiagramPlane::Primary] {
                let d = Diagram::new(scene, tree, plane, Progress::done(tree));
                let events = tree.events.len();
                for at in [0, events / 2, events.saturating_sub(1)] {
                    let progress = Progress::at(tree, at);
                    for size in [(200, 60), (41, 13)] {
                        for view in [PanZoom::fit(), zoomed] {
                            let (all, thinned, lines) =
                                drawn_both_ways(scene, &d, progress, size, view);
                            let case = format!("{n} {plane:?} at {at} {size:?} {view:?}");
                            assert_eq!(all, thinned, "{case}");
                            // The big tree's thousands of segments fall on
                            // far fewer lines of dots: the point of it.
                            if n == 0 && view.is_fit() && size == (200, 60) {
                                let segments = d.segments.len();
                                assert!(lines * 10 < segments, "{case}: {lines} of {segments}");
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_dotted_line_has_a_dot_every_spacing() {
        // 10 long at spacing 3: three whole steps, so four dots, 10/3 apart.
        let dots = dotted(DVec2::ZERO, DVec2::new(10.0, 0.0), 3.0);
        assert_eq!(dots.len(), 4);
        assert_eq!(dots[3], (10.0, 0.0));
        assert!(dotted(DVec2::ZERO, DVec2::ZERO, 3.0).is_empty());
        assert!(dotted(DVec2::ZERO, DVec2::X, 0.0).is_empty());
    }
}
