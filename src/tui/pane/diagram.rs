//! The ray diagram pane: the textbook figure of the selected pixel's ray
//! tree, drawn in Braille on a ratatui `Canvas` — object outlines, the eye,
//! the lights, every ray, and the current event's ray in white.

use glam::DVec2;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::{Line as TextLine, Span};
use ratatui::widgets::canvas::{Canvas, Circle, Context, Line};
use ratatui::widgets::{Block, Widget};

use crate::math::to_rgb8;
use crate::scene::Scene;

use crate::diagram::{
    Outline, Projection, Segment, Stroke, involved_objects, outline, ray_segments,
};
use crate::tui::App;
use crate::tui::view::labels::{Wanted, cell, place};
use crate::tui::view::stepper::progress;

/// Scenes with more objects show only those the pixel's rays meet.
const MAX_OUTLINES: usize = 300;

pub fn stroke_color(stroke: Stroke) -> Color {
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

/// The legend line for the pane's bottom border.
pub fn legend() -> TextLine<'static> {
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

/// The world rectangle shown: every ray, light and met object, with a
/// margin, stretched so that one unit is as wide as it is tall on screen
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

/// Draws the app's diagram into `area` (block included): its pixel's tree
/// at its current event, on its plane, panned and zoomed as it says.
pub fn render(area: Rect, buf: &mut ratatui::buffer::Buffer, block: Block, app: &App) {
    let (scene, pixel, screen) = (app.session().scene(), app.pixel(), app.screen());
    let (tree, current) = (pixel.tree(), pixel.current());
    let (plane, view) = (screen.plane(), screen.diagram_pan_zoom());
    let inner = block.inner(area);
    let projection = Projection::new(plane, scene, tree);
    let (segments, blockers) = ray_segments(tree, scene, &projection, progress(tree, current));
    let involved = involved_objects(tree);
    let shown: Vec<usize> = if scene.objects.len() <= MAX_OUTLINES {
        (0..scene.objects.len()).collect()
    } else {
        involved.clone()
    };
    let outlines: Vec<(usize, Vec<Outline>)> = shown
        .iter()
        .map(|&i| (i, outline(&scene.objects[i].shape, &projection)))
        .collect();
    let eye = projection.project(scene.camera.eye);
    let lights: Vec<(DVec2, &str)> = scene
        .lights
        .iter()
        .map(|l| (projection.project(l.position), l.name.as_str()))
        .collect();
    let mut points: Vec<DVec2> = segments.iter().flat_map(|s| [s.from, s.to]).collect();
    points.push(eye);
    points.extend(lights.iter().map(|l| l.0));
    for (i, shapes) in &outlines {
        if involved.contains(i) {
            points.extend(shapes.iter().flat_map(Outline::points));
        }
    }
    let (x, y) = bounds(&points, inner);
    // The projection's origin is the primary ray's first hit (the eye on
    // a miss): the zoom magnifies about it, as `raystep diagram --zoom`.
    let (x, y) = view.window(x, y, (0.0, 0.0));
    let paint = |ctx: &mut Context| {
        for (i, shapes) in &outlines {
            for shape in shapes {
                draw_outline(ctx, shape, object_color(scene, *i), x, y);
            }
        }
        ctx.layer();
        let draw = |ctx: &mut Context, s: &Segment| {
            ctx.draw(&Line::new(
                s.from.x,
                s.from.y,
                s.to.x,
                s.to.y,
                stroke_color(s.stroke),
            ));
        };
        segments
            .iter()
            .filter(|s| s.stroke != Stroke::Current)
            .for_each(|s| draw(ctx, s));
        ctx.layer();
        segments
            .iter()
            .filter(|s| s.stroke == Stroke::Current)
            .for_each(|s| draw(ctx, s));
    };
    Canvas::default()
        .block(block)
        .x_bounds(x)
        .y_bounds(y)
        .paint(paint)
        .render(area, buf);
    // Most important first: the eye, the lights, the blockers, then names;
    // the eye's and lights' markers keep a blank cell before their name.
    let mut labels = vec![Label::marker(eye, "◉ ", Color::Cyan)];
    labels.extend(
        lights
            .iter()
            .map(|(p, _)| Label::marker(*p, "☼ ", Color::Yellow)),
    );
    labels.extend(
        blockers
            .iter()
            .map(|b| Label::marker(b.at, "×", stroke_color(b.stroke))),
    );
    labels.push(Label::named(eye, "eye", 2, Color::Cyan));
    labels.extend(
        lights
            .iter()
            .map(|(p, name)| Label::named(*p, name, 2, Color::Yellow)),
    );
    for (i, shapes) in outlines.iter().filter(|(i, _)| involved.contains(i)) {
        let hit = (tree.nodes.iter())
            .filter_map(|n| n.hit.as_ref())
            .find(|h| h.object_index == *i)
            .map(|h| projection.project(h.point));
        if let Some(at) = shapes.first().and_then(|s| label_point(s, hit)) {
            let name = &scene.objects[*i].name;
            labels.push(Label::named(at, name, 0, Color::DarkGray));
        }
    }
    write_labels(buf, inner, (x, y), &labels);
}

/// A label over the drawing: a marker on its point, or a name that many
/// cells right of it (after the eye's or a light's marker and a space).
struct Label<'a> {
    point: DVec2,
    text: &'a str,
    marker: bool,
    after: i32,
    colour: Color,
}

impl<'a> Label<'a> {
    fn marker(point: DVec2, text: &'a str, colour: Color) -> Self {
        Self::new(point, text, true, 0, colour)
    }

    fn named(point: DVec2, text: &'a str, after: i32, colour: Color) -> Self {
        Self::new(point, text, false, after, colour)
    }

    fn new(point: DVec2, text: &'a str, marker: bool, after: i32, colour: Color) -> Self {
        Label {
            point,
            text,
            marker,
            after,
            colour,
        }
    }
}

/// Writes the labels over the drawing, none over another (`view::labels`);
/// earlier ones win.
fn write_labels(
    buf: &mut ratatui::buffer::Buffer,
    inner: Rect,
    (x, y): ([f64; 2], [f64; 2]),
    labels: &[Label],
) {
    let size = (inner.width, inner.height);
    let shown: Vec<(Wanted, &Label)> = labels
        .iter()
        .filter(|l| !l.text.is_empty())
        .filter_map(|l| {
            let (col, row) = cell((l.point.x, l.point.y), x, y, size)?;
            let at = (col + l.after, row);
            Some((
                Wanted {
                    at,
                    text: l.text,
                    fixed: l.marker,
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
