//! `raystep diagram`: a pixel's ray diagram as an SVG figure for a slide,
//! the assembled `Diagram` the debugger's diagram pane also draws (objects
//! cut by the plane, the eye, the lights, every ray coloured by kind with an arrowhead
//! showing its direction, blocked shadow rays marked where they are
//! blocked, polygons passed by ringed where the ray crosses their plane, spheres
//! passed by where it comes nearest,
//! lights facing away from a hit dotted), with labels that never overlap,
//! never sit on a mark and stay inside the figure, and a legend.

mod caption;
mod cell_index;
pub mod crossing_figure;
mod escaping;
mod frame_geometry;
mod labels;
mod legend;
mod plane_map;

use std::fmt::Write;

use glam::DVec2;

pub use self::caption::Caption;
use self::frame_geometry::{Box2, clip};
use self::labels::Labels;
use self::plane_map::{PlaneMap, label_anchor, outline_segments, write_outline};
use super::{Anchor, Diagram, DiagramPlane, Named, Role, Stroke};
use raystep_engine::record::light_label;

/// The figure's size in SVG units (pixels), and its margin.
const WIDTH: f64 = 800.0;
const HEIGHT: f64 = 600.0;
const MARGIN: f64 = 40.0;
/// The legend's band at the bottom: two rows.
const LEGEND: f64 = 44.0;
const FONT_SIZE: f64 = 13.0;
/// A note under the heading (rays seen edge-on).
const NOTE_SIZE: f64 = 11.0;
/// Where the scene is drawn: below the title, above the legend. Rays,
/// outlines and marks are cut at its edge, and labels stay inside it.
const FRAME: Box2 = (
    DVec2::new(6.0, 34.0),
    DVec2::new(WIDTH - 6.0, HEIGHT - LEGEND - 4.0),
);
const PASSED: &str = "#555555";
const FACES_AWAY: &str = "#999999";

fn stroke_colour(stroke: Stroke) -> &'static str {
    match stroke {
        Stroke::Primary => "#0077bb",
        Stroke::Reflected => "#cc3399",
        Stroke::Transmitted => "#33bbee",
        Stroke::ShadowLit => "#ddaa33",
        Stroke::ShadowPartial => "#ee7733",
        Stroke::ShadowBlocked => "#cc3311",
        Stroke::Normal => "#009988",
        Stroke::Later | Stroke::Current => "#777777",
    }
}

/// The arrowhead marker of a ray's stroke; none for a normal.
fn arrow(stroke: Stroke) -> Option<&'static str> {
    match stroke {
        Stroke::Primary => Some("arrow-primary"),
        Stroke::Reflected => Some("arrow-reflected"),
        Stroke::Transmitted => Some("arrow-transmitted"),
        Stroke::ShadowLit => Some("arrow-lit"),
        Stroke::ShadowPartial => Some("arrow-partial"),
        Stroke::ShadowBlocked => Some("arrow-blocked"),
        _ => None,
    }
}

/// The whole figure of `diagram`, magnified `zoom` times (at least 1)
/// about the primary ray's first hit, with no scene named.
pub fn figure(diagram: &Diagram, zoom: f64) -> String {
    slide(diagram, zoom, &Caption::default())
}

/// The figure of `raystep diagram`: `figure`, its title naming the scene
/// and the options it was drawn with.
pub fn slide(diagram: &Diagram, zoom: f64, caption: &Caption) -> String {
    // The projection's origin is the primary ray's first hit (the eye on a miss).
    let map = PlaneMap::fit(&diagram.extent()).zoomed(zoom, DVec2::ZERO);

    let zoomed = if zoom > 1.0 {
        format!(", magnified {zoom}×")
    } else {
        String::new()
    };
    let view = format!("{} (in the camera's frame){zoomed}", diagram.plane.name());
    let (title, heading) = caption.elements(diagram.pixel, &view, (MARGIN, 24.0));
    let mut out = header(&title);
    out.push_str(&heading);
    let mut labels = Labels::new(FONT_SIZE, FRAME);
    if diagram.rays_edge_on() {
        write_edge_on_note(&mut out, &mut labels, diagram.plane);
    }
    out.push_str("<g clip-path=\"url(#frame)\">\n");
    // A slide shows what the rays meet or pass by, not the rest of the scene.
    let drawn = (diagram.objects.iter()).filter(|o| o.role != Role::Context);
    for (object, shape) in drawn.flat_map(|o| o.shapes.iter().map(|s| (o.object, s))) {
        write_outline(&mut out, &map, shape);
        for (a, b) in outline_segments(shape, &map) {
            if let Some((a, b)) = clip(a, b, FRAME) {
                labels.reserve_outline(a, b, object);
            }
        }
    }
    out.push_str("</g>\n");
    for line in &diagram.faces_away {
        write_line(
            &mut out,
            &mut labels,
            &map,
            (line.hit, line.light),
            FACES_AWAY,
            " stroke-dasharray=\"2 4\"",
            None,
        );
    }
    for segment in &diagram.segments {
        let dash = match segment.stroke {
            Stroke::ShadowLit | Stroke::ShadowPartial | Stroke::ShadowBlocked => {
                " stroke-dasharray=\"6 4\""
            }
            _ => "",
        };
        let colour = stroke_colour(segment.stroke);
        let ends = (segment.from, segment.to);
        write_line(
            &mut out,
            &mut labels,
            &map,
            ends,
            colour,
            dash,
            arrow(segment.stroke),
        );
    }
    write_marks(&mut out, &mut labels, &map, diagram);
    write_labels(&mut out, &mut labels, &map, diagram);
    legend::write(&mut out, &diagram.legend());
    out.push_str("</svg>\n");
    out
}

/// Says why every ray is drawn on one line, and which plane shows them
/// apart: a figure that looks like one ray is not taken for the tree.
fn write_edge_on_note(out: &mut String, labels: &mut Labels, plane: DiagramPlane) {
    let other = match plane {
        DiagramPlane::Primary => "--plane top",
        _ => "--plane ray",
    };
    let note = format!(
        "every ray lies in one plane seen edge-on here, one line: {other} shows them apart"
    );
    let corner = DVec2::new(MARGIN, 48.0);
    labels.set_font_size(NOTE_SIZE);
    labels.reserve_text(corner, &note);
    labels.set_font_size(FONT_SIZE);
    let _ = writeln!(
        out,
        "<text x=\"{}\" y=\"{}\" font-size=\"{NOTE_SIZE}\" fill=\"#555555\">{}</text>",
        corner.x,
        corner.y,
        escaping::escape(&note)
    );
}

/// The SVG element, its arrowheads (one per ray colour: a marker cannot
/// take its line's colour in SVG 1.1) and the frame's clip path; `title`
/// is the `<title>` element, the SVG's first child.
fn header(title: &str) -> String {
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         viewBox=\"0 0 {WIDTH} {HEIGHT}\" font-family=\"Helvetica, Arial, sans-serif\" \
         font-size=\"{FONT_SIZE}\">\n{title}<defs>\n"
    );
    for stroke in [
        Stroke::Primary,
        Stroke::Reflected,
        Stroke::Transmitted,
        Stroke::ShadowLit,
        Stroke::ShadowPartial,
        Stroke::ShadowBlocked,
    ] {
        // The tip stops 8 units short of the line's end, clear of a light's
        // disc (radius 7) or a hit's dot.
        let _ = writeln!(
            out,
            "<marker id=\"{}\" markerWidth=\"10\" markerHeight=\"8\" refX=\"18\" refY=\"4\" \
             orient=\"auto\" markerUnits=\"userSpaceOnUse\"><path d=\"M0 0L10 4L0 8z\" fill=\"{}\"/></marker>",
            arrow(stroke).unwrap_or_default(),
            stroke_colour(stroke)
        );
    }
    let (lo, hi) = FRAME;
    let _ = writeln!(
        out,
        "<clipPath id=\"frame\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>\n</defs>\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>",
        lo.x,
        lo.y,
        hi.x - lo.x,
        hi.y - lo.y
    );
    out
}

/// A line in the plane, cut at the frame's edge (none when wholly off it),
/// kept free of labels; `arrow` names its arrowhead, drawn when the line
/// is long enough to hold one.
fn write_line(
    out: &mut String,
    labels: &mut Labels,
    map: &PlaneMap,
    (from, to): (DVec2, DVec2),
    colour: &str,
    dash: &str,
    arrow: Option<&str>,
) {
    let Some((a, b)) = clip(map.to_figure(from), map.to_figure(to), FRAME) else {
        return;
    };
    labels.reserve_ray(a, b);
    let head = match arrow {
        Some(id) if (b - a).length() > 24.0 => format!(" marker-end=\"url(#{id})\""),
        _ => String::new(),
    };
    let _ = writeln!(
        out,
        "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{colour}\" stroke-width=\"2\"{dash}{head}/>",
        a.x, a.y, b.x, b.y
    );
}

/// A point's place in the figure, when it is inside the frame.
fn framed(map: &PlaneMap, p: DVec2) -> Option<DVec2> {
    let at = map.to_figure(p);
    frame_geometry::contains(FRAME, (at, at)).then_some(at)
}

/// The blockers' ×, the hits' dots, the passed-by rings, the eye and the
/// lights, each reserved so no label covers it.
fn write_marks(out: &mut String, labels: &mut Labels, map: &PlaneMap, diagram: &Diagram) {
    for (p, b) in (diagram.blockers.iter()).filter_map(|b| Some((framed(map, b.at)?, b))) {
        let colour = stroke_colour(b.stroke);
        labels.reserve(p, 5.0);
        let _ = writeln!(
            out,
            "<path d=\"M{:.1} {:.1}l8 8m0 -8l-8 8\" stroke=\"{colour}\" stroke-width=\"2.5\"/>",
            p.x - 4.0,
            p.y - 4.0
        );
    }
    for p in diagram.hits.iter().filter_map(|h| framed(map, h.at)) {
        circle(out, labels, p, 3.0, "fill=\"black\"");
    }
    for p in diagram.passed.iter().filter_map(|m| framed(map, m.at)) {
        let ring =
            format!("class=\"passed-by\" fill=\"none\" stroke=\"{PASSED}\" stroke-width=\"2\"");
        circle(out, labels, p, 6.0, &ring);
    }
    if let Some(e) = framed(map, diagram.eye) {
        circle(out, labels, e, 5.0, "fill=\"black\"");
    }
    for p in diagram.lights.iter().filter_map(|l| framed(map, l.at)) {
        circle(out, labels, p, 7.0, "fill=\"#ffdd44\" stroke=\"#aa8800\"");
    }
}

/// A round mark of radius `r`, kept free of labels (with a unit to spare).
fn circle(out: &mut String, labels: &mut Labels, p: DVec2, r: f64, attrs: &str) {
    labels.reserve(p, r + 1.0);
    let _ = writeln!(
        out,
        "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"{r}\" {attrs}/>",
        p.x, p.y
    );
}

/// The names, once every mark and ray is down; none for what lies off the
/// frame. A light is called "light NAME" on a slide, where no symbol says
/// what it is.
fn write_labels(out: &mut String, labels: &mut Labels, map: &PlaneMap, diagram: &Diagram) {
    for label in diagram.labels() {
        let at = match label.anchor {
            Anchor::Point(p) => framed(map, p),
            // A plane is named where a ray hits it, if one does in the frame.
            Anchor::Outline { outline, hits } => {
                let hit = hits.iter().find_map(|h| framed(map, *h));
                label_anchor(outline, map, hit)
                    .filter(|a| frame_geometry::contains(FRAME, (*a, *a)))
            }
        };
        let Some(at) = at else { continue };
        let (text, fill) = match label.named {
            Named::Eye => (label.text, "black"),
            Named::Light => (light_label(&label.text), "#886600"),
            Named::Object(_) => (label.text, "#444444"),
            Named::PassedBy(_) => (label.text, PASSED),
        };
        let attrs = format!("fill=\"{fill}\"");
        match label.named {
            Named::Object(object) => labels.place_name(out, at, object, &text, &attrs),
            _ => labels.place(out, at, &text, &attrs),
        }
    }
}
