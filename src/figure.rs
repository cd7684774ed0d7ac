//! `raystep diagram`: a pixel's ray diagram as an SVG figure for a slide,
//! the same projection the debugger's diagram pane draws (objects cut by the
//! plane, the eye, the lights, every ray coloured by kind with an arrowhead
//! showing its direction, blocked shadow rays marked where they are
//! blocked, polygons passed by ringed where the ray crosses their plane, spheres
//! passed by where it comes nearest,
//! lights facing away from a hit dotted), with labels that never overlap,
//! never sit on a mark and stay inside the figure, and a legend.

pub mod crossing;
mod labels;
mod legend;
mod view;

use std::fmt::Write;

use glam::{DVec2, DVec3};

use self::labels::{Box2, Labels, clip};
use self::view::{View, label_anchor, outline_segments, write_outline};
use crate::diagram::{
    BlockerMark, DiagramPlane, Outline, Progress, Projection, Stroke, involved_objects, outline,
    ray_segments,
};
use crate::record::{NearMiss, Node, RayTree, light_label};
use crate::scene::Scene;
use crate::shapes::Shape;

/// The figure's size in SVG units (pixels), and its margin.
const WIDTH: f64 = 800.0;
const HEIGHT: f64 = 600.0;
const MARGIN: f64 = 40.0;
/// The legend's band at the bottom: two rows.
const LEGEND: f64 = 44.0;
const FONT_SIZE: f64 = 13.0;
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

/// The figure's marks in the plane, before the view maps them.
struct Marks {
    eye: DVec2,
    lights: Vec<(String, DVec2)>,
    /// Each hit: the object hit, and where.
    hits: Vec<(usize, DVec2)>,
    /// A polygon or sphere a ray passed by, its name, and where: where the
    /// ray crosses the polygon's plane, or comes nearest the sphere.
    passed: Vec<(usize, String, DVec2)>,
    /// From a hit to a light that faces away from it (no shadow ray).
    faces_away: Vec<(DVec2, DVec2)>,
}

impl Marks {
    fn new(scene: &Scene, tree: &RayTree, projection: &Projection) -> Marks {
        let p = |v| projection.project(v);
        let mut marks = Marks {
            eye: p(tree.root().origin),
            lights: (scene.lights.iter())
                .map(|l| (light_label(&l.name), p(l.position)))
                .collect(),
            hits: Vec::new(),
            passed: Vec::new(),
            faces_away: Vec::new(),
        };
        for node in &tree.nodes {
            for near in &node.near_misses {
                let shape = scene.objects.get(near.object_index).map(|o| &o.shape);
                if let Some(at) = passed_point(node, near, shape) {
                    marks
                        .passed
                        .push((near.object_index, near.object.clone(), p(at)));
                }
            }
            let Some(hit) = &node.hit else { continue };
            marks.hits.push((hit.object_index, p(hit.point)));
            for light in node.lights.iter().filter(|l| l.faces_away) {
                if let Some(l) = scene.lights.get(light.light_index) {
                    marks.faces_away.push((p(hit.point), p(l.position)));
                }
            }
        }
        marks
    }
}

/// Where a ray passed an object by: where it crosses a polygon's plane,
/// or its point nearest a sphere's centre (o + t d, t = -B / 2A).
fn passed_point(node: &Node, near: &NearMiss, shape: Option<&Shape>) -> Option<DVec3> {
    let plane = match shape {
        Some(Shape::Polygon(polygon)) => &polygon.plane,
        Some(Shape::Patch(patch)) => &patch.polygon.plane,
        _ => {
            let closest = near.closest_approach?;
            return Some(node.origin + node.direction * closest.t);
        }
    };
    // n·(o + t d) + d0 = 0 (MODEL §1's plane/ray).
    let t = -(plane.normal.dot(node.origin) + plane.d) / plane.normal.dot(node.direction);
    t.is_finite().then(|| node.origin + node.direction * t)
}

/// The whole figure of `tree` (recorded in `scene`) on `plane`, magnified
/// `zoom` times (at least 1) about the primary ray's first hit.
pub fn svg(scene: &Scene, tree: &RayTree, plane: DiagramPlane, zoom: f64) -> String {
    let projection = Projection::new(plane, scene, tree);
    // Every event reached: each ray in its own kind's colour.
    let (segments, blockers) = ray_segments(tree, scene, &projection, Progress::done(tree));
    let partial = segments.iter().any(|s| s.stroke == Stroke::ShadowPartial);
    let objects = involved_objects(tree);
    let outlines: Vec<(usize, Vec<Outline>)> = objects
        .iter()
        .copied()
        .chain(passed_objects(tree, &objects))
        .map(|o| (o, outline(&scene.objects[o].shape, &projection)))
        .collect();
    let marks = Marks::new(scene, tree, &projection);
    let mut points: Vec<DVec2> = segments.iter().flat_map(|s| [s.from, s.to]).collect();
    points.push(marks.eye);
    points.extend(marks.lights.iter().map(|l| l.1));
    points.extend(marks.passed.iter().map(|m| m.2));
    for (_, shapes) in &outlines {
        points.extend(shapes.iter().flat_map(Outline::points));
    }
    // The projection's origin is the primary ray's first hit (the eye on a miss).
    let view = View::fit(&points).zoomed(zoom, DVec2::ZERO);

    let mut out = header();
    let zoomed = if zoom > 1.0 {
        format!(", magnified {zoom}×")
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "<text x=\"{MARGIN}\" y=\"24\" font-size=\"15\">Pixel ({}, {}), {} (in the camera's frame){zoomed}</text>",
        tree.pixel.0,
        tree.pixel.1,
        plane.name()
    );
    let mut labels = Labels::new(FONT_SIZE, FRAME);
    out.push_str("<g clip-path=\"url(#frame)\">\n");
    for (_, shapes) in &outlines {
        for shape in shapes {
            write_outline(&mut out, &view, shape);
            for (a, b) in outline_segments(shape, &view) {
                if let Some((a, b)) = clip(a, b, FRAME) {
                    labels.reserve_ray(a, b);
                }
            }
        }
    }
    out.push_str("</g>\n");
    for (from, to) in &marks.faces_away {
        write_line(
            &mut out,
            &mut labels,
            &view,
            (*from, *to),
            FACES_AWAY,
            " stroke-dasharray=\"2 4\"",
            None,
        );
    }
    for segment in &segments {
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
            &view,
            ends,
            colour,
            dash,
            arrow(segment.stroke),
        );
    }
    write_marks(&mut out, &mut labels, &view, &marks, &blockers);
    write_labels(
        &mut out,
        &mut labels,
        &view,
        scene,
        &outlines,
        &marks,
        &objects,
    );
    legend::write(
        &mut out,
        partial,
        !marks.passed.is_empty(),
        !marks.faces_away.is_empty(),
    );
    out.push_str("</svg>\n");
    out
}

/// The polygons and spheres a ray passed by that no ray hit: drawn, named at their ring.
fn passed_objects(tree: &RayTree, involved: &[usize]) -> Vec<usize> {
    let mut passed: Vec<usize> = (tree.nodes.iter())
        .flat_map(|n| n.near_misses.iter())
        .filter(|n| n.crossing_figure.is_some() || n.closest_approach.is_some())
        .map(|n| n.object_index)
        .filter(|o| !involved.contains(o))
        .collect();
    passed.sort_unstable();
    passed.dedup();
    passed
}

/// The SVG element, its arrowheads (one per ray colour: a marker cannot
/// take its line's colour in SVG 1.1) and the frame's clip path.
fn header() -> String {
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         viewBox=\"0 0 {WIDTH} {HEIGHT}\" font-family=\"Helvetica, Arial, sans-serif\" \
         font-size=\"{FONT_SIZE}\">\n<defs>\n"
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
    view: &View,
    (from, to): (DVec2, DVec2),
    colour: &str,
    dash: &str,
    arrow: Option<&str>,
) {
    let Some((a, b)) = clip(view.map(from), view.map(to), FRAME) else {
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
fn framed(view: &View, p: DVec2) -> Option<DVec2> {
    let at = view.map(p);
    labels::contains(FRAME, (at, at)).then_some(at)
}

/// The blockers' ×, the hits' dots, the passed-by rings, the eye and the
/// lights, each reserved so no label covers it.
fn write_marks(
    out: &mut String,
    labels: &mut Labels,
    view: &View,
    marks: &Marks,
    blockers: &[BlockerMark],
) {
    for (p, b) in blockers
        .iter()
        .filter_map(|b| Some((framed(view, b.at)?, b)))
    {
        let colour = stroke_colour(b.stroke);
        labels.reserve(p, 5.0);
        let _ = writeln!(
            out,
            "<path d=\"M{:.1} {:.1}l8 8m0 -8l-8 8\" stroke=\"{colour}\" stroke-width=\"2.5\"/>",
            p.x - 4.0,
            p.y - 4.0
        );
    }
    for p in marks.hits.iter().filter_map(|h| framed(view, h.1)) {
        circle(out, labels, p, 3.0, "fill=\"black\"");
    }
    for p in marks.passed.iter().filter_map(|m| framed(view, m.2)) {
        let ring =
            format!("class=\"passed-by\" fill=\"none\" stroke=\"{PASSED}\" stroke-width=\"2\"");
        circle(out, labels, p, 6.0, &ring);
    }
    if let Some(e) = framed(view, marks.eye) {
        circle(out, labels, e, 5.0, "fill=\"black\"");
    }
    for p in marks.lights.iter().filter_map(|l| framed(view, l.1)) {
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

/// The names, once every mark and ray is down: the eye's, the lights', the
/// objects' and the passed-by rings'; none for what lies off the frame.
fn write_labels(
    out: &mut String,
    labels: &mut Labels,
    view: &View,
    scene: &Scene,
    outlines: &[(usize, Vec<Outline>)],
    marks: &Marks,
    involved: &[usize],
) {
    if let Some(e) = framed(view, marks.eye) {
        labels.place(out, e, "eye", "fill=\"black\"");
    }
    for (name, at) in &marks.lights {
        if let Some(p) = framed(view, *at) {
            labels.place(out, p, name, "fill=\"#886600\"");
        }
    }
    for (object, shapes) in outlines.iter().filter(|o| involved.contains(&o.0)) {
        // A plane is named where a ray hits it, if one does in the frame.
        let hit = (marks.hits.iter())
            .filter(|h| h.0 == *object)
            .find_map(|h| framed(view, h.1));
        let anchor = shapes.first().and_then(|s| label_anchor(s, view, hit));
        if let Some(at) = anchor.filter(|a| labels::contains(FRAME, (*a, *a))) {
            let name = &scene.objects[*object].name;
            labels.place(out, at, name, "fill=\"#444444\"");
        }
    }
    for (object, name, at) in &marks.passed {
        // An object named at its outline already: "passed by" alone.
        let text = if involved.contains(object) {
            "passed by".to_string()
        } else {
            format!("{name}: passed by")
        };
        if let Some(p) = framed(view, *at) {
            labels.place(out, p, &text, &format!("fill=\"{PASSED}\""));
        }
    }
}
