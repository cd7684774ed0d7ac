//! `raystep diagram`: a pixel's ray diagram as an SVG figure for a slide,
//! the same projection the debugger's diagram pane draws (objects cut by the
//! plane, the eye, the lights, every ray coloured by kind, blocked shadow
//! rays marked where they are blocked), with labels that never overlap and a
//! legend.

pub mod crossing;
mod labels;

use std::fmt::Write;

use glam::DVec2;

use self::labels::Labels;
use crate::diagram::{
    DiagramPlane, Outline, Progress, Projection, Stroke, involved_objects, outline, ray_segments,
};
use crate::record::{RayTree, light_label};
use crate::scene::Scene;

/// The figure's size in SVG units (pixels), and its margin.
const WIDTH: f64 = 800.0;
const HEIGHT: f64 = 600.0;
const MARGIN: f64 = 40.0;
/// The legend's band at the bottom.
const LEGEND: f64 = 30.0;
const FONT_SIZE: f64 = 13.0;

fn stroke_colour(stroke: Stroke) -> &'static str {
    match stroke {
        Stroke::Primary => "#0077bb",
        Stroke::Reflected => "#cc3399",
        Stroke::Transmitted => "#33bbee",
        Stroke::ShadowLit => "#ddaa33",
        Stroke::ShadowBlocked => "#cc3311",
        Stroke::Normal => "#009988",
        Stroke::Later | Stroke::Current => "#777777",
    }
}

/// The whole figure of `tree` (recorded in `scene`) on `plane`.
pub fn svg(scene: &Scene, tree: &RayTree, plane: DiagramPlane) -> String {
    let projection = Projection::new(plane, scene, tree);
    // Every event reached: each ray in its own kind's colour.
    let (segments, blockers) = ray_segments(tree, scene, &projection, Progress::done(tree));
    let objects = involved_objects(tree);
    let outlines: Vec<(usize, Vec<Outline>)> = objects
        .iter()
        .map(|&o| (o, outline(&scene.objects[o].shape, &projection)))
        .collect();
    let eye = projection.project(tree.root().origin);
    let lights: Vec<(String, DVec2)> = scene
        .lights
        .iter()
        .map(|l| (l.name.clone(), projection.project(l.position)))
        .collect();
    let mut points: Vec<DVec2> = segments.iter().flat_map(|s| [s.from, s.to]).collect();
    points.push(eye);
    points.extend(lights.iter().map(|l| l.1));
    for (_, shapes) in &outlines {
        points.extend(shapes.iter().flat_map(Outline::points));
    }
    let view = View::fit(&points);

    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         viewBox=\"0 0 {WIDTH} {HEIGHT}\" font-family=\"Helvetica, Arial, sans-serif\" \
         font-size=\"{FONT_SIZE}\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    let _ = writeln!(
        out,
        "<text x=\"{MARGIN}\" y=\"24\" font-size=\"15\">Pixel ({}, {}), {} (in the camera's frame)</text>",
        tree.pixel.0,
        tree.pixel.1,
        plane.name()
    );
    let mut labels = Labels::new(FONT_SIZE, MARGIN);
    for (object, shapes) in &outlines {
        for shape in shapes {
            write_outline(&mut out, &view, shape);
        }
        if let Some(at) = shapes.first().and_then(|s| label_anchor(s, &view)) {
            labels.place(
                &mut out,
                at,
                &scene.objects[*object].name,
                "fill=\"#444444\"",
            );
        }
    }
    for segment in &segments {
        let (a, b) = (view.map(segment.from), view.map(segment.to));
        let dash = match segment.stroke {
            Stroke::ShadowLit | Stroke::ShadowBlocked => " stroke-dasharray=\"6 4\"",
            _ => "",
        };
        let _ = writeln!(
            out,
            "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{}\" stroke-width=\"2\"{dash}/>",
            a.x,
            a.y,
            b.x,
            b.y,
            stroke_colour(segment.stroke)
        );
    }
    for blocker in &blockers {
        let p = view.map(*blocker);
        let colour = stroke_colour(Stroke::ShadowBlocked);
        let _ = writeln!(
            out,
            "<path d=\"M{:.1} {:.1}l8 8m0 -8l-8 8\" stroke=\"{colour}\" stroke-width=\"2.5\"/>",
            p.x - 4.0,
            p.y - 4.0
        );
    }
    let e = view.map(eye);
    let _ = writeln!(
        out,
        "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"5\" fill=\"black\"/>",
        e.x, e.y
    );
    labels.place(&mut out, e, "eye", "fill=\"black\"");
    for (name, at) in &lights {
        let p = view.map(*at);
        let _ = writeln!(
            out,
            "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"7\" fill=\"#ffdd44\" stroke=\"#aa8800\"/>",
            p.x, p.y
        );
        labels.place(&mut out, p, &light_label(name), "fill=\"#886600\"");
    }
    write_legend(&mut out);
    out.push_str("</svg>\n");
    out
}

/// The mapping from the plane to the figure: uniform scale, y up.
struct View {
    centre: DVec2,
    scale: f64,
}

impl View {
    fn fit(points: &[DVec2]) -> View {
        let finite: Vec<DVec2> = points.iter().copied().filter(|p| p.is_finite()).collect();
        let min = finite.iter().fold(DVec2::INFINITY, |a, &p| a.min(p));
        let max = finite.iter().fold(DVec2::NEG_INFINITY, |a, &p| a.max(p));
        let (min, max) = if finite.is_empty() {
            (DVec2::splat(-1.0), DVec2::splat(1.0))
        } else {
            (min, max)
        };
        let size = (max - min).max(DVec2::splat(1e-3));
        let room = DVec2::new(WIDTH - 2.0 * MARGIN, HEIGHT - 2.0 * MARGIN - LEGEND - 20.0);
        View {
            centre: (min + max) / 2.0,
            scale: (room.x / size.x).min(room.y / size.y),
        }
    }

    fn map(&self, p: DVec2) -> DVec2 {
        let middle = DVec2::new(WIDTH / 2.0, (HEIGHT - LEGEND + 20.0) / 2.0);
        let v = (p - self.centre) * self.scale;
        DVec2::new(middle.x + v.x, middle.y - v.y)
    }
}

fn write_outline(out: &mut String, view: &View, outline: &Outline) {
    let style = "fill=\"none\" stroke=\"#999999\" stroke-width=\"1.5\"";
    match outline {
        Outline::Circle { center, radius } => {
            let c = view.map(*center);
            let _ = writeln!(
                out,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"{:.1}\" {style}/>",
                c.x,
                c.y,
                radius * view.scale
            );
        }
        Outline::Polyline(points) => {
            let list: Vec<String> = points
                .iter()
                .map(|&p| view.map(p))
                .map(|p| format!("{:.1},{:.1}", p.x, p.y))
                .collect();
            let _ = writeln!(out, "<polyline points=\"{}\" {style}/>", list.join(" "));
        }
        Outline::Line { normal, c } => {
            // a·x + c = 0, drawn across the figure: the point nearest the
            // centre, then far both ways along the line.
            let n = *normal / normal.length_squared();
            let foot = view.centre - n * (normal.dot(view.centre) + c);
            let along = normal.perp().normalize() * (WIDTH + HEIGHT) / view.scale;
            let (a, b) = (view.map(foot - along), view.map(foot + along));
            let _ = writeln!(
                out,
                "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" {style}/>",
                a.x, a.y, b.x, b.y
            );
        }
    }
}

/// Where an object's name goes: beside its outline.
fn label_anchor(outline: &Outline, view: &View) -> Option<DVec2> {
    match outline {
        Outline::Circle { center, radius } => {
            Some(view.map(*center + DVec2::new(radius * 0.7, radius * 0.7)))
        }
        Outline::Polyline(points) => {
            let sum = points.iter().fold(DVec2::ZERO, |a, &p| a + p);
            (!points.is_empty()).then(|| view.map(sum / points.len() as f64))
        }
        Outline::Line { .. } => None,
    }
}

fn write_legend(out: &mut String) {
    let y = HEIGHT - LEGEND / 2.0;
    let items = [
        ("primary", Stroke::Primary, false),
        ("reflected", Stroke::Reflected, false),
        ("transmitted", Stroke::Transmitted, false),
        ("shadow ray, lit", Stroke::ShadowLit, true),
        (
            "shadow ray, blocked (× at the blocker)",
            Stroke::ShadowBlocked,
            true,
        ),
        ("normal N", Stroke::Normal, false),
    ];
    let mut x = MARGIN;
    for (name, stroke, dashed) in items {
        let dash = if dashed {
            " stroke-dasharray=\"6 4\""
        } else {
            ""
        };
        let _ = writeln!(
            out,
            "<line x1=\"{x:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"{}\" stroke-width=\"2\"{dash}/>",
            x + 20.0,
            stroke_colour(stroke)
        );
        let _ = writeln!(
            out,
            "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"11\">{name}</text>",
            x + 24.0,
            y + 4.0
        );
        x += 24.0 + name.chars().count() as f64 * 6.2 + 14.0;
    }
}
